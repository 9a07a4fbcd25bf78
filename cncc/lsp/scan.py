"""A lexical view of a program for editor features: words, labels, calls, variables.

Editor features need to know what is under the cursor and where labels and calls
are, also on lines the compiler rejects.  This scanner reads one line at a time,
skips the dialect's comments, and yields the address words (letter + number),
the dialect's keywords (``Dialect.lexicon``: ``GOTO``, ``WHILE``, LinuxCNC's
``sub``/``call`` ...), variables (``#100``),
LinuxCNC named parameters (``#<depth>``) and named O-words (``o<square>``) with
their offsets.  It
never fails; anything it does not recognise is skipped.
"""

from __future__ import annotations

import functools
import re
from collections.abc import Iterator
from dataclasses import dataclass

from cncc.dialects import Dialect, code_tenths


@functools.cache
def token_re(spellings: tuple[tuple[str, str], ...]) -> tuple[re.Pattern[str], dict[str, str]]:
    """The scanner's token pattern for a dialect's keyword ``spellings`` (spelling, keyword), and
    the map spelling -> keyword (``Dialect.lexicon.spellings``: ``WH`` is ``WHILE`` on a Fanuc)."""
    full = dict(spellings)
    words = "|".join(re.escape(k) for k in sorted(full, key=lambda k: (-len(k), k))) or "(?!)"
    pattern = re.compile(
        r"(?P<var>#\s*(?P<varnum>\d+))"
        r"|(?P<named>#[ \t]*<(?P<pname_>[^>]*)>)"
        r"|(?P<oname>[Oo][ \t]*<(?P<oname_>[^>]*)>)"
        rf"|(?P<kw>(?i:{words}))(?![A-Za-z])"
        r"|(?P<bare>\d+\.?\d*)"
        r"|(?P<pname>[Pp])(?P<name>[A-Za-z_][\w/]*)"
        r"|(?P<letter>[A-Za-z])[ \t]*(?P<num>[-+]?[ \t]*(?:\d+\.?\d*|\.\d+))?"
    )
    return pattern, full


@dataclass(frozen=True, slots=True)
class Token:
    kind: str  # "word", "keyword", "var", "named", "oname", "number" (after a keyword: GOTO 5, DO 1),
    # "signal" (the I/O signal after SZGH's WAT/OUT: X12)
    text: str  # letter (word), keyword upper-cased, variable number (var), name (named: ``#<name>``,
    # oname: LinuxCNC ``o<name>``) in LinuxCNC's form: blanks removed, lower case
    value: str  # number text of a word ("" when the letter has no value); keyword: ""
    start: int  # absolute offsets in the document
    end: int

    @property
    def number(self) -> float | None:
        try:
            return float(self.value.replace(" ", "").replace("\t", ""))
        except ValueError:
            return None

    @property
    def tenths(self) -> int | None:
        """G/M code number in tenths (``G59.1`` -> 591), None when not a number."""
        v = self.value.strip().lstrip("+")
        if not v or not (v[0].isdigit() or v[0] == "."):
            return None
        try:
            return code_tenths(v)
        except ValueError:
            return None


@dataclass(frozen=True, slots=True)
class Comments:
    """What the scanner needs of a dialect: its comment forms, its keywords with their spellings
    (``Dialect.lexicon``), the marks read as ``O`` at the start of a line (``:1000`` on an ISO
    tape) and the prefix of lines that are controller commands, not G-code (grbl's ``$H``)."""

    paren: bool
    slash: bool
    semi: bool
    spellings: tuple[tuple[str, str], ...] = ()
    program_marks: str = ""
    command_prefix: str = ""
    signal_statements: frozenset[str] = frozenset()  # WAT+X12: X12 is a signal, not an X word

    @property
    def keywords(self) -> frozenset[str]:
        return frozenset(word for _, word in self.spellings)

    @staticmethod
    def of(dialect: Dialect) -> Comments:
        return dialect.derived("lsp.scan.comments", _comments_of)


def _comments_of(dialect: Dialect) -> Comments:
    kinds = set(dialect.comments)
    marks = "".join(str(m) for m in dialect.raw.get("program_number_marks", []) if len(str(m)) == 1)
    return Comments("paren" in kinds, "slash" in kinds, "semi" in kinds and dialect.block_end != ";",
                    tuple(sorted(dialect.lexicon.spellings.items())), marks,
                    str(dialect.raw.get("system_command_prefix", "")), frozenset(dialect.lexicon.signal_statements))


def code_part(line: str, comments: Comments) -> list[tuple[int, int]]:
    """The (start, end) pieces of ``line`` that are outside comments."""
    if comments.command_prefix and line.lstrip().startswith(comments.command_prefix):
        return []  # a controller command line: the parser keeps it as a comment
    pieces: list[tuple[int, int]] = []
    i = 0
    start = 0
    n = len(line)
    while i < n:
        ch = line[i]
        if ch == "(" and comments.paren:
            pieces.append((start, i))
            close = line.find(")", i + 1)
            if close < 0:
                return pieces
            i = start = close + 1
            continue
        if (ch == "/" and comments.slash and line.startswith("//", i)) or (ch == ";" and comments.semi):
            pieces.append((start, i))
            return pieces
        i += 1
    pieces.append((start, n))
    return pieces


def tokens(line: str, base: int, comments: Comments) -> Iterator[Token]:
    """Tokens of one line (``base`` is the line's offset in the document)."""
    pattern, full = token_re(comments.spellings)
    first = line.lstrip()[:1]
    if first and first in comments.program_marks:
        lead = len(line) - len(line.lstrip())
        line = line[:lead] + "O" + line[lead + 1:]  # ':1000' is O1000 (one character for one)
    signal = False
    for lo, hi in code_part(line, comments):
        for m in pattern.finditer(line, lo, hi):
            if signal and m.group("letter"):
                signal = False
                yield Token("signal", m.group(0).replace(" ", "").upper(), "", base + m.start(), base + m.end())
                continue
            signal = bool(m.group("kw")) and full.get(m.group("kw").upper(), "") in comments.signal_statements
            if m.group("var"):
                yield Token("var", m.group("varnum"), "", base + m.start(), base + m.end())
            elif m.group("named"):
                yield Token("named", _name(m.group("pname_")), "", base + m.start(), base + m.end())
            elif m.group("oname"):
                yield Token("oname", _name(m.group("oname_")), "", base + m.start(), base + m.end())
            elif m.group("kw"):
                yield Token("keyword", full.get(m.group("kw").upper(), m.group("kw").upper()), "",
                            base + m.start(), base + m.end())
            elif m.group("bare"):
                yield Token("number", "", m.group("bare"), base + m.start(), base + m.end())
            elif m.group("pname"):
                yield Token("word", "P", m.group("name"), base + m.start(), base + m.end())
            else:
                value = m.group("num") or ""
                yield Token("word", m.group("letter").upper(), value.strip(), base + m.start(), base + m.end())


def _name(inner: str) -> str:
    """LinuxCNC ignores blanks and case in ``#<names>`` and ``o<names>``."""
    return "".join(inner.split()).lower()


def token_at(line: str, base: int, offset: int, comments: Comments) -> Token | None:
    """The token that contains ``offset`` (or ends just before it)."""
    best = None
    for tok in tokens(line, base, comments):
        if tok.start <= offset < tok.end:
            return tok
        if tok.end == offset:
            best = tok
    return best


def in_comment(line: str, col: int, comments: Comments) -> bool:
    return not any(lo <= col <= hi for lo, hi in code_part(line, comments))
