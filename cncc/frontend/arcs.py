"""Arc geometry for the front end: centres from I/J/K or R, and turn counts."""

from __future__ import annotations

import math

from cncc.ir import Plane, Vec6


def center_from_offsets(start: Vec6, plane: Plane, off1: float, off2: float) -> Vec6:
    """Centre = start + (I/J/K offsets in the plane)."""
    c = list(start)
    c[plane.first] = start[plane.first] + off1
    c[plane.second] = start[plane.second] + off2
    return (c[0], c[1], c[2], c[3], c[4], c[5])


def center_from_radius(start: Vec6, end: Vec6, plane: Plane, radius: float, clockwise: bool,
                       tolerance: float) -> tuple[Vec6, str]:
    """Centre of the arc through ``start`` and ``end`` with signed ``radius``.

    R > 0 selects the arc of at most 180 degrees, R < 0 the larger one.  Returns the
    centre and an error string ("" when fine): "full" for coincident end points,
    "small" when the chord exceeds 2|R| by more than ``tolerance``.
    """
    i, j = plane.first, plane.second
    x0, y0, x1, y1 = start[i], start[j], end[i], end[j]
    dx, dy = x1 - x0, y1 - y0
    chord = math.hypot(dx, dy)
    r = abs(radius)
    if chord < 1e-12:
        return start, "full"
    half = chord / 2.0
    err = ""
    if half > r:
        if half - r > tolerance + 1e-9:  # at the limit itself (inch words made mm) the arc is fine
            err = "small"
        h = 0.0
    else:
        h = math.sqrt(r * r - half * half)
    # Unit normal to the chord, pointing left of start->end.
    nx, ny = -dy / chord, dx / chord
    # Minor arc CCW has its centre on the left; CW on the right; R<0 flips.
    side = 1.0 if not clockwise else -1.0
    if radius < 0:
        side = -side
    mx, my = (x0 + x1) / 2.0, (y0 + y1) / 2.0
    c = list(start)
    c[i] = mx + side * h * nx
    c[j] = my + side * h * ny
    return (c[0], c[1], c[2], c[3], c[4], c[5]), err


def radius_mismatch(start: Vec6, end: Vec6, center: Vec6, plane: Plane) -> tuple[float, float]:
    i, j = plane.first, plane.second
    r0 = math.hypot(start[i] - center[i], start[j] - center[j])
    r1 = math.hypot(end[i] - center[i], end[j] - center[j])
    return r0, r1
