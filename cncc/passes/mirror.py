"""``mirror``: apply the programmable mirror (G51.1, SZGH G11) to programmed positions.

Consumes commands whose frames may carry a :class:`~cncc.ir.frame.Mirror` record;
produces them reflected about the record's lines (``p' = 2a - p`` on each mirrored
axis), with the record removed.  With one axis of the plane mirrored, arcs reverse
(G02 <-> G03), the cutter-compensation side swaps (G41 <-> G42) and a rotation in
force turns the other way about the mirrored centre: the mirror acts on the rotated
part as a whole, which is what "the rotation direction reverses" means.  Mirroring
both plane axes is a half turn and reverses nothing.  Records in ``keep`` are left in
the frames untouched (a G-code target with G51.1 runs them itself).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import ClassVar

from cncc.ir import Frame
from cncc.ir.frame import Rotation
from cncc.passes import register
from cncc.passes.affine import Affine, AffinePass, flip_side


@register
@dataclass(frozen=True, kw_only=True)
class MirrorPass(AffinePass):
    """Programmable mirror about axis-parallel lines."""

    name: ClassVar[str] = "mirror"
    keep: frozenset[object] = frozenset()  # records left in the frames (a G-code target runs them)

    def affine(self, frame: Frame) -> Affine | None:
        m = frame.mirror
        if m is None or not any(m.axes) or m in self.keep:
            return None
        sx, sy, sz = (-1.0 if flag else 1.0 for flag in m.axes)
        return Affine(m.center_mm, ((sx, 0.0, 0.0), (0.0, sy, 0.0), (0.0, 0.0, sz)))

    def strip(self, frame: Frame, affine: Affine | None) -> Frame:
        if frame.mirror is None or frame.mirror in self.keep:
            return frame
        if affine is None:
            return replace(frame, mirror=None)
        side = flip_side(frame.comp_side) if affine.det2(frame.plane) < 0 else frame.comp_side
        rot = frame.rotation
        if rot is not None:
            i, j = rot.plane.first, rot.plane.second
            c = [0.0, 0.0, 0.0]
            c[i], c[j] = rot.center_mm
            mc = affine.point((c[0], c[1], c[2], 0.0, 0.0, 0.0))
            angle = -rot.angle_deg if affine.det2(rot.plane) < 0 else rot.angle_deg
            rot = Rotation(rot.plane, (mc[i], mc[j]), angle)
        return replace(frame, mirror=None, comp_side=side, rotation=rot)
