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

from cncc.ir import ZERO6, Arc, Command, Frame, Linear, Rapid, Vec6, with_ends
from cncc.ir.batch import Item, MoveBatch, expand
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
        return expand(self.run_items(cmds, ctx))

    def run_items(self, items: Iterable[Item], ctx: PassContext) -> Iterator[Item]:
        last: Vec6 | None = None  # actual end of the previous motion (program + offsets)
        cache: dict[int, tuple[Frame, Frame]] = {}
        for x in items:
            f = x.frame
            entry = cache.get(id(f))
            if entry is None or entry[0] is not f:
                # the H number stays (like cutter-comp's D): reports show which offsets a tool used
                nf = f if f.tool_length_mm == 0.0 else replace(f, tool_length_mm=0.0)
                entry = cache[id(f)] = (f, nf)
            nf = entry[1]
            if isinstance(x, MoveBatch):
                out = _batch(x, nf, last)
                if out is not None:
                    yield out
                    last = add_offsets(out.last_end, f)
                    continue
                cmds: Iterable[Command] = x.commands()
            else:
                cmds = (x,)
            for c in cmds:
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
                else:
                    yield with_ends(c, nf, start, end, _shift(c.center, axis, d) if isinstance(c, Arc) else None)


def _batch(b: MoveBatch, nf: Frame, last: Vec6 | None) -> MoveBatch | None:
    """The batch with the frame's length offset applied; None when its frame has offsets (a start
    re-derived from the offset end may differ in its last bits there: the per-command path decides)."""
    f = b.frame
    if f.total_offset_mm != ZERO6 or (f.rotation is not None and f.rotation.work):
        return None
    start = b.start0 if last is None else (last[0], last[1], last[2], last[3], last[4], last[5])
    axis, d = f.tool_length_axis, f.tool_length_mm
    if d == 0.0 and nf is f and start == b.start0:
        return b
    end, center = b.end, b.center
    if d != 0.0:
        end, center = end.copy(), center.copy()
        end[:, axis] += d
        center[:, axis] += d
    return b.with_(frame=nf, start0=start, end=end, center=center)
