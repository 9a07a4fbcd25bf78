"""Polar coordinates (G15/G16): a block's end point from its radius and angle words.

The G15/G16 handlers are in :mod:`cncc.frontend.transforms`; the radius and angle in
force are in the interpreter's transform record.  :func:`cncc.frontend.ops.target`
calls :func:`polar_target` while the frame is polar.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from cncc.ir import Vec6

if TYPE_CHECKING:
    from cncc.frontend.interp import BlockContext, Interpreter

AXES = "XYZABC"


def polar_target(it: Interpreter, ctx: BlockContext) -> Vec6:
    """End point of a block in polar mode: first plane word = radius, second = angle.

    Angles are counter-clockwise positive from the first plane axis (SYNTEC A-23).
    Absolute words replace the last radius/angle, incremental words add to them.
    """
    pol = it.frame.polar
    assert pol is not None
    plane = it.frame.plane
    i, j = plane.first, plane.second
    rd = it.reader
    inc = it.modal.incremental
    p = list(it.pos)
    for k, letter in enumerate(AXES):
        w = ctx.words.get(letter)
        if w is None or k in (i, j):
            continue
        v = rd.axis_value(w)
        p[k] = p[k] + v if inc else v
    st = it.transform
    rw, aw = ctx.words.get(AXES[i]), ctx.words.get(AXES[j])
    if rw is not None:
        v = rd.length_mm(rw)
        st.polar_radius_mm = st.polar_radius_mm + v if inc else v
    if aw is not None:
        v = rd.angle_deg(aw)
        st.polar_angle_deg = st.polar_angle_deg + v if inc else v
    if rw is not None or aw is not None:
        a = math.radians(st.polar_angle_deg)
        p[i] = pol.origin_mm[0] + st.polar_radius_mm * math.cos(a)
        p[j] = pol.origin_mm[1] + st.polar_radius_mm * math.sin(a)
    return (p[0], p[1], p[2], p[3], p[4], p[5])
