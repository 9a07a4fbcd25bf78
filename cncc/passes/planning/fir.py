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

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from cncc.ir.trajectory import FloatArray, Limit
from cncc.passes.planning.profile import Phases, boundary_speeds, trapezoids
from cncc.passes.planning.ranges import cover_min, range_max, range_min
from cncc.passes.planning.segments import Segments

MAX_CUT_ROUNDS = 3
KNOT_SNAP_S = 1e-9


@dataclass
class _Grid:
    """Elementary intervals between all cap-region ends, with their caps."""

    bp: FloatArray  # (n+1,) breakpoints on s
    vcap: FloatArray  # (n,) widened speed cap
    acap: FloatArray  # (n,) acceleration cap (window minimum)
    limit: np.ndarray  # (n,) int8
    pins: FloatArray  # positions where the path is at rest (besides both ends)


TF_SHARES = (1.0, 0.5, 0.25, 0.125)
FORCED_SHARE = 0.02
REFINE_STEPS = (2**0.5, 2**0.25, 2**0.125)


def fir_profile(seg: Segments) -> Phases:
    ph, tf = unfiltered_profile(seg)
    return _filter(ph, tf, float(seg.s0[-1]))


def unfiltered_profile(seg: Segments) -> tuple[Phases, float]:
    """The fastest of :func:`unfiltered_at` over the filter widths ``share * max A/J``.

    Narrower widths are tried only when the widest one spends a noticeable share of the
    time (:data:`FORCED_SHARE`) in the cruises of about ``Tf`` that the filter forces at
    every speed minimum and cut peak — the only time a narrower filter can save.
    """
    tf_max = float(np.max(seg.acap / seg.jcap))
    best = unfiltered_at(seg, tf_max)
    ph, tf = best
    forced = float(ph.dur[(ph.a0 == 0.0) & (ph.dur < 2 * tf)].sum()) + tf
    if forced < FORCED_SHARE * (ph.end_time + tf):
        return best
    share_best = 1.0
    for share in TF_SHARES[1:]:
        ph, tf = unfiltered_at(seg, tf_max * share)
        if ph.end_time + tf < best[0].end_time + best[1]:
            best, share_best = (ph, tf), share
    # refine around the best width: the time is a smooth function of log(tf) near its
    # minimum, so two halvings of the step find most of what a finer grid would
    centre = share_best
    for step in REFINE_STEPS:
        for share in (centre * step, centre / step):
            if share > 1.0:
                continue
            ph, tf = unfiltered_at(seg, tf_max * share)
            if ph.end_time + tf < best[0].end_time + best[1]:
                best, share_best = (ph, tf), share
        centre = share_best
    return best


def unfiltered_at(seg: Segments, tf: float) -> tuple[Phases, float]:
    """TOPP on the widened caps with the short peaks cut, for the filter width ``tf``.

    The acceleration caps become ``min(acap, jcap * tf)``, so that the filter's jerk
    ``A / tf`` stays within the jerk caps.  A narrow filter loses on long ramps (less
    acceleration) and wins where the speed changes by little between close caps (a
    short filter, narrow widening).  Interior vertices whose cap is zero are rest
    points; the filtered profile of a part from rest to rest lasts the unfiltered time
    plus ``tf``.
    """
    from dataclasses import replace

    seg = replace(seg, acap=np.minimum(seg.acap, seg.jcap * tf))
    grid = _grid(seg, tf)
    ph = _topp(grid)
    for _ in range(MAX_CUT_ROUNDS):
        cuts = peak_cuts(ph, tf)
        if cuts.size == 0:
            return merge_phases(ph), tf
        grid = _with_cuts(grid, cuts)
        ph = _topp(grid)
    # Numerical safety net (never reached in the test suite): a window of 2 A / J bounds
    # the jerk even where the acceleration flips.
    return _topp(_grid(seg, 2 * tf)), 2 * tf


def _grid(seg: Segments, tf: float) -> _Grid:
    total = float(seg.s0[-1])
    inner = seg.vvert[1:-1]
    binding = inner < np.minimum(seg.vcap[:-1], seg.vcap[1:])
    xv, vv = seg.s0[1:-1][binding], inner[binding]
    v_near = np.maximum(np.concatenate([seg.vcap[:1], seg.vcap]), np.concatenate([seg.vcap, seg.vcap[-1:]]))
    v_lo = np.concatenate([seg.s0[:-1] - seg.vcap * tf / 2, xv - vv * tf / 2])
    v_hi = np.concatenate([seg.s0[1:] + seg.vcap * tf / 2, xv + vv * tf / 2])
    v_val = np.concatenate([seg.vcap, vv])
    ends = np.clip(np.concatenate([seg.s0, v_lo, v_hi, seg.s0 - v_near * tf, seg.s0 + v_near * tf]), 0.0, total)
    bp = np.unique(ends)
    vcap = _cover(bp, v_lo, v_hi, v_val)
    k = np.clip(np.searchsorted(seg.s0, (bp[:-1] + bp[1:]) / 2, side="right") - 1, 0, seg.count - 1)
    limit = np.where(vcap < seg.vcap[k] * (1 - 1e-9), Limit.CORNER, seg.vlim[k]).astype(np.int8)
    pins = seg.s0[1:-1][inner <= 0.0]
    return _Grid(bp, vcap, _window_accel(seg, bp, vcap, tf, _xcap(bp, pins)), limit, pins)


def _xcap(bp: FloatArray, pins: FloatArray) -> FloatArray:
    xcap = np.full(bp.size, np.inf)
    xcap[0] = xcap[-1] = 0.0
    xcap[np.clip(np.searchsorted(bp, pins), 0, bp.size - 1)] = 0.0
    return xcap


def _cover(bp: FloatArray, lo: FloatArray, hi: FloatArray, val: FloatArray) -> FloatArray:
    total = float(bp[-1])
    lo_i = np.searchsorted(bp, np.clip(lo, 0.0, total), side="left")
    hi_i = np.searchsorted(bp, np.clip(hi, 0.0, total), side="right") - 1
    return cover_min(bp.size - 1, lo_i, hi_i, val)


def _topp(grid: _Grid) -> Phases:
    length = np.diff(grid.bp)
    x = boundary_speeds(length, grid.vcap, grid.acap, _xcap(grid.bp, grid.pins))
    return trapezoids(length, grid.vcap, grid.acap, x, grid.limit, int(Limit.ACCEL))


def _window_accel(seg: Segments, bp: FloatArray, vcap: FloatArray, tf: float, xcap: FloatArray) -> FloatArray:
    """Acceleration cap of each interval: min over the segments the filter window can reach.

    While the filtered position passes ``x`` the unfiltered one is within ``D`` of it,
    ``D <= Tf * max speed within D``.  The speed is bounded by an *envelope*: the TOPP
    profile with each interval's own (un-windowed, hence larger) acceleration cap, which
    is above every profile with smaller caps.  Iterating ``D`` from ``Tf * max(envelope)``
    keeps a valid, shrinking bound; near a slow corner ``D`` becomes tiny, so the full
    acceleration is used right up to it.
    """
    k_lo = np.clip(np.searchsorted(seg.s0, bp[:-1], side="right") - 1, 0, seg.count - 1)
    k_hi = np.clip(np.searchsorted(seg.s0, bp[1:], side="left"), 1, seg.count)
    own = range_min(seg.acap, k_lo, k_hi)
    env = _envelope(bp, vcap, own, xcap)
    dist = np.full(vcap.size, tf * float(env.max()))
    for _ in range(4):
        lo = np.searchsorted(bp[1:], bp[:-1] - dist, side="right")
        hi = np.searchsorted(bp[:-1], bp[1:] + dist, side="left")
        dist = np.minimum(dist, tf * range_max(env, lo, hi))
    lo = np.searchsorted(seg.s0[1:], bp[:-1] - dist, side="right")
    hi = np.searchsorted(seg.s0[:-1], bp[1:] + dist, side="left")
    out: FloatArray = np.minimum(range_min(seg.acap, lo, hi), own)
    return out


def _envelope(bp: FloatArray, vcap: FloatArray, acap: FloatArray, xcap: FloatArray) -> FloatArray:
    """Largest speed within each interval of the TOPP profile under ``vcap``/``acap``."""
    length = np.diff(bp)
    x = boundary_speeds(length, vcap, acap, xcap)
    peak2 = np.minimum(vcap * vcap, (2 * acap * length + x[:-1] + x[1:]) / 2)
    out: FloatArray = np.sqrt(np.maximum(peak2, np.maximum(x[:-1], x[1:])))
    return out


def _with_cuts(grid: _Grid, cuts: FloatArray) -> _Grid:
    """The grid refined at the cut ends, caps inherited, speed capped at each cut's level."""
    bp = np.unique(np.concatenate([grid.bp, np.clip(cuts[:, :2].reshape(-1), grid.bp[0], grid.bp[-1])]))
    parent = np.clip(np.searchsorted(grid.bp, (bp[:-1] + bp[1:]) / 2, side="right") - 1, 0, grid.vcap.size - 1)
    level = _cover(bp, cuts[:, 0], cuts[:, 1], cuts[:, 2])
    vcap = np.minimum(grid.vcap[parent], level)
    limit = np.where(level < grid.vcap[parent], Limit.ACCEL, grid.limit[parent]).astype(np.int8)
    return _Grid(bp, vcap, grid.acap[parent], limit, grid.pins)


def _flips(ph: Phases, tf: float) -> tuple[np.ndarray, np.ndarray]:
    """Phase pairs (first, second): ``+A`` then ``-A`` with less than ``tf`` of cruise between."""
    nz = np.flatnonzero(ph.a0 != 0.0)
    if nz.size < 2:
        return nz[:0], nz[:0]
    first, second = nz[:-1], nz[1:]
    gap = ph.t0[second] - (ph.t0[first] + ph.dur[first])
    bad = (ph.a0[first] > 0) & (ph.a0[second] < 0) & (gap < tf * (1 - 1e-9))
    return first[bad], second[bad]


def peak_cuts(ph: Phases, tf: float) -> FloatArray:
    """Rows ``(s_from, s_to, level)``: cut every short speed peak flat at ``level``.

    A ``+A -> -A`` flip with less than ``tf`` of cruise between would make the filter's
    jerk ``2A / Tf``.  The fix is the time-optimal one among profiles that follow the
    TOPP envelopes: the highest ``level`` at which the connected part of
    ``{v >= level}`` around the peak is at least ``level * tf`` long, so that cutting
    it flat leaves a cruise of ``tf``.  The level is searched above the higher
    neighbouring minimum first (the part is then the peak's own); only a peak too short
    for that is cut lower, across its neighbours.  Cutting a level set only lowers the
    profile (every cap stays met), needs no other change (the cut profile is TOPP's
    under the extra cap) and creates no new peak.  Levels come from vectorised
    bisections, the parts' ends from binary lifting over a sparse table of per-phase
    minimum speeds: no global re-runs.
    """
    first, second = _flips(ph, tf)
    if first.size == 0:
        return np.zeros((0, 3))
    v_end = ph.v0 + ph.a0 * ph.dur
    tables = _min_tables(np.minimum(ph.v0, v_end))
    s_end = ph.s0 + ph.v0 * ph.dur + ph.a0 * ph.dur**2 / 2
    m_l, m_r, x_l, x_r = _neighbour_minima(ph, v_end, s_end, first, second)
    v_pk = v_end[first]

    def own(level: FloatArray) -> np.ndarray:
        s_a, s_b = _component(ph, tables, first, second, level)
        return np.asarray(s_b - s_a >= level * tf)

    # strictly above the neighbouring minima, or the part would run into the next peak
    m_hi = np.maximum(m_l, m_r)
    top = np.minimum(m_hi * (1 + 1e-7) + 1e-12, v_pk)
    fits = own(top)
    level = np.where(fits, _bisect(own, top, v_pk), m_hi)
    s_a, s_b = _component(ph, tables, first, second, level)
    # a peak too short for its own cruise is cut at the higher neighbouring minimum,
    # from minimum to minimum: the speed then cruises through the higher minimum's
    # plateau and the acceleration does not flip (the neighbouring peaks stay intact)
    s_a = np.where(fits, s_a, x_l)
    s_b = np.where(fits, s_b, x_r)
    return np.stack([s_a, s_b, level], axis=1)


def _bisect(ok: Callable[[FloatArray], np.ndarray], lo: FloatArray, hi: FloatArray) -> FloatArray:
    """Largest level in ``[lo, hi]`` with ``ok`` (``ok`` holds at ``lo``, fails above some level)."""
    lo, hi = lo.copy(), np.maximum(hi, lo)
    for _ in range(44):
        mid = (lo + hi) / 2
        good = ok(mid)
        lo = np.where(good, mid, lo)
        hi = np.where(good, hi, mid)
    out: FloatArray = np.maximum(lo, 1e-9 * hi)
    return out


def _neighbour_minima(ph: Phases, v_end: FloatArray, s_end: FloatArray, first: np.ndarray, second: np.ndarray
                      ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """Speed and position of the minimum before each peak (end of the last braking phase)
    and after it (start of the next accelerating phase); rest at the part's ends."""
    dec = np.flatnonzero(ph.a0 < 0)
    acc = np.flatnonzero(ph.a0 > 0)
    i = np.searchsorted(dec, first) - 1
    q = dec[np.maximum(i, 0)] if dec.size else np.zeros_like(first)
    m_l = np.where(i >= 0, v_end[q], 0.0)
    x_l = np.where(i >= 0, s_end[q], 0.0)
    i = np.searchsorted(acc, second, side="right")
    r = acc[np.minimum(i, acc.size - 1)] if acc.size else np.zeros_like(second)
    m_r = np.where(i < acc.size, ph.v0[r], 0.0)
    x_r = np.where(i < acc.size, ph.s0[r], s_end[-1])
    return m_l, m_r, x_l, x_r


def _min_tables(values: FloatArray) -> list[FloatArray]:
    tables = [values]
    width = 1
    while width * 2 <= values.size:
        prev = tables[-1]
        tables.append(np.minimum(prev[:-width], prev[width:]))
        width *= 2
    return tables


def _component(ph: Phases, tables: list[FloatArray], first: np.ndarray, second: np.ndarray, level: FloatArray
               ) -> tuple[FloatArray, FloatArray]:
    """s-extent of the part of ``{v >= level}`` that contains each peak.

    Left end: in the last phase ``q <= first`` whose minimum speed is below ``level``
    (an accelerating phase); right end: in the first such phase ``r >= second``.
    """
    n = tables[0].size
    in_l = tables[0][first] >= level
    in_r = tables[0][second] >= level
    pos_l, pos_r = first.copy(), second.copy()  # [pos_l, first] and [second, pos_r] are >= level
    for k in range(len(tables) - 1, -1, -1):
        w = 1 << k
        tab = tables[k]
        can = in_l & (pos_l - w >= 0)
        step = can & (tab[np.where(can, pos_l - w, 0)] >= level)
        pos_l = np.where(step, pos_l - w, pos_l)
        can = in_r & (pos_r + w <= n - 1)
        step = can & (tab[np.where(can, pos_r + 1, 0)] >= level)
        pos_r = np.where(step, pos_r + w, pos_r)
    left = np.clip(np.where(in_l, pos_l - 1, first), 0, n - 1)
    right = np.clip(np.where(in_r, pos_r + 1, second), 0, n - 1)
    l2 = level * level
    a_l, a_r = ph.a0[left], ph.a0[right]
    end_l = ph.s0[left] + ph.v0[left] * ph.dur[left] + a_l * ph.dur[left] ** 2 / 2
    with np.errstate(divide="ignore", invalid="ignore"):
        s_a = np.where(a_l > 0, ph.s0[left] + (l2 - ph.v0[left] ** 2) / (2 * a_l), end_l)
        s_b = ph.s0[right] + np.where(a_r < 0, (ph.v0[right] ** 2 - l2) / (-2 * a_r), 0.0)
    return s_a, s_b


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


def merge_phases(ph: Phases) -> Phases:
    """Join consecutive phases of equal acceleration, jerk and limit whose speed is
    continuous (the same polynomial)."""
    n = ph.t0.size
    if n < 2:
        return ph
    new = np.ones(n, bool)
    v_prev = ph.v0[:-1] + ph.a0[:-1] * ph.dur[:-1] + ph.j[:-1] * ph.dur[:-1] ** 2 / 2
    jump = np.abs(ph.v0[1:] - v_prev) > 1e-12 * np.maximum(np.abs(ph.v0[1:]), 1e-300)
    new[1:] = (ph.a0[1:] != ph.a0[:-1]) | (ph.j[1:] != ph.j[:-1]) | (ph.limit[1:] != ph.limit[:-1]) | jump
    if new.all():
        return ph
    start = np.flatnonzero(new)
    end_t = np.append(ph.t0[start[1:]], ph.end_time)
    return Phases(ph.t0[start], end_t - ph.t0[start], ph.s0[start], ph.v0[start], ph.a0[start], ph.j[start],
                  ph.limit[start])


def _snap(knots: FloatArray) -> FloatArray:
    """Drop knots closer than :data:`KNOT_SNAP_S` to the previous kept one.

    A knot ``t0 + Tf`` that coincides with a phase start up to rounding would make a
    phase of ~1e-12 s whose mid-point samples the two sides of a flip inconsistently.
    """
    if knots.size < 2:
        return knots
    close = np.diff(knots) < KNOT_SNAP_S
    if not close.any():
        return knots
    # keep a knot unless it is within the snap distance of the last *kept* knot: group
    # runs of close knots and keep the first of each run (runs are short in practice)
    keep = np.ones(knots.size, bool)
    keep[1:] = ~close
    out: FloatArray = knots[keep]
    return out


def _filter(ph: Phases, tf: float, total_s: float) -> Phases:
    """The moving average of width ``tf`` of the unfiltered profile, as exact cubic phases.

    Positions and speeds at the knots come from the (continuous) position and its time
    integral; acceleration and jerk from samples at the middle of each knot interval,
    where no unfiltered phase boundary can be confused with its neighbour by rounding.
    """
    d, v0, a = ph.dur, ph.v0, ph.a0
    piece = ph.s0 * d + v0 * d**2 / 2 + a * d**3 / 6
    cum_int = np.concatenate([[0.0], np.cumsum(piece)])
    end = ph.end_time
    knots = _snap(np.unique(np.concatenate([ph.t0, ph.t0 + tf, [end, end + tf]])))
    knots = knots[knots < end + tf - KNOT_SNAP_S]
    dur = np.diff(np.concatenate([knots, [end + tf]]))
    s1, _, _, i1 = _state(ph, cum_int, total_s, knots)
    s2, _, _, i2 = _state(ph, cum_int, total_s, knots - tf)
    mid = knots + dur / 2
    _, vm1, am1, _ = _state(ph, cum_int, total_s, mid)
    _, vm2, am2, _ = _state(ph, cum_int, total_s, mid - tf)
    k = np.clip(np.searchsorted(ph.t0, mid - tf / 2, side="right") - 1, 0, ph.t0.size - 1)
    jerk = (am1 - am2) / tf
    acc = (vm1 - vm2) / tf - jerk * dur / 2
    return Phases(knots, dur, (i1 - i2) / tf, (s1 - s2) / tf, acc, jerk, ph.limit[k])
