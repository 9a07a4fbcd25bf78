"""Tool-centre paths of the SERIES 8 milled cavities (G34/G35 rectangle, G36 circle).

Pure plane geometry, relative to the cavity centre: the caller has already taken the
tool radius off the cavity (``a``, ``b`` are the half sizes of the rectangle the tool
centre may reach, ``rho`` the radius of its circle) and checked that the step-over is
positive and no larger than the tool diameter.  Every point and every straight move
stays in that region, which is convex, so the tool never leaves the cavity.

Clearing (option ``cavity_clearing``):

* ``concentric``: from the centre outwards, rings spaced by at most the step-over (the
  innermost ring of a rectangle is the slot along its longer side), each run in the
  programmed direction and joined by a short move outwards; the last ring is the wall;
* ``zigzag``: rows along the plane's first axis, at most a step-over apart, joined at
  their ends, then one ring along the wall in the programmed direction.

A :class:`Step` is a feed move to ``to``; with ``centre`` it is an arc about it
(``turns`` +1 counter-clockwise, -1 clockwise, at most a half circle each).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

Pt = tuple[float, float]
EPS = 1e-9


@dataclass(frozen=True, slots=True)
class Step:
    to: Pt
    centre: Pt | None = None
    turns: int = 0


@dataclass(frozen=True, slots=True)
class LevelPath:
    """The path at one depth: the plunge point, then the steps (the tool ends at ``steps[-1].to``)."""

    start: Pt
    steps: tuple[Step, ...]


def divisions(length: float, step: float) -> int:
    """How many equal parts of ``length`` keep each part no longer than ``step``."""
    return max(0, math.ceil(length / step - 1e-9)) if length > EPS else 0


def depth_levels(r_level: float, bottom: float, per_pass: float) -> list[float]:
    """The depths cut one after the other from ``r_level`` to ``bottom``, at most ``per_pass`` apart
    (all at once when ``per_pass`` is 0)."""
    down = -1.0 if bottom < r_level else 1.0
    total = abs(bottom - r_level)
    n = divisions(total, per_pass) if per_pass > 0 else 1
    n = max(n, 1)
    return [r_level + down * total * k / n for k in range(1, n)] + [bottom]


def _ring(a: float, b: float, ccw: bool, first: Pt) -> list[Step]:
    """Once round the rectangle |u| <= a, |v| <= b from ``first`` (a point on its edge at
    a corner or at (a, 0)) back to it; zero-length moves are left out."""
    corners = [(a, b), (-a, b), (-a, -b), (a, -b)]
    if not ccw:
        corners.reverse()
    start = next((k for k, q in enumerate(corners) if _same(q, first)), None)
    if start is None:  # (a, 0): the middle of the first-axis side
        order = [*corners, first]
    else:
        order = corners[start + 1:] + corners[:start + 1]
    out: list[Step] = []
    at = first
    for q in order:
        if not _same(q, at):
            out.append(Step(q))
            at = q
    return out


def _same(p: Pt, q: Pt) -> bool:
    return abs(p[0] - q[0]) < EPS and abs(p[1] - q[1]) < EPS


def rect_concentric(a: float, b: float, step: float, ccw: bool) -> LevelPath:
    m = min(a, b)
    n = divisions(m, step)
    out: list[Step] = []
    at: Pt = (0.0, 0.0)
    for k in range(n + 1):
        grow = m * k / n if n else 0.0
        ak, bk = a - m + grow, b - m + grow
        first = (ak, 0.0)
        if not _same(first, at):
            out.append(Step(first))
        out.extend(_ring(ak, bk, ccw, first))
        at = first
    return LevelPath((0.0, 0.0), tuple(out))


def _rows(half_width: float, step: float) -> list[float]:
    n = divisions(2.0 * half_width, step)
    return [-half_width + 2.0 * half_width * k / n for k in range(n + 1)] if n else [0.0]


def rect_zigzag(a: float, b: float, step: float, ccw: bool) -> LevelPath:
    out: list[Step] = []
    rows = _rows(b, step)
    start: Pt = (-a, rows[0])
    at = start
    for k, v in enumerate(rows):
        u0, u1 = (-a, a) if k % 2 == 0 else (a, -a)
        for q in ((u0, v), (u1, v)):
            if not _same(q, at):
                out.append(Step(q))
                at = q
    out.extend(_ring(a, b, ccw, at))
    return LevelPath(start, tuple(out))


def _circle(rho: float, ccw: bool, first: Pt) -> list[Step]:
    """A full circle of radius ``rho`` about the origin from ``first`` (on it), as two half circles."""
    turns = 1 if ccw else -1
    opposite = (-first[0], -first[1])
    return [Step(opposite, (0.0, 0.0), turns), Step(first, (0.0, 0.0), turns)]


def circle_concentric(rho: float, step: float, ccw: bool) -> LevelPath:
    n = divisions(rho, step)
    out: list[Step] = []
    for k in range(1, n + 1):
        rk = rho * k / n
        out.append(Step((rk, 0.0)))
        out.extend(_circle(rk, ccw, (rk, 0.0)))
    return LevelPath((0.0, 0.0), tuple(out))


def circle_zigzag(rho: float, step: float, ccw: bool) -> LevelPath:
    out: list[Step] = []
    rows = _rows(rho, step)
    at: Pt = (0.0, rows[0])
    start = at
    for k, v in enumerate(rows):
        w = math.sqrt(max(rho * rho - v * v, 0.0))
        u0, u1 = (-w, w) if k % 2 == 0 else (w, -w)
        for q in ((u0, v), (u1, v)):
            if not _same(q, at):
                out.append(Step(q))
                at = q
    if rho > EPS:
        out.extend(_circle(rho, ccw, at))
    return LevelPath(start, tuple(out))
