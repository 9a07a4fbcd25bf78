"""``tool-length``: apply G43/G44 tool length offsets to positions.

Consumes commands whose frames carry ``tool_length_mm`` on ``tool_length_axis`` (Z,
or the plane normal for SZGH type B); produces them with the offset added to that
axis and the frame's length offset cleared.  A block that only changes the offset
(``G43 H1`` without Z, ``G49``) moves nothing by itself: the next move starts where
the tool is and ends at the newly offset point, as the controllers do.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from dataclasses import dataclass, replace
from typing import ClassVar

from cncc.ir import Arc, Command, Frame, Linear, Rapid, Vec6
from cncc.ir.frame import add_offsets
from cncc.passes import Pass, PassContext, register


def _shift(p: Vec6, axis: int, d: float) -> Vec6:
    if d == 0.0:
        return p
    q = list(p)
    q[axis] += d
    return (q[0], q[1], q[2], q[3], q[4], q[5])


@register
@dataclass(frozen=True, kw_only=True)
class ToolLength(Pass):
    """Tool length compensation on the frame's length axis."""

    name: ClassVar[str] = "tool-length"

    def run(self, cmds: Iterable[Command], ctx: PassContext) -> Iterator[Command]:
        last: Vec6 | None = None  # actual end of the previous motion (program + offsets)
        cache: dict[int, tuple[Frame, Frame]] = {}
        for c in cmds:
            f = c.frame
            entry = cache.get(id(f))
            if entry is None or entry[0] is not f:
                # the H number stays (like cutter-comp's D): reports show which offsets a tool used
                nf = f if f.tool_length_mm == 0.0 else replace(f, tool_length_mm=0.0)
                entry = cache[id(f)] = (f, nf)
            nf = entry[1]
            if not isinstance(c, Rapid | Linear | Arc):
                yield c if nf is f else replace(c, frame=nf)
                continue
            axis, d = f.tool_length_axis, f.tool_length_mm
            end = _shift(c.end, axis, d)
            start = c.start
            if last is not None:
                o = f.total_offset_mm
                start = (last[0] - o[0], last[1] - o[1], last[2] - o[2], last[3] - o[3], last[4] - o[4],
                         last[5] - o[5])
            last = add_offsets(end, f)
            if nf is f and start == c.start and end == c.end:
                yield c
            elif isinstance(c, Rapid):
                yield Rapid(c.span, nf, start, end, c.motion, c.origin)
            elif isinstance(c, Linear):
                yield Linear(c.span, nf, start, end, c.feed_mm_min, c.motion, c.origin)
            else:
                yield Arc(c.span, nf, start, end, _shift(c.center, axis, d), c.turns, c.plane, c.feed_mm_min,
                          c.motion, c.origin)
