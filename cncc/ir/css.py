"""Constant surface speed (G96) on a feed-per-revolution move.

Under CSS the spindle speed follows the tool's distance from the spindle axis, so a
G95 feed (length per revolution) changes along the move.  :class:`Css` is the record
a front end puts on a move's :class:`~cncc.ir.commands.Motion`; ``Linear.feed_mm_min``
stays the feed at the start, and :meth:`Css.time_s` gives the exact time of the move
in closed form (no acceleration).

The radius is ``r = p[axis] + shift + offset_mm`` where ``shift`` is the move's
``frame.total_offset_mm[axis]``: ``p + shift`` is the machine position, the same before
and after the frame-lowering passes move the offsets into the positions.  The speed
is ``rpm(r) = min(clamp_rpm, surface_mm_min / (2 pi |r|))``.  With the path
parameter linear in r, ``t = L / (F dr) * integral of 1 / rpm(r) dr``; the integrand is
``max(1 / clamp, 2 pi |r| / v)``, constant inside the clamp radius and linear outside,
so the integral has two pieces on each side of the axis.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

AXIS_RADIUS_MIN_MM = 1e-3
"""Without a clamp, a radius below this is taken as this (the speed would be infinite)."""


@dataclass(frozen=True, slots=True)
class Css:
    surface_mm_min: float  # surface speed v (SFM x 304.8 or m/min x 1000)
    clamp_rpm: float  # top spindle speed (G92 S ...); 0: none
    feed_mm_rev: float  # the G95 feed F
    axis: int = 0  # the radius axis (X)
    offset_mm: float = 0.0  # r = machine position of the axis + offset_mm

    def radius_mm(self, p: Sequence[float], shift_mm: float = 0.0) -> float:
        return p[self.axis] + shift_mm + self.offset_mm

    def rpm_at(self, r_mm: float) -> float:
        r = max(abs(r_mm), 0.0 if self.clamp_rpm > 0 else AXIS_RADIUS_MIN_MM)
        free = self.surface_mm_min / (2 * math.pi * r) if r > 0 else math.inf
        return min(free, self.clamp_rpm) if self.clamp_rpm > 0 else free

    def feed_at_mm_min(self, p: Sequence[float], shift_mm: float = 0.0) -> float:
        return self.feed_mm_rev * self.rpm_at(self.radius_mm(p, shift_mm))

    def slowest_feed_mm_min(self, start: Sequence[float], end: Sequence[float], shift_mm: float = 0.0) -> float:
        """The lowest feed along a straight move: at the largest |r| (an end point)."""
        r = max(abs(self.radius_mm(start, shift_mm)), abs(self.radius_mm(end, shift_mm)))
        return self.feed_mm_rev * self.rpm_at(r)

    def _min_per_rev(self, r_mm: float) -> float:
        return 1.0 / self.rpm_at(r_mm)

    def _antiderivative(self, x_mm: float) -> float:
        """Odd antiderivative of 1/rpm(r) (minutes x mm per revolution) from 0 to x."""
        a, k = abs(x_mm), 2 * math.pi / self.surface_mm_min
        if self.clamp_rpm > 0:
            r_clamp = self.surface_mm_min / (2 * math.pi * self.clamp_rpm)
            if a <= r_clamp:
                g = a / self.clamp_rpm
            else:
                g = r_clamp / self.clamp_rpm + k * (a * a - r_clamp * r_clamp) / 2
        else:
            g = k * a * a / 2
        return math.copysign(g, x_mm)

    def time_s(self, length_mm: float, start: Sequence[float], end: Sequence[float], shift_mm: float = 0.0) -> float:
        """Exact time of a straight move of path length ``length_mm`` from ``start`` to ``end``."""
        if self.feed_mm_rev <= 0 or self.surface_mm_min <= 0 or length_mm <= 0:
            return 0.0
        r0, r1 = self.radius_mm(start, shift_mm), self.radius_mm(end, shift_mm)
        if abs(r1 - r0) <= 1e-9 * max(1.0, length_mm):
            return 60.0 * length_mm * self._min_per_rev(r0) / self.feed_mm_rev
        mean = (self._antiderivative(r1) - self._antiderivative(r0)) / (r1 - r0)  # minutes per revolution
        return 60.0 * length_mm * mean / self.feed_mm_rev
