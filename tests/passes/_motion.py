"""Helpers for planner tests: commands in machine coordinates with the identity frame."""

from __future__ import annotations

import itertools

from cncc.ir.commands import Arc, Dwell, Linear, Rapid
from cncc.ir.frame import IDENTITY_FRAME, Plane, Vec6
from cncc.source import NO_SPAN


def v6(x: float, y: float, z: float = 0.0) -> Vec6:
    return (float(x), float(y), float(z), 0.0, 0.0, 0.0)


def line(a: tuple[float, ...], b: tuple[float, ...], feed: float = 3000.0) -> Linear:
    return Linear(NO_SPAN, IDENTITY_FRAME, v6(*a), v6(*b), feed)


def rapid(a: tuple[float, ...], b: tuple[float, ...]) -> Rapid:
    return Rapid(NO_SPAN, IDENTITY_FRAME, v6(*a), v6(*b))


def arc(a: tuple[float, ...], b: tuple[float, ...], c: tuple[float, ...], turns: int = 1, feed: float = 3000.0) -> Arc:
    return Arc(NO_SPAN, IDENTITY_FRAME, v6(*a), v6(*b), v6(*c), turns, Plane.XY, feed)


def dwell(s: float) -> Dwell:
    return Dwell(NO_SPAN, IDENTITY_FRAME, s)


def polyline(points: list[tuple[float, ...]], feed: float = 3000.0) -> list[Linear]:
    return [line(a, b, feed) for a, b in itertools.pairwise(points)]
