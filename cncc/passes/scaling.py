"""``scaling``: apply G51 (SZGH G36) scaling to programmed positions.

Consumes commands whose frames may carry a :class:`~cncc.ir.frame.Scaling` record;
produces them scaled about the record's centre (``p' = c + k (p - c)`` per axis),
with the record removed.  Offsets, feeds and tool radii are not scaled.  A negative
factor mirrors, which reverses arcs and the compensation side like G51.1.  Records in
``keep`` are left in the frames (a G-code target runs them itself).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import ClassVar

from cncc.ir import Frame
from cncc.passes import register
from cncc.passes.affine import Affine, AffinePass, flip_side


@register
@dataclass(frozen=True, kw_only=True)
class ScalingPass(AffinePass):
    """Scaling about a centre, per axis."""

    name: ClassVar[str] = "scaling"
    keep: frozenset[object] = frozenset()  # records left in the frames (a G-code target runs them)

    def affine(self, frame: Frame) -> Affine | None:
        s = frame.scaling
        if s is None or s in self.keep:
            return None
        fx, fy, fz = s.factors
        return Affine(s.center_mm, ((fx, 0.0, 0.0), (0.0, fy, 0.0), (0.0, 0.0, fz)))

    def strip(self, frame: Frame, affine: Affine | None) -> Frame:
        if frame.scaling is None or frame.scaling in self.keep:
            return frame
        side = frame.comp_side
        if affine is not None and affine.det2(frame.plane) < 0:
            side = flip_side(side)
        return replace(frame, scaling=None, comp_side=side)
