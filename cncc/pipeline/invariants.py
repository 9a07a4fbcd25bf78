"""IR invariants that ``--verify-each`` checks after every pass (docs/architecture.md, "Pipeline").

* **continuity**: every motion starts where the previous motion ended, compared in
  program + offset coordinates (``add_offsets``), so a change of work offset between
  them is no jump.  A kept canned cycle (``Cycle``: translation keeps it for the
  target) moves the tool itself and restarts the comparison.
* **spans**: every command's span lies inside a file of the source map
  (``0 <= start <= end <= len(text)``), or is ``NO_SPAN``.
* **machine frame**: after ``to-machine`` every frame has no work, local or G92
  offset and no G53 flag; once ``to-machine``, ``tool-length`` and ``cutter-comp``
  have all run, every frame is the identity (``Frame.is_identity``).

:class:`Checker` streams: it looks at each command once, as it passes.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink
from cncc.ir import ZERO6, Arc, Command, Cycle, Linear, Rapid, Vec6
from cncc.ir.frame import Frame, add_offsets
from cncc.source import NO_SPAN, SourceMap, Span

TOLERANCE_MM = 1e-6
"""How far a motion may start from the previous end (mm, per axis) before it is a jump."""

MACHINE_FRAME_PASSES = frozenset({"to-machine", "tool-length", "cutter-comp"})
"""Passes after all of which every frame is the identity."""

_MOTIONS = (Rapid, Linear, Arc)


def _fmt(p: Vec6) -> str:
    return "(" + ", ".join(f"{v:.4f}" for v in p) + ")"


@dataclass(slots=True)
class Checker:
    """The invariants of one pass's output; ``ran``: the passes that ran before it and itself."""

    pass_name: str
    sink: DiagnosticSink
    sources: SourceMap | None
    ran: frozenset[str]
    counts: dict[str, int] = field(default_factory=dict)
    first: dict[str, Span] = field(default_factory=dict)

    def check(self, cmds: Iterable[Command]) -> Iterator[Command]:
        last: Vec6 | None = None
        offsets_gone = "to-machine" in self.ran
        identity = self.ran >= MACHINE_FRAME_PASSES
        frames_ok: dict[int, Frame] = {}  # frames already checked (shared records; held, so ids stay theirs)
        for c in cmds:
            self._span(c)
            if offsets_gone and frames_ok.get(id(c.frame)) is not c.frame and self._frame(c, c.frame, identity):
                frames_ok[id(c.frame)] = c.frame
            if isinstance(c, _MOTIONS):
                start = add_offsets(c.start, c.frame)
                if last is not None and any(abs(a - b) > TOLERANCE_MM for a, b in zip(start, last, strict=True)):
                    self._report("continuity", c.span, f"a {type(c).__name__} starts at {_fmt(start)} but the "
                                 f"previous motion ended at {_fmt(last)}")
                last = add_offsets(c.end, c.frame)
            elif isinstance(c, Cycle):
                last = None
            yield c
        self._summary()

    def _span(self, c: Command) -> None:
        s = c.span
        if s == NO_SPAN or self.sources is None:
            return
        src = self.sources.get(s.source_id)
        if src is None:
            self._report("spans", NO_SPAN, f"a {type(c).__name__} has a span in source {s.source_id}, which the "
                         "source map does not hold")
        elif not 0 <= s.start <= s.end <= len(src.text):
            self._report("spans", NO_SPAN, f"a {type(c).__name__} has the span {s.start}..{s.end}, outside "
                         f"{src.name} (0..{len(src.text)})")

    def _frame(self, c: Command, f: Frame, identity: bool) -> bool:
        if f.machine_coords or f.total_offset_mm != ZERO6 or f.work_offset_mm != ZERO6:
            self._report("frame", c.span, f"a {type(c).__name__} still has a program offset "
                         f"{_fmt(f.total_offset_mm)} after to-machine")
            return False
        if identity and not f.is_identity:
            self._report("frame", c.span, f"a {type(c).__name__} has no identity frame after "
                         f"{', '.join(sorted(MACHINE_FRAME_PASSES))}")
            return False
        return True

    def _report(self, invariant: str, span: Span, message: str) -> None:
        n = self.counts.get(invariant, 0)
        self.counts[invariant] = n + 1
        if n == 0:
            self.first[invariant] = span
            self.sink.emit(dg.IR_INVARIANT, span, f"--verify-each: after pass '{self.pass_name}': {message} "
                                                  f"[{invariant}]")

    def _summary(self) -> None:
        for invariant, n in self.counts.items():
            if n > 1:
                self.sink.emit(dg.IR_INVARIANT, self.first[invariant],
                               f"--verify-each: after pass '{self.pass_name}': {n - 1} more {invariant} "
                               "violations like the first")
