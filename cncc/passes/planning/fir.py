"""-O2 path profile: TOPP on widened caps, then a moving-average (FIR) jerk filter.

Consumes :class:`Segments` of a run (rest to rest); produces constant-jerk
:class:`Phases` on the path coordinate.

1. ``Tf = max_k acap_k / jcap_k``.  Every speed cap (segment caps and vertex caps) is
   widened by ``v_cap * Tf / 2`` on each side, every acceleration cap by the distance
   travelled in ``Tf`` (bounded from the widened speed caps); the elementary intervals between all region ends get the
   minimum of the caps covering them (:func:`cover_min`).
2. TOPP on these intervals (``profile.py``): bang-bang acceleration.
3. Wherever the acceleration flips from ``+A`` to ``-A`` with less than ``Tf`` of
   cruise between, a point cap with a plateau of ``Tf`` is added and step 2 repeated.
4. The path position is averaged over a sliding window of ``Tf``.  The result is
   exactly piecewise cubic (knots at the unfiltered knots and ``Tf`` after them), lasts
   ``Tf`` longer, and satisfies: speed at any ``x`` <= the cap at ``x`` (widening),
   ``|accel|`` <= the cap at ``x`` (averaging), ``|jerk| = |a(t) - a(t - Tf)| / Tf``
   <= ``A / Tf`` <= the jerk cap (no sign flip within ``Tf``).
For a single move this is the classic 7-phase S-curve (time ``L/v + v/A + A/J``).
"""

from __future__ import annotations

import numpy as np

from cncc.ir.trajectory import FloatArray, Limit
from cncc.passes.planning.profile import Phases, boundary_speeds, trapezoids
from cncc.passes.planning.ranges import cover_min, range_max, range_min
from cncc.passes.planning.segments import Segments

MAX_PEAK_ROUNDS = 12


def fir_profile(seg: Segments) -> Phases:
    tf = float(np.max(seg.acap / seg.jcap))
    extra = np.zeros((0, 2))
    for _ in range(MAX_PEAK_ROUNDS):
        ph = _topp(seg, tf, extra)
        peaks = _short_peaks(ph, tf)
        if peaks.size == 0:
            return _filter(ph, tf, float(seg.s0[-1]))
        extra = np.vstack([extra, peaks])
    # Fallback: a window of 2 A / J bounds the jerk even where the acceleration flips.
    ph = _topp(seg, 2 * tf, np.zeros((0, 2)))
    return _filter(ph, 2 * tf, float(seg.s0[-1]))


def _topp(seg: Segments, tf: float, extra: FloatArray) -> Phases:
    total = float(seg.s0[-1])
    inner = seg.vvert[1:-1]
    binding = inner < np.minimum(seg.vcap[:-1], seg.vcap[1:])
    xv, vv = seg.s0[1:-1][binding], inner[binding]
    if extra.size:
        xv, vv = np.concatenate([xv, extra[:, 0]]), np.concatenate([vv, extra[:, 1]])
    v_near = np.maximum(np.concatenate([seg.vcap[:1], seg.vcap]), np.concatenate([seg.vcap, seg.vcap[-1:]]))
    v_lo = np.concatenate([seg.s0[:-1] - seg.vcap * tf / 2, xv - vv * tf / 2])
    v_hi = np.concatenate([seg.s0[1:] + seg.vcap * tf / 2, xv + vv * tf / 2])
    v_val = np.concatenate([seg.vcap, vv])
    ends = np.clip(np.concatenate([seg.s0, v_lo, v_hi, seg.s0 - v_near * tf, seg.s0 + v_near * tf]), 0.0, total)
    bp = np.unique(ends)
    n = bp.size - 1

    def cover(lo: FloatArray, hi: FloatArray, val: FloatArray) -> FloatArray:
        lo_i = np.searchsorted(bp, np.clip(lo, 0.0, total), side="left")
        hi_i = np.searchsorted(bp, np.clip(hi, 0.0, total), side="right") - 1
        return cover_min(n, lo_i, hi_i, val)

    vcap = cover(v_lo, v_hi, v_val)
    acap = _window_accel(seg, bp, vcap, tf)
    length = np.diff(bp)
    xcap = np.full(n + 1, np.inf)
    xcap[0] = xcap[-1] = 0.0
    k = np.clip(np.searchsorted(seg.s0, (bp[:-1] + bp[1:]) / 2, side="right") - 1, 0, seg.count - 1)
    x = boundary_speeds(length, vcap, acap, xcap)
    limit = np.where(vcap < seg.vcap[k] * (1 - 1e-9), Limit.CORNER, seg.vlim[k]).astype(np.int8)
    return trapezoids(length, vcap, acap, x, limit, int(Limit.ACCEL))


def _window_accel(seg: Segments, bp: FloatArray, vcap: FloatArray, tf: float) -> FloatArray:
    """Acceleration cap of each interval: min over the segments reachable within ``Tf``.

    ``D`` (distance travelled in ``Tf``) is bounded by ``Tf`` times the largest speed cap
    within ``D``; iterating from ``D = Tf * max(vcap)`` keeps a valid, shrinking bound.
    """
    dist = np.full(vcap.size, tf * float(vcap.max()))
    for _ in range(4):
        lo = np.searchsorted(bp[1:], bp[:-1] - dist, side="right")
        hi = np.searchsorted(bp[:-1], bp[1:] + dist, side="left")
        dist = np.minimum(dist, tf * range_max(vcap, lo, hi))
    lo = np.searchsorted(seg.s0[1:], bp[:-1] - dist, side="right")
    hi = np.searchsorted(seg.s0[:-1], bp[1:] + dist, side="left")
    return range_min(seg.acap, lo, hi)


def _short_peaks(ph: Phases, tf: float) -> FloatArray:
    """Point caps ``(x, v)`` for every ``+A -> -A`` flip with less than ``tf`` between."""
    nz = np.flatnonzero(ph.a0 != 0.0)
    if nz.size < 2:
        return np.zeros((0, 2))
    first, second = nz[:-1], nz[1:]
    end_t = ph.t0[first] + ph.dur[first]
    gap = ph.t0[second] - end_t
    bad = (ph.a0[first] > 0) & (ph.a0[second] < 0) & (gap < tf * (1 - 1e-9))
    if not bad.any():
        return np.zeros((0, 2))
    f, s, g = first[bad], second[bad], gap[bad]
    tau = ph.dur[f]
    v_pk = ph.v0[f] + ph.a0[f] * tau
    x_end = ph.s0[f] + ph.v0[f] * tau + ph.a0[f] * tau**2 / 2
    x_pk = x_end + v_pk * g / 2
    acc = np.minimum(ph.a0[f], -ph.a0[s])
    v_c = (-acc * tf + np.sqrt((acc * tf) ** 2 + 4 * v_pk**2)) / 2
    return np.stack([x_pk, v_c * (1 - 1e-9)], axis=1)


def _state(ph: Phases, cum_int: FloatArray, total_s: float, t: FloatArray
           ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """Unfiltered s, v, a and the time integral of s at times ``t`` (rest outside)."""
    end = ph.end_time
    k = np.clip(np.searchsorted(ph.t0, t, side="right") - 1, 0, ph.t0.size - 1)
    tau = np.clip(t - ph.t0[k], 0.0, ph.dur[k])
    v0, a = ph.v0[k], ph.a0[k]
    s = ph.s0[k] + v0 * tau + a * tau**2 / 2
    v = v0 + a * tau
    integ = cum_int[k] + ph.s0[k] * tau + v0 * tau**2 / 2 + a * tau**3 / 6
    before, after = t <= 0.0, t >= end
    s = np.where(before, 0.0, np.where(after, total_s, s))
    v = np.where(before | after, 0.0, v)
    a = np.where(before | after, 0.0, a)
    integ = np.where(before, 0.0, np.where(after, cum_int[-1] + total_s * (t - end), integ))
    return s, v, a, integ


def _filter(ph: Phases, tf: float, total_s: float) -> Phases:
    d, v0, a = ph.dur, ph.v0, ph.a0
    piece = ph.s0 * d + v0 * d**2 / 2 + a * d**3 / 6
    cum_int = np.concatenate([[0.0], np.cumsum(piece)])
    end = ph.end_time
    knots = np.unique(np.concatenate([ph.t0, ph.t0 + tf, [end, end + tf]]))
    knots = knots[knots < end + tf - 1e-13]
    dur = np.diff(np.concatenate([knots, [end + tf]]))
    s1, v1, _a1, i1 = _state(ph, cum_int, total_s, knots)
    s2, v2, _a2, i2 = _state(ph, cum_int, total_s, knots - tf)
    mid = knots + dur / 2
    _, _, am1, _ = _state(ph, cum_int, total_s, mid)
    _, _, am2, _ = _state(ph, cum_int, total_s, mid - tf)
    k = np.clip(np.searchsorted(ph.t0, mid - tf / 2, side="right") - 1, 0, ph.t0.size - 1)
    return Phases(knots, dur, (i1 - i2) / tf, (s1 - s2) / tf, (v1 - v2) / tf, (am1 - am2) / tf, ph.limit[k])
