"""Labels, programs, calls and tool changes of a document, for go-to and outlines.

Consumes the document text and its dialect; produces an :class:`Outline`: the
``O`` program headers, the ``N`` labels (the first word of a block), the calls
(``M98 P``/``H``, ``G65 P``, ``G66 P``, ``M99 P``, ``GOTO``) and the tool changes,
all with offsets.  Definition and references are lookups in it.  Program keys are
normalised so that ``O0010``, ``O10`` and ``P10`` meet; named programs (SZGH
``M98 PKG11``) are keyed by their upper-cased name.

LinuxCNC subroutines (``o<square> sub`` ... ``o<square> endsub``, ``o100 sub``) are
``"sub"`` references keyed by the name as LinuxCNC reads it (blanks removed, lower
case) or the number; ``o<square> call`` is a call of one.  The other O-words
(``o101 if``, ``o102 while`` ...) are flow labels, not programs.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass, field

from cncc.dialects import Dialect
from cncc.dialects.lexicon import parse_lexicon
from cncc.lsp.positions import LineIndex
from cncc.lsp.scan import Comments, Token, tokens

CALL_OPS = {"subprogram_call", "macro_call", "modal_call", "subprogram_return"}
O_KEYWORDS = frozenset(parse_lexicon("rs274ngc", {}).statements)  # the words after a LinuxCNC O-word


@dataclass(frozen=True, slots=True)
class Ref:
    kind: str  # "program", "label" or "sub" (a LinuxCNC subroutine)
    key: str  # normalised program key or label number
    start: int
    end: int
    what: str  # e.g. "M98 P", "GOTO", "O", "N"


@dataclass(slots=True)
class Outline:
    programs: list[Ref] = field(default_factory=list)  # O headers
    labels: list[Ref] = field(default_factory=list)  # N at the start of a block
    calls: list[Ref] = field(default_factory=list)
    tools: list[tuple[int, int, int, str]] = field(default_factory=list)  # (start, end, tool, text)
    program_ends: list[int] = field(default_factory=list)  # offsets of M02/M30
    subs: list[Ref] = field(default_factory=list)  # LinuxCNC ``o<name> sub``
    sub_ends: dict[str, int] = field(default_factory=dict)  # key -> offset just past its endsub line

    def at(self, offset: int) -> Ref | None:
        for ref in (*self.calls, *self.labels, *self.programs, *self.subs):
            if ref.start <= offset <= ref.end:
                return ref
        return None

    def definitions(self, ref: Ref) -> list[Ref]:
        pool = {"program": self.programs, "label": self.labels, "sub": self.subs}[ref.kind]
        return [r for r in pool if r.key == ref.key]

    def definitions_of(self, kind: str, key: str) -> list[Ref]:
        return self.definitions(Ref(kind, key, 0, 0, ""))

    def references(self, ref: Ref, include_definition: bool) -> list[Ref]:
        out = [r for r in self.calls if r.kind == ref.kind and r.key == ref.key]
        if include_definition:
            out = self.definitions(ref) + out
        return out


def program_key(value: str) -> str:
    """``"0010"`` -> ``"10"``; ``"kg11"`` -> ``"KG11"``; ``"O0010"`` -> ``"10"``."""
    v = value.strip()
    if v[:1] in ("O", "o") and v[1:].isdigit():
        v = v[1:]
    if v.isdigit():
        return str(int(v))
    try:
        f = float(v)
    except ValueError:
        return v.upper()
    return str(int(f)) if f == int(f) else v


def outline(text: str, dialect: Dialect, check: Callable[[], None] | None = None) -> Outline:
    index = LineIndex(text)
    comments = Comments.of(dialect)
    codes = {(c.letter, c.tenths): c.op for c in dialect.codes.values()}
    out = Outline()
    for line in range(index.line_count):
        if check is not None and line % 2048 == 0:
            check()
        base = index.line_start(line)
        toks = list(tokens(index.line_text(line), base, comments))
        if toks and not _oword(out, toks, index.line_end(line)):
            _line(out, toks, codes)
    return out


_SUB_LINE_RE = re.compile(r"^[ \t]*[Oo][ \t]*(<[^>\n]*>|\d+)[ \t]*(sub|endsub|call)\b", re.IGNORECASE | re.MULTILINE)


def subroutines(text: str) -> Outline:
    """Only the LinuxCNC subroutines and their calls (a regex scan: for hover on big files)."""
    out = Outline()
    for m in _SUB_LINE_RE.finditer(text):
        raw = m.group(1)
        key = "".join(raw[1:-1].split()).lower() if raw.startswith("<") else str(int(raw))
        keyword = m.group(2).upper()
        start = m.start() + m.group(0).lower().index("o")  # the O of the O-word
        ref = Ref("sub", key, start, m.end(1), keyword.lower())
        if keyword == "SUB":
            out.subs.append(ref)
        elif keyword == "CALL":
            out.calls.append(ref)
        else:
            end = text.find("\n", m.end())
            out.sub_ends[key] = len(text) if end < 0 else end
    return out


def oword_key(toks: list[Token]) -> tuple[str, str] | None:
    """(key, keyword) of a LinuxCNC O-word line (``o<square> call``, ``o100 sub``), else None."""
    first = toks[0]
    if len(toks) < 2 or toks[1].kind != "keyword" or toks[1].text not in O_KEYWORDS:
        return None
    if first.kind == "oname":
        return first.text, toks[1].text
    if first.kind == "word" and first.text == "O" and first.value.isdigit():
        return str(int(first.value)), toks[1].text
    return None


def _oword(out: Outline, toks: list[Token], line_end: int) -> bool:
    found = oword_key(toks)
    if found is None:
        return False
    key, keyword = found
    first = toks[0]
    if keyword == "SUB":
        out.subs.append(Ref("sub", key, first.start, first.end, "sub"))
    elif keyword == "ENDSUB":
        out.sub_ends[key] = line_end
    elif keyword == "CALL":
        out.calls.append(Ref("sub", key, first.start, first.end, "call"))
    return True


def _line(out: Outline, toks: list[Token], codes: dict[tuple[str, int], str]) -> None:
    first = toks[0]
    if first.kind == "word" and first.text == "O" and first.value:
        out.programs.append(Ref("program", program_key(first.value), first.start, first.end, "O"))
    if first.kind == "word" and first.text == "N" and first.value:
        out.labels.append(Ref("label", program_key(first.value), first.start, first.end, "N"))
    ops = []
    for t in toks:
        if t.kind == "word" and t.text in "GM" and t.tenths is not None:
            ops.append((t, codes.get((t.text, t.tenths), "")))
    call_ops = [(t, op) for t, op in ops if op in CALL_OPS]
    words = {t.text: t for t in toks if t.kind == "word" and t.value}
    for code_tok, op in call_ops:
        name = f"{code_tok.text}{code_tok.value}"
        p, h = words.get("P"), words.get("H")
        if op == "subprogram_return":
            if p is not None:
                out.calls.append(Ref("label", program_key(p.value), p.start, p.end, f"{name} P"))
            continue
        if op == "subprogram_call" and h is not None:
            out.calls.append(Ref("label", program_key(h.value), h.start, h.end, f"{name} H"))
        if p is not None:
            out.calls.append(Ref("program", program_key(p.value), p.start, p.end, f"{name} P"))
    for i, t in enumerate(toks):
        if t.kind == "keyword" and t.text == "GOTO" and i + 1 < len(toks) and toks[i + 1].kind == "number":
            target = toks[i + 1]
            out.calls.append(Ref("label", program_key(target.value), target.start, target.end, "GOTO"))
    tool = words.get("T")
    if tool is not None:
        changes = any(op == "tool_change" for _, op in ops)
        label = f"T{tool.value}" + (" tool change" if changes else " tool select")
        try:
            number = int(float(tool.value))
        except ValueError:
            number = -1
        out.tools.append((toks[0].start, toks[-1].end, number, label))
    if any(op in ("program_end", "program_end_rewind") for _, op in ops):
        out.program_ends.append(toks[0].start)
