"""``relink``: each motion starts where the previous one ended.

This is all the frame passes (polar, scaling, mirror, rotation, cutter compensation) do
to commands whose frames transform nothing: a cycle's expanded moves and a change of
work offset leave a motion's ``start`` in other coordinates than the previous end.
Positions are compared in program + offset coordinates.  The language server's light
pipeline (:func:`cncc.pipeline.builder.light_passes`) runs it instead of the frame
passes until the first frame that needs them.

``memory`` (an object with a ``last`` attribute: the language server's incremental
memory) gives the position to start from and is kept up to date, so a re-run of a
program's tail links to the head that was not re-run.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from typing import ClassVar, Protocol

from cncc.ir import Arc, Command, Linear, Rapid, with_ends
from cncc.passes import Pass, PassContext, register


class LastPosition(Protocol):
    last: tuple[float, ...] | None


@register
@dataclass(frozen=True, kw_only=True)
class Relink(Pass):
    """Motions start where the previous one ended."""

    name: ClassVar[str] = "relink"
    memory: LastPosition | None = field(default=None, compare=False, repr=False)

    def run(self, cmds: Iterable[Command], ctx: PassContext) -> Iterator[Command]:
        memory = self.memory
        last: tuple[float, ...] | None = memory.last if memory is not None else None
        for c in cmds:
            if not isinstance(c, Rapid | Linear | Arc):
                yield c
                continue
            f = c.frame
            if last is not None:
                o = f.total_offset_mm
                start = (last[0] - o[0], last[1] - o[1], last[2] - o[2], last[3] - o[3], last[4] - o[4],
                         last[5] - o[5])
                if start != c.start:
                    c = with_ends(c, f, start, c.end)
            o = f.total_offset_mm
            e = c.end
            last = (e[0] + o[0], e[1] + o[1], e[2] + o[2], e[3] + o[3], e[4] + o[4], e[5] + o[5])
            if memory is not None:
                memory.last = last
            yield c
