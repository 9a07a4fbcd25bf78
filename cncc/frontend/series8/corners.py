"""G10 inserted radius and chamfer (spec 4.3).

:class:`Stream` sits after the interpreter of a SERIES 8 program.  A line programmed
with G10 is held until the next move is known; then, with u the unit direction into
the corner P and v the one out of it, and delta the angle between them:

* ``R``: the setback is t = R tan(delta/2); the line ends at T1 = P - t u, a tangent
  arc of radius R (CCW on a left turn, CW on a right turn) runs to T2 = P + t v, and
  the next line starts at T2;
* ``L``: the setback is L along each line (it reproduces the manual's numbers); a
  straight chamfer joins P - L u and P + L v.

The inserted element runs at the G10 line's feed and motion mode.  A next move that
is not a line, a setback longer than either line, lines in line or reversing, or a
frame change at the corner are E0257 (A-42); the two lines are then left as they are.
"""

from __future__ import annotations

import math
from collections.abc import Generator, Iterator
from dataclasses import replace

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink
from cncc.ir import Arc, Command, Linear, Origin, OriginKind, Rapid, Vec6
from cncc.source import Span

_EPS = 1e-9


def _along(a: Vec6, b: Vec6, t: float) -> Vec6:
    return (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2]),
            a[3] + t * (b[3] - a[3]), a[4] + t * (b[4] - a[4]), a[5] + t * (b[5] - a[5]))


class Stream:
    """Commands of one SERIES 8 program after the interpreter, with corners inserted."""

    def __init__(self, sink: DiagnosticSink) -> None:
        self.sink = sink
        self.pending: tuple[Linear, str, float, Span] | None = None
        self.held: list[Command] = []

    def push(self, cmds: list[Command], corner: tuple[str, float, Span] | None) -> Iterator[Command]:
        """The commands of one block; ``corner`` is its G10 request (the block's last line)."""
        line = None
        if corner is not None:
            line = next((c for c in reversed(cmds) if isinstance(c, Linear)), None)
            if line is None:
                self.sink.emit(dg.CORNER_INSERT, corner[2], "G10 needs a straight feed move (G01/G21) in its block")
        for c in cmds:
            is_line = c is line
            if self.pending is not None and isinstance(c, Rapid | Linear | Arc):
                c = yield from self._join(c)
            if is_line and corner is not None and isinstance(c, Linear):
                self.pending = (c, corner[0], corner[1], corner[2])
            elif self.pending is not None:
                self.held.append(c)
            else:
                yield c

    def finish(self) -> Iterator[Command]:
        if self.pending is not None:
            self.sink.emit(dg.CORNER_INSERT, self.pending[3], "G10: no line follows to insert the corner into")
            yield self.pending[0]
            yield from self.held
            self.pending, self.held = None, []

    def _join(self, nxt: Rapid | Linear | Arc) -> Generator[Command, None, Rapid | Linear | Arc]:
        """Emit the held line with its corner; return ``nxt`` (its start moved to the corner's end)."""
        assert self.pending is not None
        first, kind, size, span = self.pending
        self.pending = None
        got = self._corner(first, kind, size, span, nxt)
        if got is None:
            yield first
            yield from self.held
            self.held = []
            return nxt
        trimmed, element, new_next = got
        yield trimmed
        yield element
        yield from self.held
        self.held = []
        return new_next

    def _corner(self, first: Linear, kind: str, size: float, span: Span,
                nxt: Rapid | Linear | Arc) -> tuple[Linear, Command, Linear] | None:
        if not isinstance(nxt, Linear) or not nxt.origin.programmed:
            self.sink.emit(dg.CORNER_INSERT, span, "G10: the move after the corner must be a straight feed "
                                                   "move (G01/G21) (spec A-42)")
            return None
        if first.frame != nxt.frame:
            self.sink.emit(dg.CORNER_INSERT, span, "G10: the coordinate frame changes at the corner")
            return None
        p = first.frame.plane
        i, j = p.first, p.second
        ux, uy = first.end[i] - first.start[i], first.end[j] - first.start[j]
        vx, vy = nxt.end[i] - nxt.start[i], nxt.end[j] - nxt.start[j]
        lu, lv = math.hypot(ux, uy), math.hypot(vx, vy)
        if lu < _EPS or lv < _EPS:
            self.sink.emit(dg.CORNER_INSERT, span, "G10: a line at the corner has no length in the plane")
            return None
        ux, uy, vx, vy = ux / lu, uy / lu, vx / lv, vy / lv
        cross = ux * vy - uy * vx
        delta = math.atan2(abs(cross), ux * vx + uy * vy)
        if delta < 1e-7 or math.pi - delta < 1e-7:
            self.sink.emit(dg.CORNER_INSERT, span, "G10: the lines are in line or reverse; there is no corner")
            return None
        setback = size * math.tan(delta / 2.0) if kind == "R" else size
        if setback > lu + 1e-9 or setback > lv + 1e-9:
            self.sink.emit(dg.CORNER_INSERT, span, f"G10 {kind}: the setback {setback:.4f} mm is longer than a line "
                                                   "at the corner (spec A-42)")
            return None
        t1 = _along(first.start, first.end, (lu - setback) / lu)
        t2 = _along(nxt.start, nxt.end, setback / lv)
        trimmed = replace(first, end=t1)
        element: Command
        if kind == "R":
            side = 1.0 if cross > 0 else -1.0
            c = list(t1)
            c[i] = t1[i] - side * size * uy
            c[j] = t1[j] + side * size * ux
            centre = (c[0], c[1], c[2], c[3], c[4], c[5])
            element = Arc(first.span, first.frame, t1, t2, centre, 1 if cross > 0 else -1, p, first.feed_mm_min,
                          first.motion, Origin(OriginKind.CODE, "G10"))
        else:
            element = Linear(first.span, first.frame, t1, t2, first.feed_mm_min, first.motion,
                             Origin(OriginKind.CODE, "G10"))
        return trimmed, element, replace(nxt, start=t2)
