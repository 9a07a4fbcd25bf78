"""``to-machine``: lower work, local and G92 offsets to machine coordinates.

Consumes commands in the program coordinates of their frames; produces the same
commands in machine coordinates, each pointing to a frame without offsets.  The
tool length and compensation fields are left for ``tool-length`` and
``cutter-comp``; after all three every frame is the identity (``Frame.is_identity``).
The planner, timing and pulse backends read this; the canon trace does not (it
reports offsets as calls of their own).
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from dataclasses import dataclass, replace
from typing import ClassVar

from cncc.ir import ZERO6, Arc, Command, Frame, Linear, Rapid, Vec6, with_ends
from cncc.ir.batch import Item, MoveBatch, expand
from cncc.passes import Pass, PassContext, register


def _add(p: Vec6, o: Vec6) -> Vec6:
    return (p[0] + o[0], p[1] + o[1], p[2] + o[2], p[3] + o[3], p[4] + o[4], p[5] + o[5])


@register
@dataclass(frozen=True, kw_only=True)
class ToMachine(Pass):
    """Offsets to machine coordinates."""

    name: ClassVar[str] = "to-machine"

    def run(self, cmds: Iterable[Command], ctx: PassContext) -> Iterator[Command]:
        return expand(self.run_items(cmds, ctx))

    def run_items(self, items: Iterable[Item], ctx: PassContext) -> Iterator[Item]:
        cache: dict[int, tuple[Frame, Frame]] = {}
        for c in items:
            f = c.frame
            entry = cache.get(id(f))
            if entry is None or entry[0] is not f:
                plain = f.total_offset_mm == ZERO6 and not f.machine_coords and f.work_offset_mm == ZERO6
                nf = f if plain else replace(f, work_offset_mm=ZERO6, local_offset_mm=ZERO6, g92_offset_mm=ZERO6,
                                             machine_coords=False)
                entry = cache[id(f)] = (f, nf)
            nf = entry[1]
            o = f.total_offset_mm
            if isinstance(c, MoveBatch):  # every row and its F word shifted at once
                if nf is f:
                    yield c
                else:
                    yield c.with_(frame=nf, start0=_add(c.start0, o), end=c.end + o, center=c.center + o)
            elif nf is f or not isinstance(c, Rapid | Linear | Arc):
                yield c if nf is f else replace(c, frame=nf)
            else:
                center = _add(c.center, o) if isinstance(c, Arc) else None
                yield with_ends(c, nf, _add(c.start, o), _add(c.end, o), center)
