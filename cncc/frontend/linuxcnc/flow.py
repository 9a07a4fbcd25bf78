"""The O-word structure of one file: subroutines, branches and loops, matched by label.

LinuxCNC pairs ``O<label> if`` with the ``elseif``/``else``/``endif`` lines of the same
label, ``while`` with ``endwhile`` (or ``do`` with its closing ``while``), ``repeat``
with ``endrepeat`` and ``sub`` with ``endsub``.  :meth:`FlowIndex.build` matches them
once before the program runs, reporting what does not pair up (``E0350``).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink
from cncc.frontend.linuxcnc.builder import OWord, oword_of
from cncc.frontend.syntax import Block
from cncc.source import SourceFile, Span


@dataclass(slots=True)
class Loop:
    label: str
    kind: str  # "while", "do", "repeat"
    head: int  # the while / do / repeat line
    end: int  # endwhile / the closing while / endrepeat


@dataclass(slots=True)
class FlowIndex:
    blocks: list[Block]
    src: SourceFile
    owords: dict[int, OWord] = field(default_factory=dict)
    subs: dict[str, tuple[int, int]] = field(default_factory=dict)  # label -> (sub line, endsub line)
    next_branch: dict[int, int] = field(default_factory=dict)  # if/elseif/else -> next branch line of the label
    endif: dict[int, int] = field(default_factory=dict)  # if/elseif/else -> endif line
    loops: list[Loop] = field(default_factory=list)
    loop_at: dict[int, Loop] = field(default_factory=dict)  # head and end lines -> loop
    programs: dict[str, int] = field(default_factory=dict)  # bare O<n> (M98 targets) -> line
    repeat_jumps: dict[int, int] = field(default_factory=dict)  # repeat line -> a break/continue of its label inside

    def span(self, b: Block) -> Span:
        return Span(self.src.source_id, b.start, b.end)

    def span_of(self, start: int, end: int) -> Span:
        return Span(self.src.source_id, start, end)

    def enclosing_loop(self, label: str, line: int) -> Loop | None:
        best = None
        for lp in self.loops:
            if lp.label == label and lp.head <= line <= lp.end and (best is None or lp.head > best.head):
                best = lp
        return best

    @staticmethod
    def build(blocks: list[Block], src: SourceFile, sink: DiagnosticSink) -> FlowIndex | None:
        fx = FlowIndex(blocks, src)
        ok = _Matcher(fx, sink).run()
        return fx if ok else None


class _Matcher:
    def __init__(self, fx: FlowIndex, sink: DiagnosticSink) -> None:
        self.fx, self.sink, self.ok = fx, sink, True
        self.open: list[tuple[str, str, int]] = []  # (label, keyword, line)
        self.branch_lines: dict[int, list[int]] = {}  # if line -> its branch lines

    def error(self, line: int, message: str, code: str = dg.OWORD_STRUCTURE) -> None:
        self.sink.emit(code, self.fx.span(self.fx.blocks[line]), message)
        self.ok = False

    def _program(self, i: int, label: str) -> None:
        """A Fanuc-style program number ``O100`` (an M98 target up to its M99); the first one counts."""
        if any(k == "sub" for _, k, _ in self.open):
            self.error(i, "Nested subroutine definition")
        self.fx.programs.setdefault(label, i)

    def run(self) -> bool:
        for i, b in enumerate(self.fx.blocks):
            ow = oword_of(b.statements)
            if ow is None:
                if b.words and b.words[0].letter == "O":  # a plain "O100" line (parsed as a word)
                    self._program(i, str(round(b.words[0].value)))
                continue
            self.fx.owords[i] = ow
            if ow.label_expr is None:  # a computed call matches nothing
                self.line(i, ow)
        for label, kw, line in self.open:
            self.error(line, f"o{label} {kw} has no matching end{'sub' if kw == 'sub' else kw}")
        return self.ok

    def _pop(self, i: int, ow: OWord, opener: tuple[str, ...]) -> int | None:
        if self.open and self.open[-1][0] == ow.label and self.open[-1][1] in opener:
            return self.open.pop()[2]
        self.error(i, f"o{ow.label} {ow.keyword} without a matching o{ow.label} {' or '.join(opener)}")
        return None

    def line(self, i: int, ow: OWord) -> None:
        kw, fx = ow.keyword, self.fx
        if kw == "":
            self._program(i, ow.label)
        elif kw in ("endsub", "return") and ow.label in fx.programs and \
                not any(lb == ow.label and k == "sub" for lb, k, _ in self.open):
            self.error(i, f"O{ow.label} ... must end with M99, not o{ow.label} {kw} (it is called by M98)",
                       dg.SUB_STYLE_MIXED)
        elif kw == "sub" and any(k == "sub" for _, k, _ in self.open):
            self.error(i, "Nested subroutine definition")
        elif kw in ("sub", "if", "repeat", "do"):
            self.open.append((ow.label, kw, i))
            if kw == "if":
                self.branch_lines[i] = [i]
        elif kw == "while":
            if self.open and self.open[-1][:2] == (ow.label, "do"):
                head = self.open.pop()[2]
                self._loop(ow.label, "do", head, i)
            else:
                self.open.append((ow.label, "while", i))
        elif kw in ("elseif", "else"):
            if self.open and self.open[-1][:2] == (ow.label, "if"):
                self.branch_lines[self.open[-1][2]].append(i)
            else:
                self.error(i, f"o{ow.label} {kw} without a matching o{ow.label} if")
        elif kw in ("endsub", "endif", "endwhile", "endrepeat"):
            opener = {"endsub": "sub", "endif": "if", "endwhile": "while", "endrepeat": "repeat"}[kw]
            start = self._pop(i, ow, (opener,))
            if start is not None:
                self._close(ow.label, opener, start, i)

    def _close(self, label: str, opener: str, head: int, end: int) -> None:
        fx = self.fx
        if opener == "sub":
            fx.subs[label] = (head, end)
        elif opener == "if":
            lines = [*self.branch_lines.pop(head), end]
            for a, b in itertools.pairwise(lines):
                fx.next_branch[a] = b
                fx.endif[a] = end
        else:
            self._loop(label, opener, head, end)

    def _loop(self, label: str, kind: str, head: int, end: int) -> None:
        lp = Loop(label, kind, head, end)
        if kind == "repeat":  # LinuxCNC 2.9 has break and continue for while and do loops only
            jump = next((k for k in range(head + 1, end) if (ow := self.fx.owords.get(k)) is not None
                         and ow.label == label and ow.keyword in ("break", "continue")), None)
            if jump is not None:
                self.fx.repeat_jumps[head] = jump
        self.fx.loops.append(lp)
        self.fx.loop_at[head] = lp
        self.fx.loop_at[end] = lp
