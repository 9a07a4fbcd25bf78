"""-O2 path profile in closed form: blocks of segments, jerk-limited S-curves, linear cost.

Consumes the :class:`Segments` of a part (rest to rest, vertex caps filled); produces
constant-jerk :class:`Phases` on the path coordinate, at most seven per block.

1. *Blocks.*  Consecutive segments whose speed, acceleration and jerk caps (vertex caps
   included) stay within :data:`CAP_BAND` of each other form one block (the chords of an
   arc, a smooth polyline); a vertex whose cap is below its neighbours' (a corner) or
   where the caps change ends a block.  A block is planned as one straight move of its
   total length under the minimum of its caps.
2. *Boundary speeds.*  The acceleration is zero at every block boundary, so the distance
   of a speed change ``v0 -> v1`` is ``(v0 + v1) / 2 * T`` with ``T = 2 sqrt(dv / J)``
   (``dv < A^2 / J``) or ``dv / A + A / J``; its inverse :func:`reach` is a cubic or a
   quadratic in closed form.  One backward and one forward pass over the blocks give
   the largest boundary speeds that every block can join (``O(blocks)``).
3. *Profiles.*  Each block accelerates to a peak, cruises and decelerates: the peak is
   the largest speed within the block's cap whose two ramps fit its length (vectorised
   bisection over all blocks at once), the cruise takes the rest, so the distance is
   exact.  A ramp is the time-optimal jerk-limited change of speed between zero
   accelerations (two or three constant-jerk phases): the profile is continuous in
   position, speed and acceleration, and within the speed, acceleration and jerk caps of
   every segment of the block.  For one move this is the 7-phase S-curve
   (``L/v + v/A + A/J``), which is ruckig's time-optimal rest-to-rest profile.

The cost is a few numpy passes over the segments plus a Python loop of a few
microseconds per block; nothing depends on the planned time or on repeated re-plans.
"""

from __future__ import annotations

import math

import numpy as np

from cncc.ir.trajectory import FloatArray, Limit
from cncc.passes.planning.profile import Phases
from cncc.passes.planning.segments import Segments

CAP_BAND = 0.1
"""Speed caps within this share of each other are one block (planned at their minimum)."""

ACCEL_BAND = 0.5
"""Acceleration and jerk caps within this share of each other are one block (a curve's
path caps change with its direction, by up to 1 - 1/sqrt(2) on a circle in XY)."""

BISECT_STEPS = 60


def ramp_time(v0: FloatArray, v1: FloatArray, a_max: FloatArray, j_max: FloatArray) -> FloatArray:
    """Time of the fastest change of speed ``v0 -> v1`` that starts and ends at zero acceleration."""
    dv = np.abs(v1 - v0)
    knee = a_max * a_max / j_max
    out: FloatArray = np.where(dv >= knee, dv / a_max + a_max / j_max, 2.0 * np.sqrt(dv / j_max))
    return out


def ramp_distance(v0: FloatArray, v1: FloatArray, a_max: FloatArray, j_max: FloatArray) -> FloatArray:
    out: FloatArray = (v0 + v1) / 2 * ramp_time(v0, v1, a_max, j_max)
    return out


def reach(v0: float, length: float, a_max: float, j_max: float) -> float:
    """The largest ``v1 >= v0`` that a ramp from ``v0`` reaches within ``length``."""
    if length <= 0.0:
        return v0
    tj = a_max / j_max
    knee = a_max * tj
    if length >= (2 * v0 + knee) * tj:
        # dv^2 / (2A) + dv (v0 / A + A / (2J)) + (v0 A / J - L) = 0
        b = v0 / a_max + tj / 2
        c = v0 * tj - length
        return v0 + -2 * c / (b + math.sqrt(b * b - 2 * c / a_max))
    # x = sqrt(dv): x^3 + 2 v0 x - L sqrt(J) = 0 (one real root, Cardano, one Newton step)
    p, q = 2 * v0, length * math.sqrt(j_max)
    disc = math.sqrt(q * q / 4 + p * p * p / 27)
    w = (q / 2 + disc) ** (1 / 3)
    x = w - p / (3 * w) if w > 0 else 0.0
    if p > 1e3 * q ** (2 / 3):  # cancellation: x ~ q / p
        x = q / p
    for _ in range(2):
        f = x * x * x + p * x - q
        x -= f / (3 * x * x + p)
    return v0 + max(x, 0.0) ** 2


def blocks(seg: Segments) -> np.ndarray:
    """Start segment of every block, ``(b,)`` ascending, starting with 0.

    A vertex inside an arc or a blend (the chords of one curve), or whose cap does not
    bind, joins its two segments; a binding vertex (a corner) ends a block.  Within the
    joined runs a block also ends where the segments' caps (with the caps of the joining
    vertices) leave the band :data:`CAP_BAND` of the block's running minimum.
    """
    k = seg.count
    if k == 1:
        return np.zeros(1, np.int64)
    band, a_band = 1 - CAP_BAND, 1 - ACCEL_BAND
    inner = seg.vvert[1:-1]
    near = np.minimum(seg.vcap[:-1], seg.vcap[1:])
    smooth = seg.smooth[1:-1] if seg.smooth is not None else np.zeros(k - 1, bool)
    soft = (smooth | (inner >= band * near)) & (inner > 0.0)  # a stop always ends a block
    # cap of each segment with its soft vertices
    left = np.concatenate([[np.inf], np.where(soft, inner, np.inf)])
    right = np.concatenate([np.where(soft, inner, np.inf), [np.inf]])
    cap = np.minimum(seg.vcap, np.minimum(left, right))
    starts = [0]
    hard_l = (~soft).tolist()
    cap_l, acap_l, jcap_l = cap.tolist(), seg.acap.tolist(), seg.jcap.tolist()
    lo_v, ac, jc = cap_l[0], acap_l[0], jcap_l[0]
    for m in range(1, k):
        z, a, j = cap_l[m], acap_l[m], jcap_l[m]
        if (hard_l[m - 1] or z < band * lo_v or z * band > lo_v or a < a_band * ac or a * a_band > ac
                or j < a_band * jc or j * a_band > jc):
            starts.append(m)
            lo_v, ac, jc = z, a, j
        else:
            lo_v, ac, jc = min(lo_v, z), min(ac, a), min(jc, j)
    return np.array(starts, np.int64)


def block_caps(seg: Segments, starts: np.ndarray, raw_acap: FloatArray | None = None
               ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray]:
    """Length, speed, acceleration and jerk caps of each block, and the caps at the boundaries.

    ``seg.acap`` leaves the velocity steps at the vertices their share of the axis
    acceleration; a block of one segment has no vertex inside and its acceleration is
    zero at both ends, where the neighbouring steps happen, so it gets ``raw_acap``."""
    ends = np.append(starts[1:], seg.count)
    length = seg.s0[ends] - seg.s0[starts]
    vmin = np.minimum.reduceat(seg.vcap, starts)
    inner = np.concatenate([[np.inf], seg.vvert[1:-1], [np.inf]])  # inner[m]: vertex m (m=0..k)
    inside = np.where(ends - starts > 1, _inside_min(inner, starts), np.inf)
    vcap = np.minimum(vmin, inside)
    acap = np.minimum.reduceat(seg.acap, starts)
    if raw_acap is not None:
        acap = np.where(ends - starts == 1, raw_acap[starts], acap)
    jcap = np.minimum.reduceat(seg.jcap, starts)
    wcap = seg.vvert[np.append(starts, seg.count)].copy()
    return length, vcap, acap, jcap, wcap


def _inside_min(inner: FloatArray, starts: np.ndarray) -> FloatArray:
    """Minimum of ``inner[start + 1 .. end - 1]`` per block (blocks of at least two segments)."""
    vals = inner[1:-1]  # vertex 1 .. k-1
    # vertex m is inside the block whose start < m < end
    owner = np.searchsorted(starts, np.arange(1, vals.size + 1), side="right") - 1
    is_inside = np.arange(1, vals.size + 1) != starts[owner]
    out = np.full(starts.size, np.inf)
    np.minimum.at(out, owner[is_inside], vals[is_inside])
    return out


def boundary_speeds(length: FloatArray, vcap: FloatArray, acap: FloatArray, jcap: FloatArray,
                    wcap: FloatArray) -> FloatArray:
    """Largest speeds at the block boundaries (acceleration zero there) that every block joins."""
    nb = length.size
    cap = np.minimum(wcap, np.minimum(np.concatenate([[np.inf], vcap]), np.concatenate([vcap, [np.inf]])))
    w = cap.tolist()
    ln, ac, jc = length.tolist(), acap.tolist(), jcap.tolist()
    for i in range(nb - 1, -1, -1):
        r = reach(w[i + 1], ln[i], ac[i], jc[i])
        if r < w[i]:
            w[i] = r
    for i in range(nb):
        r = reach(w[i], ln[i], ac[i], jc[i])
        if r < w[i + 1]:
            w[i + 1] = r
    out: FloatArray = np.maximum(np.array(w, float), 0.0)
    return out


def _peak(vs: FloatArray, ve: FloatArray, length: FloatArray, vcap: FloatArray, acap: FloatArray,
          jcap: FloatArray) -> FloatArray:
    """Largest peak in ``[max(vs, ve), vcap]`` whose two ramps fit ``length``."""
    lo = np.maximum(vs, ve)
    hi = np.maximum(vcap, lo)

    def fits(vp: FloatArray) -> np.ndarray:
        return np.asarray(ramp_distance(vs, vp, acap, jcap) + ramp_distance(vp, ve, acap, jcap) <= length)

    top = fits(hi)
    lo = np.where(top, hi, lo)
    for _ in range(BISECT_STEPS):
        mid = (lo + hi) / 2
        good = fits(mid) & ~top
        lo = np.where(good, mid, lo)
        hi = np.where(good | top, hi, mid)
    return lo


def _ramp_phases(v0: FloatArray, v1: FloatArray, a_max: FloatArray, j_max: FloatArray
                 ) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Durations ``(b, 3)``, start accelerations and jerks of the ramps' three phases."""
    dv = v1 - v0
    sign = np.sign(dv)
    mag = np.abs(dv)
    knee = a_max * a_max / j_max
    full = mag >= knee
    tj = np.where(full, a_max / j_max, np.sqrt(mag / j_max))
    ta = np.where(full, mag / a_max - a_max / j_max, 0.0)
    peak = sign * j_max * tj
    dur = np.stack([tj, ta, tj], axis=1)
    acc = np.stack([np.zeros_like(dv), peak, peak], axis=1)
    jerk = np.stack([sign * j_max, np.zeros_like(dv), -sign * j_max], axis=1)
    return dur, acc, jerk


def step_accel_caps(seg: Segments, jmax_mm_s3: FloatArray, period_s: float) -> FloatArray:
    """Path acceleration at each interior vertex whose per-axis step ``a |du_i|`` the
    controller spreads over one period within the jerk limit: ``min_i j_i T / |du_i|``."""
    du = seg.turn()
    budget = jmax_mm_s3[None, :] * period_s
    if seg.a_normal is not None:  # next to an arc the centripetal step takes its share (blending.py)
        curved = np.asarray(seg.a_normal.any(axis=1), bool)
        budget = np.where((curved[1:] | curved[:-1])[:, None], 0.5 * budget, budget)
    with np.errstate(divide="ignore"):
        out: FloatArray = np.where(du > 1e-12, budget / np.maximum(du, 1e-300), np.inf).min(axis=1, initial=np.inf)
    return out


def curvature_jumps(seg: Segments) -> tuple[FloatArray, FloatArray]:
    """Per vertex ``m = 0..k``: the per-axis jump of ``p''(s)`` (the centripetal acceleration
    steps by ``v^2`` times it, ``(k + 1, m)``, zero at the ends) and the largest ``|kappa|`` of
    the two pieces there (``(k + 1,)``, 1/mm)."""
    k = seg.count
    m = seg.p0.shape[1]
    jump = np.zeros((k + 1, m))
    kap = np.zeros(k + 1)
    if seg.geo is None or k < 2:
        return jump, kap
    geo = seg.geo
    rows = np.arange(k)
    _, _, c0, _ = geo.derivatives(rows, np.zeros(k))
    _, _, c1, _ = geo.derivatives(rows, seg.length)
    jump[1:-1] = np.abs(c0[1:] - c1[:-1])
    kappa = np.abs(geo.kappa)
    kap[1:-1] = np.maximum(kappa[1:], kappa[:-1])
    kap[0], kap[-1] = kappa[0], kappa[-1]
    return jump, kap


def coast_times(w: FloatArray, jump: FloatArray, kappa: FloatArray, jmax_mm_s3: FloatArray,
                period_s: float) -> FloatArray:
    """Coast (zero path jerk) on each side of a block boundary crossed at ``w`` where the
    curvature jumps, so that the controller's average over one period ``T`` sees the
    centripetal step ``b_i = w^2 jump_i / (j_i T)`` plus at most ``(1 - b_i) j_i T`` of the
    path's own jerk: outside the coasts the axis jerk is within ``j_i``; during them only the
    circle's turning jerk ``r_i = w^3 kappa^2 / j_i`` acts, so ``c = T max_i b_i / (1 - r_i)``
    (at most ``T``)."""
    step = (w * w)[:, None] * jump / (jmax_mm_s3[None, :] * period_s)
    turn = np.minimum((w**3 * kappa**2)[:, None] / jmax_mm_s3[None, :], 0.5)  # (the caps keep it <= 1/4)
    need = np.where(jump > 1e-12, step / (1.0 - turn), 0.0).max(axis=1, initial=0.0)
    out: FloatArray = period_s * np.minimum(1.0, need)
    return out


def scurve_profile(seg: Segments, raw_acap: FloatArray | None = None, jmax_mm_s3: FloatArray | None = None,
                   period_s: float = 0.0) -> Phases:
    """The -O2 profile of one part (rest to rest); see the module docstring and :func:`block_caps`.

    With the per-axis jerk limits and the interpolation period, a block's acceleration is
    also capped at its interior vertices by :func:`step_accel_caps` (the acceleration
    changes direction there; at block boundaries it is zero), and a block boundary where
    the curvature jumps gets a coast on both sides (:func:`coast_times`).  A vertex inside a
    block where the curvature jumps and whose step, with the axis jerk of the phases within
    one period of it, could exceed ``j_i T`` (:func:`unsafe_steps`) ends a block and gets
    coasts too; the part is re-planned until none is left (a few rounds, then every such
    vertex ends a block)."""
    starts = blocks(seg)
    if jmax_mm_s3 is None or period_s <= 0 or seg.count < 2 or seg.geo is None:
        return _profile(seg, starts, raw_acap, jmax_mm_s3, period_s)
    jump, _ = curvature_jumps(seg)
    jumpy = np.flatnonzero(jump[1:-1].max(axis=1, initial=0.0) > 1e-12) + 1
    for round_ in range(STEP_ROUNDS + 1):
        out = _profile(seg, starts, raw_acap, jmax_mm_s3, period_s)
        cand = np.setdiff1d(jumpy, starts, assume_unique=True)
        if cand.size == 0:
            return out
        bad = cand if round_ == STEP_ROUNDS else unsafe_steps(seg, starts, out, cand, jump, jmax_mm_s3, period_s)
        if bad.size == 0:
            return out
        starts = np.union1d(starts, bad)
    return _profile(seg, starts, raw_acap, jmax_mm_s3, period_s)


STEP_ROUNDS = 4
"""Re-plans of a part for curvature steps inside blocks (:func:`unsafe_steps`); after these,
every vertex inside a block where the curvature jumps ends a block."""

STEP_MARGIN = 0.02
"""Share of ``j_i T`` :func:`unsafe_steps` keeps free (arcs whose radius changes, rounding)."""


def unsafe_steps(seg: Segments, starts: np.ndarray, ph: Phases, cand: np.ndarray, jump: FloatArray,
                 jmax_mm_s3: FloatArray, period_s: float) -> np.ndarray:
    """The vertices of ``cand`` (inside blocks, the curvature jumps there) where the averaged
    jerk rule ``|a(t) - a(t - T)| <= j_i T`` is not proven by the profile ``ph``.

    At such a vertex the axis acceleration steps by ``v^2 |p''_in - p''_out|`` (the tangent
    is continuous, so the tangential part does not step); within any period ``[t - T, t]``
    around it (``t`` the vertex' time or one period later) the rest changes by at most ``T``
    times the axis jerk there, which on a segment with unit tangent bound ``u_i`` and
    curvature ``kappa`` is at most ``A_i sqrt((|s3| + v^3 kappa^2)^2 + (3 v |s2| kappa)^2)``
    (``s2``, ``s3`` the path acceleration and jerk; ``A_i = |u_i|`` on a line, 1 on an axis
    an arc moves).  With ``v``, ``|s2|``, ``|s3|`` the largest over the phases that meet one
    period either side of the phase holding the vertex (a superset of the windows), the
    vertex is safe when the step plus ``T`` times that bound stays within
    ``(1 - STEP_MARGIN) j_i T`` on every axis and those phases cross no block boundary where
    the curvature jumps too."""
    t0, dur = ph.t0, ph.dur
    t1 = t0 + dur
    v1 = ph.v0 + ph.a0 * dur + ph.j * dur * dur / 2
    a1 = ph.a0 + ph.j * dur
    vmax_p = np.maximum(np.abs(ph.v0), np.abs(v1))
    amax_p = np.maximum(np.abs(ph.a0), np.abs(a1))
    jmax_p = np.abs(ph.j)
    sv = seg.s0[cand]
    p = np.clip(np.searchsorted(ph.s0, sv, side="right") - 1, 0, t0.size - 1)
    lo = np.minimum(np.searchsorted(t1, t0[p] - period_s, side="left"), p)
    hi = np.maximum(np.searchsorted(t0, t1[p] + period_s, side="right") - 1, p)
    # maxima over the phase ranges [lo, hi]
    span = hi - lo + 1
    first = np.concatenate([[0], np.cumsum(span)[:-1]])
    idx = np.repeat(lo - first, span) + np.arange(int(span.sum()))
    vw = np.maximum.reduceat(vmax_p[idx], first)
    aw = np.maximum.reduceat(amax_p[idx], first)
    jw = np.maximum.reduceat(jmax_p[idx], first)
    # block of each phase, and the boundaries (vertex starts[b], b >= 1) where the curvature jumps
    blk = np.clip(np.searchsorted(seg.s0[starts], ph.s0 + 1e-12 * (1 + np.abs(ph.s0)), side="right") - 1,
                  0, starts.size - 1)
    jumpy_b = np.concatenate([[0], np.cumsum(jump[starts[1:]].max(axis=1, initial=0.0) > 1e-12)])
    crosses = jumpy_b[blk[hi]] > jumpy_b[blk[lo]]
    kappa = np.abs(seg.shape().kappa)
    au = np.abs(seg.u)
    amp = np.where((kappa > 0)[:, None], (au > 1e-12).astype(float), au)  # (k, m)
    worst = np.zeros((cand.size, seg.u.shape[1]))
    for side in (cand - 1, cand):
        k = kappa[side]
        bound = np.sqrt((jw + vw**3 * k**2) ** 2 + (3 * vw * aw * k) ** 2)
        worst = np.maximum(worst, amp[side] * bound[:, None])
    step = (vw * vw)[:, None] * jump[cand]
    limit = (1 - STEP_MARGIN) * jmax_mm_s3[None, :] * period_s
    bad = (step + period_s * worst > limit).any(axis=1) | crosses
    if bad.any():  # not proven by the bound: the averaged jerk where verify samples it (E0618)
        bad[bad] = ~_sampled_ok(seg, ph, cand[bad], jmax_mm_s3, period_s)
    out: np.ndarray = cand[bad]
    return out


SAMPLED_MARGIN = 0.05
"""Share of ``j_i T`` :func:`_sampled_ok` keeps free (on arcs the averaged jerk between the
sampled instants may exceed its value at them by a little)."""


def _path_state(ph: Phases, t: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """``s, s', s''`` of the profile at times ``t`` (at rest outside it)."""
    end = ph.end_time
    tt = np.clip(t, 0.0, end)
    p = np.clip(np.searchsorted(ph.t0, tt, side="right") - 1, 0, ph.t0.size - 1)
    tau = np.clip(tt - ph.t0[p], 0.0, ph.dur[p])
    j = ph.j[p]
    s = ph.s0[p] + ph.v0[p] * tau + ph.a0[p] * tau**2 / 2 + j * tau**3 / 6
    v = ph.v0[p] + ph.a0[p] * tau + j * tau**2 / 2
    a = np.where((t < 0) | (t > end), 0.0, ph.a0[p] + j * tau)
    return s, v, a


def _axis_accel(seg: Segments, s: FloatArray, v: FloatArray, a: FloatArray, g: np.ndarray | None = None
                ) -> FloatArray:
    """Axis accelerations ``p'(s) s'' + p''(s) s'^2`` (segment ``g``, or the one holding ``s``)."""
    if g is None:
        g = np.clip(np.searchsorted(seg.s0, s, side="right") - 1, 0, seg.count - 1)
    local = np.clip(s - seg.s0[g], 0.0, seg.length[g])
    _, d1, d2, _ = seg.shape().derivatives(g, local)
    out: FloatArray = d1 * a[:, None] + d2 * (v * v)[:, None]
    return out


def _sampled_ok(seg: Segments, ph: Phases, cand: np.ndarray, jmax_mm_s3: FloatArray, period_s: float
                ) -> np.ndarray:
    """``|a(t) - a(t - T)| <= (1 - SAMPLED_MARGIN) j_i T`` at the vertices' times ``t_v`` and at
    ``t_v + T``, both one-sided limits of the step (where verify's E0618 samples it)."""
    sv = seg.s0[cand]
    p = np.clip(np.searchsorted(ph.s0, sv, side="right") - 1, 0, ph.t0.size - 1)
    lo, hi = np.zeros(cand.size), ph.dur[p].copy()
    s0, v0, a0, j0 = ph.s0[p], ph.v0[p], ph.a0[p], ph.j[p]
    for _ in range(BISECT_STEPS // 2):  # s is nondecreasing in the phase: bisect s(t0 + tau) = s_v
        mid = (lo + hi) / 2
        below = s0 + mid * (v0 + mid * (a0 / 2 + mid * j0 / 6)) < sv
        lo, hi = np.where(below, mid, lo), np.where(below, hi, mid)
    tv = ph.t0[p] + (lo + hi) / 2
    _, v, a = _path_state(ph, tv)
    a_left = _axis_accel(seg, sv, v, a, cand - 1)
    a_right = _axis_accel(seg, sv, v, a, cand)
    a_before = _axis_accel(seg, *_path_state(ph, tv - period_s))
    a_after = _axis_accel(seg, *_path_state(ph, tv + period_s))
    limit = (1 - SAMPLED_MARGIN) * jmax_mm_s3[None, :] * period_s
    ok = np.ones(cand.size, bool)
    for g in (a_left - a_before, a_right - a_before, a_after - a_left, a_after - a_right):
        ok &= (np.abs(g) <= limit).all(axis=1)
    return ok


def _profile(seg: Segments, starts: np.ndarray, raw_acap: FloatArray | None, jmax_mm_s3: FloatArray | None,
             period_s: float) -> Phases:
    """The profile of :func:`scurve_profile` on the blocks that start at ``starts``."""
    length, vcap, acap, jcap, wcap = block_caps(seg, starts, raw_acap)
    nb = length.size
    bound = np.append(starts, seg.count)  # vertex of each block boundary
    coast = np.zeros(nb + 1)
    if jmax_mm_s3 is not None and period_s > 0 and seg.count > 1:
        caps = step_accel_caps(seg, jmax_mm_s3, period_s)  # vertex m = 1..k-1 at index m - 1
        owner = np.searchsorted(starts, np.arange(1, seg.count), side="right") - 1
        inside = np.arange(1, seg.count) != starts[owner]
        vertex_cap = np.full(starts.size, np.inf)
        np.minimum.at(vertex_cap, owner[inside], caps[inside])
        acap = np.minimum(acap, vertex_cap)
        jump, kap = curvature_jumps(seg)
        jump_b, kap_b = jump[bound], kap[bound]
        has = jump_b.max(axis=1, initial=0.0) > 1e-12
        if has.any():
            # the coasts must fit the blocks either side: w c(w) <= half the shorter one
            # (c(w) <= T min(1, 2 b), b = w^2 rel): w <= max(len / 2T, (len / 4 T rel)^(1/3))
            rel = (jump_b / (jmax_mm_s3[None, :] * period_s)).max(axis=1, initial=0.0)
            near = np.minimum(np.concatenate([[np.inf], length]), np.concatenate([length, [np.inf]]))
            with np.errstate(divide="ignore", invalid="ignore"):
                fit = np.maximum(near / (2 * period_s), np.cbrt(near / (4 * period_s * np.maximum(rel, 1e-300))))
            wcap = np.where(has, np.minimum(wcap, fit), wcap)
            # reserve the coasts at the boundary's highest possible speed (w c(w) grows with w)
            top = np.minimum(wcap, np.minimum(np.concatenate([[np.inf], vcap]), np.concatenate([vcap, [np.inf]])))
            top = np.where(np.isfinite(top), top, 0.0)
            res = top * coast_times(top, jump_b, kap_b, jmax_mm_s3, period_s)
            w = boundary_speeds(np.maximum(length - res[:-1] - res[1:], 0.0), vcap, acap, jcap, wcap)
            coast = coast_times(w, jump_b, kap_b, jmax_mm_s3, period_s)
    if not coast.any():
        w = boundary_speeds(length, vcap, acap, jcap, wcap)
    vs, ve = w[:-1], w[1:]
    c_s, c_e = coast[:-1], coast[1:]
    avail = np.maximum(length - vs * c_s - ve * c_e, 0.0)
    vp = _peak(vs, ve, avail, vcap, acap, jcap)
    d_up, a_up, j_up = _ramp_phases(vs, vp, acap, jcap)
    d_dn, a_dn, j_dn = _ramp_phases(vp, ve, acap, jcap)
    cruise_len = np.maximum(avail - ramp_distance(vs, vp, acap, jcap) - ramp_distance(vp, ve, acap, jcap), 0.0)
    t_cru = np.where(vp > 0, cruise_len / np.maximum(vp, 1e-300), 0.0)
    z = np.zeros((nb, 1))
    dur = np.concatenate([c_s[:, None], d_up, t_cru[:, None], d_dn, c_e[:, None]], axis=1)  # (b, 9)
    acc = np.concatenate([z, a_up, z, a_dn, z], axis=1)
    jerk = np.concatenate([z, j_up, z, j_dn, z], axis=1)
    # speeds at the phase starts from the ramps' closed forms
    v_ph = np.empty((nb, 9))
    v_ph[:, 0] = vs
    for c in range(1, 9):
        v_ph[:, c] = v_ph[:, c - 1] + acc[:, c - 1] * dur[:, c - 1] + jerk[:, c - 1] * dur[:, c - 1] ** 2 / 2
    v_ph[:, 1] = vs
    v_ph[:, 4] = vp
    v_ph[:, 5] = vp
    v_ph[:, 8] = ve
    ds = v_ph * dur + acc * dur**2 / 2 + jerk * dur**3 / 6
    s_start = seg.s0[starts]
    s_ph = s_start[:, None] + np.concatenate([np.zeros((nb, 1)), np.cumsum(ds, axis=1)[:, :-1]], axis=1)
    cruise_lim = _block_limit(seg, starts, vcap)
    lim = np.full((nb, 9), int(Limit.JERK), np.int8)
    lim[:, 2] = lim[:, 6] = int(Limit.ACCEL)
    lim[:, 4] = cruise_lim
    lim[:, 0] = lim[:, 8] = int(Limit.CORNER)
    flat = dur.reshape(-1)
    keep = flat > 1e-13
    dur_k = flat[keep]
    t0 = np.concatenate([[0.0], np.cumsum(dur_k)[:-1]])
    first = np.repeat(starts, 9)[keep]
    last = np.repeat(np.append(starts[1:], seg.count) - 1, 9)[keep]
    return Phases(t0, dur_k, s_ph.reshape(-1)[keep], v_ph.reshape(-1)[keep], acc.reshape(-1)[keep],
                  jerk.reshape(-1)[keep], lim.reshape(-1)[keep], segments=(first, last))


def _block_limit(seg: Segments, starts: np.ndarray, vcap: FloatArray) -> np.ndarray:
    """What limits each block's cruise: the segment's own limit, or a corner/curvature cap."""
    seg_min = np.minimum.reduceat(seg.vcap, starts)
    own = seg.vlim[starts]
    return np.where(vcap < seg_min * (1 - 1e-9), int(Limit.CENTRIPETAL), own).astype(np.int8)
