"""Arc forms a target accepts: split an IR arc into pieces a target can write.

Consumes one arc (start, end, centre, plane, signed turns); produces a list of
:class:`Piece` that together trace the same helix:

* single-quadrant targets (Series 8): pieces end on every quadrant boundary, so
  each piece's centre offsets can be written unsigned;
* R-form targets: pieces whose sweep is near 180 or 360 degrees (where the sign of R
  cannot tell the arcs apart reliably) are cut into equal parts;
* targets without one-block full circles: a full turn becomes two halves;
* targets without a turns word: extra helix turns become separate full circles.

The axis normal to the plane and the rotary axes advance in proportion to the
swept angle (a helix is uniform), so the pieces join on the original path.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

from cncc.ir import Plane, Vec6

ARC_LETTERS = {Plane.XY: ("I", "J"), Plane.ZX: ("K", "I"), Plane.YZ: ("J", "K")}  # centre words per plane

TAU = 2.0 * math.pi
EPS_RAD = 1e-9


@dataclass(frozen=True, slots=True)
class Piece:
    start: Vec6
    end: Vec6
    sweep_rad: float  # > 0, in the direction of travel
    turns_extra: int = 0  # full turns written with a turns word


@dataclass(frozen=True, slots=True)
class ArcForm:
    single_quadrant: bool = False
    r_form: bool = False
    full_circle: bool = True
    turns_word: bool = False
    min_piece_mm: float = 0.0  # quadrant cuts closer than this (along the arc) to an end are left out


def sweep(start: Vec6, end: Vec6, center: Vec6, plane: Plane, turns: int) -> float:
    """Total swept angle in radians (> 0) of an arc with LinuxCNC-style signed turns."""
    i, j = plane.first, plane.second
    a0 = math.atan2(start[j] - center[j], start[i] - center[i])
    a1 = math.atan2(end[j] - center[j], end[i] - center[i])
    d = (a1 - a0) if turns > 0 else (a0 - a1)
    d %= TAU
    if d <= EPS_RAD or (TAU - d <= EPS_RAD and _same_point(start, end, plane)):
        d = TAU
    return d + (abs(turns) - 1) * TAU


def _same_point(a: Vec6, b: Vec6, plane: Plane) -> bool:
    return abs(a[plane.first] - b[plane.first]) < 1e-9 and abs(a[plane.second] - b[plane.second]) < 1e-9


def split(start: Vec6, end: Vec6, center: Vec6, plane: Plane, turns: int, form: ArcForm) -> list[Piece]:
    total = sweep(start, end, center, plane, turns)
    cuts = _cuts(start, center, plane, turns, total, form)
    if not cuts and form.turns_word and total > TAU + EPS_RAD and not form.single_quadrant:
        return [Piece(start, end, total - (abs(turns) - 1) * TAU, abs(turns) - 1)]
    out: list[Piece] = []
    prev_t, prev = 0.0, start
    for t in [*cuts, total]:
        p = end if t == total else _point(start, end, center, plane, turns, total, t)
        if t - prev_t > EPS_RAD:
            out.append(Piece(prev, p, t - prev_t))
        prev_t, prev = t, p
    return out


def _cuts(start: Vec6, center: Vec6, plane: Plane, turns: int, total: float, form: ArcForm) -> list[float]:
    """Angles (from the start, along the travel) where the arc is cut, ascending, excluding 0 and total."""
    cuts: set[float] = set()
    if form.single_quadrant:
        i, j = plane.first, plane.second
        a0 = math.atan2(start[j] - center[j], start[i] - center[i])
        # distance along the travel to the next multiple of 90 degrees
        rel = (a0 if turns > 0 else -a0) % (math.pi / 2)
        first = (math.pi / 2 - rel) if rel > 1e-9 else math.pi / 2
        t = first
        r = math.hypot(start[i] - center[i], start[j] - center[j])
        while t < total - 1e-9:
            if min(t, total - t) * r >= form.min_piece_mm:  # no sliver the target could not tell apart
                cuts.add(t)
            t += math.pi / 2
    else:
        if not form.turns_word:
            t = TAU
            while t < total - 1e-9:
                cuts.add(t)
                t += TAU
        cuts |= _form_cuts(total, form, sorted(cuts))
    return sorted(c for c in cuts if 1e-9 < c < total - 1e-9)


def _form_cuts(total: float, form: ArcForm, turn_cuts: list[float]) -> set[float]:
    """Extra cuts inside each segment for R form (near 180/360 degrees) and for full circles."""
    out: set[float] = set()
    bounds = [0.0, *turn_cuts, total]
    for a, b in itertools.pairwise(bounds):
        seg = b - a
        deg = math.degrees(seg)
        n = 1
        if form.r_form and (170.0 < deg < 190.0 or deg > 350.0):
            n = max(2, math.ceil(deg / 170.0))
        elif not form.full_circle and deg > 359.999:
            n = 2
        out |= {a + seg * k / n for k in range(1, n)}
    return out


def _point(start: Vec6, end: Vec6, center: Vec6, plane: Plane, turns: int, total: float, t: float) -> Vec6:
    """The point at swept angle ``t`` (radius of the start; other axes in proportion)."""
    i, j = plane.first, plane.second
    r = math.hypot(start[i] - center[i], start[j] - center[j])
    a0 = math.atan2(start[j] - center[j], start[i] - center[i])
    a = a0 + (t if turns > 0 else -t)
    f = t / total
    p = [start[k] + (end[k] - start[k]) * f for k in range(6)]
    p[i] = center[i] + r * math.cos(a)
    p[j] = center[j] + r * math.sin(a)
    return (p[0], p[1], p[2], p[3], p[4], p[5])


def helix_feed_ratio(start: Vec6, end: Vec6, center: Vec6, plane: Plane, turns: int,
                     sweep_rad: float | None = None) -> float:
    """In-plane length / path length of a helix (1 for a flat arc)."""
    rise = end[plane.normal] - start[plane.normal]
    if rise == 0.0:
        return 1.0
    i, j = plane.first, plane.second
    swept = sweep(start, end, center, plane, turns) if sweep_rad is None else sweep_rad
    planar = swept * math.hypot(start[i] - center[i], start[j] - center[j])
    if planar <= 1e-9:  # a degenerate arc of no radius: the feed is left as it is
        return 1.0
    return planar / math.hypot(planar, rise)
