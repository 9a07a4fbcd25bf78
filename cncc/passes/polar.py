"""``polar``: retire the polar-coordinate record of the frames.

The front end resolves G16 radius/angle words to Cartesian program coordinates
(incremental polar words and R-arcs between polar points need the current point,
which only the interpreter knows; see ``docs/frames.md``).  The frame keeps a
:class:`~cncc.ir.frame.Polar` record so emitters can tell; this pass, first of the
transform passes, removes it so that frames end as the identity.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from dataclasses import dataclass, replace
from typing import ClassVar

from cncc.ir import Command, Frame
from cncc.ir.batch import Item, MoveBatch, expand
from cncc.passes import Pass, PassContext, register


@register
@dataclass(frozen=True, kw_only=True)
class PolarPass(Pass):
    """Drop ``Frame.polar`` (positions are already Cartesian)."""

    name: ClassVar[str] = "polar"

    def run(self, cmds: Iterable[Command], ctx: PassContext) -> Iterator[Command]:
        return expand(self.run_items(cmds, ctx))

    def run_items(self, items: Iterable[Item], ctx: PassContext) -> Iterator[Item]:
        cache: dict[int, tuple[Frame, Frame]] = {}
        for c in items:
            f = c.frame
            if f.polar is None:
                yield c
                continue
            if isinstance(c, MoveBatch):  # the front end makes batches outside G16 only; should one come
                yield from self.run(c.commands(), ctx)
                continue
            entry = cache.get(id(f))
            if entry is None or entry[0] is not f:
                entry = cache[id(f)] = (f, replace(f, polar=None))
            yield replace(c, frame=entry[1])
