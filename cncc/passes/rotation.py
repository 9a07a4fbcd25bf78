"""``rotation``: apply G68 coordinate rotation to programmed positions.

Consumes commands whose frames may carry a :class:`~cncc.ir.frame.Rotation` record;
produces them turned by the record's angle (counter-clockwise positive) about its
centre in the record's plane, with the record removed.  Arc directions and the
compensation side are unchanged.  In G91 the increment is turned about the actual
start point (see :mod:`cncc.passes.affine`).  Records in ``keep`` are left in the
frames untouched (a G-code target with G68 runs them itself), and so are work-system
rotations (LinuxCNC G10 L2 R, ``Rotation.work``) under ``keep_work`` (the canon trace);
a work rotation also turns G53 moves and home legs (their program point is the front
end's).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import ClassVar

from cncc.ir import Frame
from cncc.ir.frame import Rotation
from cncc.passes import register
from cncc.passes.affine import Affine, AffinePass


@register
@dataclass(frozen=True, kw_only=True)
class RotationPass(AffinePass):
    """Rotation in the plane of the G68 block."""

    name: ClassVar[str] = "rotation"
    keep: frozenset[object] = frozenset()  # records left in the frames (a G-code target runs them)
    keep_work: bool = False  # leave work-system rotations (the canon trace has program coordinates)

    def _kept(self, r: Rotation) -> bool:
        return r in self.keep or (r.work and self.keep_work)

    def bypasses(self, frame: Frame) -> bool:
        """A work-system rotation turns G53 and home legs too: the front end gave their program point."""
        return frame.rotation is None or not frame.rotation.work

    def affine(self, frame: Frame) -> Affine | None:
        r = frame.rotation
        if r is None or self._kept(r):
            return None
        i, j = r.plane.first, r.plane.second
        a = math.radians(r.angle_deg)
        cos_a, sin_a = math.cos(a), math.sin(a)
        m = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
        m[i][i], m[i][j], m[j][i], m[j][j] = cos_a, -sin_a, sin_a, cos_a
        c = [0.0, 0.0, 0.0]
        c[i], c[j] = r.center_mm
        rows = ((m[0][0], m[0][1], m[0][2]), (m[1][0], m[1][1], m[1][2]), (m[2][0], m[2][1], m[2][2]))
        return Affine((c[0], c[1], c[2]), rows)

    def strip(self, frame: Frame, affine: Affine | None) -> Frame:
        return frame if frame.rotation is None or self._kept(frame.rotation) else replace(frame, rotation=None)
