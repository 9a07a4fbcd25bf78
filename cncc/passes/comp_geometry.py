"""Plane geometry for cutter compensation: path elements, offsets, intersections.

Points are ``(u, v)`` pairs in the compensation plane (the plane's first and second
axes).  An :class:`Element` is one programmed line or arc with its offset curve; the
compensation pass trims the offset curve's ends at corners (``q0``, ``q1``).
Signs: ``side`` is +1 for G41 (tool left of the path) and -1 for G42; arc sweeps are
counter-clockwise positive.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

Pt = tuple[float, float]
EPS = 1e-9


def sub(a: Pt, b: Pt) -> Pt:
    return (a[0] - b[0], a[1] - b[1])


def add(a: Pt, b: Pt, k: float = 1.0) -> Pt:
    return (a[0] + k * b[0], a[1] + k * b[1])


def cross(a: Pt, b: Pt) -> float:
    return a[0] * b[1] - a[1] * b[0]


def dot(a: Pt, b: Pt) -> float:
    return a[0] * b[0] + a[1] * b[1]


def norm(a: Pt) -> float:
    return math.hypot(a[0], a[1])


def unit(a: Pt) -> Pt:
    n = norm(a)
    return (a[0] / n, a[1] / n) if n > 0 else (0.0, 0.0)


def left(t: Pt) -> Pt:
    """``t`` turned a quarter counter-clockwise (the left normal of a direction)."""
    return (-t[1], t[0])


def wrap(a: float) -> float:
    """An angle in (-pi, pi]."""
    a = math.fmod(a, 2 * math.pi)
    if a <= -math.pi:
        a += 2 * math.pi
    elif a > math.pi:
        a -= 2 * math.pi
    return a


@dataclass(slots=True)
class Element:
    """A programmed line (``center is None``) or arc, and its offset curve."""

    p0: Pt
    p1: Pt
    side: float  # +1 left (G41), -1 right (G42)
    r: float  # tool radius
    center: Pt | None = None
    ccw: bool = True
    sweep: float = 0.0  # signed programmed sweep of an arc (radians)
    q0: Pt = (0.0, 0.0)  # offset start (trimmed at the previous corner)
    q1: Pt = (0.0, 0.0)  # offset end (trimmed at the next corner)

    @property
    def is_arc(self) -> bool:
        return self.center is not None

    @property
    def radius(self) -> float:
        assert self.center is not None
        return norm(sub(self.p0, self.center))

    @property
    def offset_radius(self) -> float:
        """Radius of the offset circle: smaller when the tool is on the centre side."""
        d = 1.0 if self.ccw else -1.0
        return self.radius - self.side * d * self.r

    def tangent(self, at_end: bool) -> Pt:
        if self.center is None:
            return unit(sub(self.p1, self.p0))
        p = self.p1 if at_end else self.p0
        t = left(unit(sub(p, self.center)))
        return t if self.ccw else (-t[0], -t[1])

    def normal_point(self, at_end: bool) -> Pt:
        """The programmed end (or start) moved by r to the tool side, square to the path."""
        p = self.p1 if at_end else self.p0
        return add(p, left(self.tangent(at_end)), self.side * self.r)

    def offset_sweep(self) -> float:
        """Signed sweep of the trimmed offset arc (same sign as ``sweep`` unless it reversed)."""
        assert self.center is not None
        c = self.center
        a_p0 = math.atan2(self.p0[1] - c[1], self.p0[0] - c[0])
        a_p1 = math.atan2(self.p1[1] - c[1], self.p1[0] - c[0])
        a_q0 = math.atan2(self.q0[1] - c[1], self.q0[0] - c[0])
        a_q1 = math.atan2(self.q1[1] - c[1], self.q1[0] - c[0])
        return self.sweep - wrap(a_q0 - a_p0) + wrap(a_q1 - a_p1)

    def reversed_offset(self) -> bool:
        """True when the trimmed offset runs against the programmed direction (a gouge)."""
        if self.center is None:
            d = sub(self.q1, self.q0)
            along = dot(d, unit(sub(self.p1, self.p0)))
            return along < -1e-6
        sw = self.offset_sweep()
        return sw * self.sweep < 0 and abs(sw) * self.offset_radius > 1e-6


def arc_sweep(p0: Pt, p1: Pt, c: Pt, ccw: bool, turns: int) -> float:
    """Signed sweep of an arc; equal end points make a full circle."""
    a0 = math.atan2(p0[1] - c[1], p0[0] - c[0])
    a1 = math.atan2(p1[1] - c[1], p1[0] - c[0])
    if ccw:
        s = (a1 - a0) % (2 * math.pi)
        if s < 1e-12:
            s = 2 * math.pi
        return s + 2 * math.pi * (abs(turns) - 1)
    s = (a0 - a1) % (2 * math.pi)
    if s < 1e-12:
        s = 2 * math.pi
    return -(s + 2 * math.pi * (abs(turns) - 1))


def _line_line(p: Pt, d: Pt, q: Pt, e: Pt) -> list[Pt]:
    den = cross(d, e)
    if abs(den) < 1e-12:
        return []
    t = cross(sub(q, p), e) / den
    return [add(p, d, t)]


def _line_circle(p: Pt, d: Pt, c: Pt, r: float) -> list[Pt]:
    d = unit(d)
    f = sub(p, c)
    b = dot(f, d)
    disc = b * b - (dot(f, f) - r * r)
    if disc < -1e-9:
        return []
    s = math.sqrt(max(disc, 0.0))
    return [add(p, d, -b - s), add(p, d, -b + s)]


def _circle_circle(c1: Pt, r1: float, c2: Pt, r2: float) -> list[Pt]:
    dvec = sub(c2, c1)
    d = norm(dvec)
    if d < 1e-12 or d > r1 + r2 + 1e-9 or d < abs(r1 - r2) - 1e-9:
        return []
    a = (r1 * r1 - r2 * r2 + d * d) / (2 * d)
    h = math.sqrt(max(r1 * r1 - a * a, 0.0))
    m = add(c1, dvec, a / d)
    n = left(unit(dvec))
    return [add(m, n, h), add(m, n, -h)]


def offset_intersections(a: Element, b: Element) -> list[Pt]:
    """Points where the offset curves of ``a`` and ``b`` (extended: lines, full circles) meet."""
    if a.center is None and b.center is None:
        return _line_line(a.normal_point(True), a.tangent(True), b.normal_point(False), b.tangent(False))
    if a.center is None:
        assert b.center is not None
        return _line_circle(a.normal_point(True), a.tangent(True), b.center, b.offset_radius)
    if b.center is None:
        return _line_circle(b.normal_point(False), b.tangent(False), a.center, a.offset_radius)
    return _circle_circle(a.center, a.offset_radius, b.center, b.offset_radius)


def nearest(points: list[Pt], target: Pt) -> Pt | None:
    return min(points, key=lambda p: norm(sub(p, target))) if points else None
