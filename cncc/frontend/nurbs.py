"""NURBS curves in the XY plane and their biarc approximation, as LinuxCNC draws them.

LinuxCNC's interpreter turns ``G5`` (cubic: 4 control points), ``G5.1`` (quadratic:
3) and ``G5.2``/``G5.3`` (any order L) into one ``NURBS_FEED`` call; its motion
controller then samples the curve at ``4 x (number of control points)`` equal steps
of the parameter and joins each pair of samples by a *biarc* (two tangent arcs, each
degenerating to a line when it is straight) that starts and ends with the curve's
tangents.  :func:`biarcs` does the same, so cncc's IR holds the path the machine
follows.

The knot vector is LinuxCNC's clamped uniform one with integer knots
``0 ... 0, 1, 2, ..., n-k+2 ... n-k+2``; the basis is Cox-de Boor with half-open
spans (the last one closed); tangents are finite differences over ``du = 0.001`` as
LinuxCNC computes them.  Points are ``(x, y, w)``, weights positive.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

Pt = tuple[float, float]
CtrlPoint = tuple[float, float, float]  # x, y, weight
_DU = 0.001
_SMALL = 1e-6  # LinuxCNC's limit below which an arc is drawn as a line


@dataclass(frozen=True, slots=True)
class Segment:
    """One piece of the approximation: a line, or an arc about ``center`` (``ccw`` its sense)."""

    end: Pt
    center: Pt | None = None
    ccw: bool = True


def knots(n_points: int, order: int) -> list[int]:
    """LinuxCNC's knot vector for ``n_points`` control points of order ``order`` (degree + 1)."""
    n, k = n_points - 1, order
    return [0 if i < k else (i - k + 1 if i <= n else n - k + 2) for i in range(n + k + 1)]


def _basis(i: int, k: int, u: float, kv: Sequence[int], umax: float) -> float:
    if k == 1:
        if kv[i] <= u < kv[i + 1]:
            return 1.0
        return 1.0 if u == umax and kv[i] < kv[i + 1] == umax else 0.0
    value = 0.0
    if kv[i + k - 1] > kv[i]:
        value += (u - kv[i]) * _basis(i, k - 1, u, kv, umax) / (kv[i + k - 1] - kv[i])
    if kv[i + k] > kv[i + 1]:
        value += (kv[i + k] - u) * _basis(i + 1, k - 1, u, kv, umax) / (kv[i + k] - kv[i + 1])
    return value


def point(u: float, order: int, cps: Sequence[CtrlPoint], kv: Sequence[int]) -> Pt:
    umax = float(kv[-1])
    ns = [_basis(i, order, u, kv, umax) * cps[i][2] for i in range(len(cps))]
    den = sum(ns)
    if den == 0.0:
        return cps[-1][0], cps[-1][1]
    return (sum(n * c[0] for n, c in zip(ns, cps, strict=True)) / den,
            sum(n * c[1] for n, c in zip(ns, cps, strict=True)) / den)


def tangent(u: float, order: int, cps: Sequence[CtrlPoint], kv: Sequence[int]) -> Pt:
    """Unit tangent by a forward difference (backward at the end of the curve)."""
    umax = float(kv[-1])
    if u + _DU > umax:
        a, b = point(u - _DU, order, cps, kv), point(u, order, cps, kv)
    else:
        a, b = point(u, order, cps, kv), point(u + _DU, order, cps, kv)
    return _unit(b[0] - a[0], b[1] - a[1])


def _unit(x: float, y: float) -> Pt:
    h = math.hypot(x, y)
    return (x / h, y / h) if h else (x, y)


def _arc(p0: Pt, p1: Pt, d: Pt) -> Segment:
    """The arc from ``p0`` to ``p1`` leaving ``p0`` along ``d`` (LinuxCNC's ``arc``)."""
    x, y = p1[0] - p0[0], p1[1] - p0[1]
    den = 2.0 * (y * d[0] - x * d[1])
    if abs(den) <= _SMALL:
        return Segment(p1)
    r = -(x * x + y * y) / den
    return Segment(p1, (p0[0] + d[1] * r, p0[1] - d[0] * r), r < 0)


def biarc(p0: Pt, ts: Pt, p4: Pt, te: Pt) -> list[Segment]:
    """Two arcs from ``p0`` (tangent ``ts``) to ``p4`` (tangent ``te``), equal tangent lengths.

    Where LinuxCNC's formula has no solution (parallel tangents along the chord, or
    both roots positive) cncc draws a straight line, where LinuxCNC would draw nothing
    or divide by zero.
    """
    ts, te = _unit(*ts), _unit(*te)
    vx, vy = p0[0] - p4[0], p0[1] - p4[1]
    c = vx * vx + vy * vy
    if c == 0.0:
        return []
    b = 2.0 * (vx * (ts[0] + te[0]) + vy * (ts[1] + te[1]))
    a = 2.0 * (ts[0] * te[0] + ts[1] * te[1] - 1.0)
    discr = b * b - 4.0 * a * c
    if abs(a) < 1e-12 or discr < 0:
        return [Segment(p4)]
    disq = math.sqrt(discr)
    beta1, beta2 = (-b - disq) / 2.0 / a, (-b + disq) / 2.0 / a
    if beta1 > 0 and beta2 > 0:
        return [Segment(p4)]
    beta = max(beta1, beta2)
    alpha = beta  # LinuxCNC's r = 1: equal tangent lengths
    p1 = (p0[0] + alpha * ts[0], p0[1] + alpha * ts[1])
    p3 = (p4[0] - beta * te[0], p4[1] - beta * te[1])
    ab = alpha + beta
    p2 = ((p1[0] * beta + p3[0] * alpha) / ab, (p1[1] * beta + p3[1] * alpha) / ab)
    tm = _unit(p3[0] - p2[0], p3[1] - p2[1])
    return [_arc(p0, p2, ts), _arc(p2, p4, tm)]


def biarcs(cps: Sequence[CtrlPoint], order: int) -> list[Segment]:
    """LinuxCNC's approximation of the NURBS ``cps`` of order ``order``."""
    if order < 2 or len(cps) < order:
        return [Segment((c[0], c[1])) for c in cps[1:]]
    kv = knots(len(cps), order)
    umax = float(kv[-1])
    div = 4 * len(cps)
    p0, t0 = point(0.0, order, cps, kv), tangent(0.0, order, cps, kv)
    out: list[Segment] = []
    for i in range(1, div + 1):
        u = umax * i / div
        p1, t1 = point(u, order, cps, kv), tangent(u, order, cps, kv)
        out += biarc(p0, t0, p1, t1)
        p0, t0 = p1, t1
    return out
