"""Corner rounding and the velocity-step rule of the jerk-limited levels (-O2, -O3).

**Rounding** (:func:`round_corners`): every corner between two pieces that is not
inside one arc is replaced by a circular arc in the plane of the corner whose
deviation from the corner is at most the incoming command's blend tolerance and whose
tangent length is at most half of each neighbouring piece.  The arc becomes chords of
about one interpolation period at its centripetal speed.  The first half of the chords
belongs to the incoming command, the second half to the outgoing one.

**Velocity steps** (:func:`velocity_step_caps`): on a polyline the velocity of axis
``i`` jumps by ``v |du_i|`` at a vertex.  The controller spreads a jump over one
interpolation period ``T``; the machine sees the acceleration ``a_cont + sum(jumps in
the last T) / T``.  With ``D(x) = T * max speed near x`` and
``W_i(m) = sum |du_i|`` over the vertices within ``D`` of vertex ``m``, the cap
``v_m <= share * a_i * T / W_i(m)`` keeps the jump part at most ``share * a_i``
(``W_i(m)``: the largest sum of ``|du_i|`` over the vertices a jump at ``m`` can overlap)
(``share`` = :data:`NORMAL_SHARE`); :func:`reduce_accel` then leaves each segment the
rest of the axis acceleration for the tangential part.
"""

from __future__ import annotations

import numpy as np

from cncc.ir.machine import MachineModel
from cncc.ir.trajectory import FloatArray
from cncc.passes.planning.geometry import NORMAL_SHARE, PathRun
from cncc.passes.planning.limits import AxisLimits, path_limit
from cncc.passes.planning.ranges import cover_min
from cncc.passes.planning.segments import Segments

MAX_BLEND_CHORDS = 64


def round_corners(run: PathRun, limits: AxisLimits, machine: MachineModel,
                  sharp: np.ndarray | None = None) -> PathRun:
    """The run with its corners rounded; ``sharp`` (``(k+1,)`` bool) marks vertices left as
    they are (the planner stops there).  The result's ``origin`` maps each new point to the
    vertex it comes from."""
    pts = run.points
    k = pts.shape[0] - 1
    if k < 2:
        return run
    d = np.diff(pts, axis=0)
    length = np.linalg.norm(d, axis=1)
    u = d / np.maximum(length, 1e-300)[:, None]
    u_in, u_out = u[:-1], u[1:]
    cos_t = np.clip(np.einsum("ij,ij->i", u_in, u_out), -1.0, 1.0)
    theta = np.arccos(cos_t)  # deflection angle at interior vertices 1..k-1
    tol = run.tol_mm[:-1]
    straight = run.straight
    ok = (~run.arc_vertex[1:-1]) & (theta > 1e-7) & (theta < np.pi - 1e-3) & (tol > 0)
    ok &= straight[:-1] & straight[1:]  # native arcs keep their corners (vertex caps)
    ok &= (length[:-1] > 1e-9) & (length[1:] > 1e-9)
    if sharp is not None:
        ok &= ~sharp[1:-1]
    if not ok.any():
        return run
    half = theta / 2
    with np.errstate(divide="ignore", invalid="ignore"):
        r_tol = tol / (1.0 / np.cos(half) - 1.0)
        d_tol = np.nan_to_num(r_tol * np.tan(half), nan=0.0, posinf=np.inf)
    d_t = np.minimum.reduce([d_tol, 0.5 * length[:-1], 0.5 * length[1:]])
    ok &= d_t > 1e-9
    radius = np.where(ok, d_t / np.tan(np.where(ok, half, 1.0)), 0.0)
    e2 = u_out - cos_t[:, None] * u_in
    e2 /= np.maximum(np.linalg.norm(e2, axis=1), 1e-300)[:, None]
    a_min = path_limit(limits.amax_mm_s2, np.abs(u_in) + np.abs(e2))
    v_c = np.sqrt(NORMAL_SHARE * a_min * np.maximum(radius, 1e-12))
    t = machine.interpolation_period_s
    chord = np.maximum(1.02 * v_c * t + 2.2 * t * t * a_min, 1e-5)
    n_b = np.where(ok, np.clip(np.ceil(radius * theta / chord), 1, MAX_BLEND_CHORDS), 0).astype(np.int64)
    return _rebuild(run, pts, u_in, e2, d_t, radius, theta, n_b)


def _rebuild(run: PathRun, pts: FloatArray, u_in: FloatArray, e2: FloatArray, d_t: FloatArray,
             radius: FloatArray, theta: FloatArray, n_b: np.ndarray) -> PathRun:
    """New polyline: P0, then per interior vertex its blend points (or itself), then Pk."""
    k = pts.shape[0] - 1
    per_vertex = np.where(n_b > 0, n_b + 1, 1)  # points contributed by each interior vertex
    owner = np.repeat(np.arange(k - 1), per_vertex)
    first = np.concatenate([[0], np.cumsum(per_vertex)[:-1]])
    j = np.arange(owner.size) - first[owner]  # index within the vertex' blend
    nb = n_b[owner]
    phi = np.where(nb > 0, theta[owner] * j / np.maximum(nb, 1), 0.0)
    vertex = pts[1:-1][owner]
    b1 = vertex - u_in[owner] * d_t[owner][:, None]
    r = radius[owner][:, None]
    arc = b1 + r * (np.sin(phi)[:, None] * u_in[owner] + (1 - np.cos(phi))[:, None] * e2[owner])
    mid = np.where((nb > 0)[:, None], arc, vertex)
    new_pts = np.vstack([pts[:1], mid, pts[-1:]])
    # piece attributes: piece p of the new polyline ends at new point p+1
    end_owner = np.concatenate([owner, [k - 1]])
    end_j = np.concatenate([j, [0]])
    end_nb = np.concatenate([nb, [0]])
    is_last = np.arange(end_owner.size) == end_owner.size - 1
    # a piece ending at blend point j of vertex v (j >= 1) is a blend chord: owner v or v+1 by half;
    # a piece ending at the first point of vertex v (or at Pk) is the straight part of piece v (or k-1)
    src = np.where(is_last, k - 1, np.where(end_j == 0, end_owner, np.where(end_j <= end_nb // 2, end_owner,
                                                                              end_owner + 1)))
    arcv = np.zeros(new_pts.shape[0], dtype=bool)
    arcv[1:-1] = run.arc_vertex[1:-1][owner] | ((nb > 0) & (j > 0) & (j < nb))
    origin = np.concatenate([[0], owner + 1, [k]])
    return PathRun(new_pts, run.cmd[src], run.rapid[src], run.feed_mm_s[src], run.tol_mm[src], arcv, run.stop_cmd,
                   origin, None if run.geo is None else np.where(end_j == 0, run.geo[src], -1), run.arcs)


def _reach_mm(seg: Segments, caps: FloatArray, period_s: float) -> FloatArray:
    """Distance within which a jump at each vertex still overlaps a later one.

    Within ``delta`` of a vertex crossed at ``<= c`` the speed is at most
    ``sqrt(c^2 + 2 A delta)``; two jumps overlap only if they are less than ``T`` apart,
    hence ``delta < T^2 A + sqrt(T^4 A^2 + T^2 c^2)``.
    """
    acc = float(seg.acap.max())
    c = np.minimum(np.minimum(caps, seg.vcap[:-1]), seg.vcap[1:])
    t2a = period_s * period_s * acc
    out: FloatArray = t2a + np.sqrt(t2a * t2a + (period_s * c) ** 2)
    return out


def _caps_from(seg: Segments, du: FloatArray, caps: FloatArray, period_s: float, budget: FloatArray) -> FloatArray:
    xv = seg.s0[1:-1]
    reach = _reach_mm(seg, caps, period_s)
    cs = np.vstack([np.zeros((1, 6)), np.cumsum(du, axis=0)])
    lo = np.arange(xv.size)
    hi = np.searchsorted(xv, xv + reach, side="right")
    axes = np.flatnonzero(du.max(axis=0) > 1e-12)  # only the axes that turn
    window = cs[hi][:, axes] - cs[lo][:, axes]  # (k-1, m) sum over the window starting at each vertex
    w = -cover_min(xv.size, lo, hi, -window)
    with np.errstate(divide="ignore"):
        cap = np.where(w > 1e-15, budget[None, axes] / np.maximum(w, 1e-300), np.inf).min(axis=1, initial=np.inf)
    return np.where(du.max(axis=1) > 1e-12, cap, np.inf)


def velocity_step_caps(seg: Segments, limits: AxisLimits, period_s: float) -> FloatArray:
    """Caps at the interior vertices, shape ``(k - 1,)`` (inf where the path is straight).

    ``F(caps)`` (caps from the windows that ``caps`` imply) is decreasing, so
    ``min(c, F(c))`` is always self-consistent; three rounds climb towards the fixed point.
    """
    du = seg.turn()  # (k-1, 6)
    if du.size == 0:
        return np.zeros(0)
    budget = NORMAL_SHARE * limits.amax_mm_s2 * period_s
    caps = _caps_from(seg, du, np.full(du.shape[0], np.inf), period_s, budget)
    for _ in range(3):
        new = _caps_from(seg, du, caps, period_s, budget)
        caps = np.minimum(new, _caps_from(seg, du, new, period_s, budget))
    if seg.geo is not None:
        caps = np.minimum(caps, curvature_step_caps(seg, limits, period_s))
    return caps


TANGENT_STEP_SHARE = 0.95
"""Share of what a curvature step at a tangent joint may take of ``(1 - r_i) j_i T``, ``r_i =
v^3 kappa^2 / j_i`` the circle's turning jerk share at the joint.  At a block boundary the coasts
(``scurve.coast_times``, ``c = T b / (1 - r)``) leave only that turning jerk within the period, so
the step ``b`` plus the path's jerk stay within ``j_i T`` while ``b <= 1 - r``; inside a block
``scurve.unsafe_steps`` ends the block where the ramp's jerk would add too much.  (A flat 1/2 of
``j_i T`` while vertices inside blocks had no such check; 0.7 before the turning share was used.)"""

CURVATURE_STEP_SHARE = 0.5
"""Share of ``j_i T`` the centripetal acceleration step at a curvature jump may take where
the path also turns (the tangential step takes the other half); all of it at tangent joints."""


def curvature_step_caps(seg: Segments, limits: AxisLimits, period_s: float) -> FloatArray:
    """Speed caps at the interior vertices where the curvature jumps (line -> arc, arc ->
    arc): the centripetal acceleration steps by ``v^2 |p''_in - p''_out|`` per axis, which
    the controller spreads over one period within :data:`CURVATURE_STEP_SHARE` of
    ``j_i T`` (the jerk-step rule E0618), shape ``(k - 1,)``."""
    geo = seg.shape()
    rows = np.arange(seg.count)
    _, _, c0, _ = geo.derivatives(rows, np.zeros(seg.count))
    _, _, c1, _ = geo.derivatives(rows, seg.length)
    jump = np.abs(c0[1:] - c1[:-1])
    # a tangent joint has no tangential acceleration step: the whole j T is the centripetal one's
    tangent = seg.turn().max(axis=1, initial=0.0) < 1e-9
    jt = limits.jmax_mm_s3[None, :] * period_s
    with np.errstate(divide="ignore"):
        v2 = np.where(jump > 1e-12, TANGENT_STEP_SHARE * jt / np.maximum(jump, 1e-300), np.inf).min(axis=1)
    # the turning share at that speed (an over-estimate at the lower speed it leads to, so the
    # lowered cap keeps b <= TANGENT_STEP_SHARE (1 - r) at its own speed)
    kappa = np.abs(geo.kappa)
    k2 = np.maximum(kappa[1:], kappa[:-1]) ** 2
    with np.errstate(invalid="ignore", over="ignore"):
        turn = np.where(np.isfinite(v2), v2**1.5 * k2, 0.0)[:, None] / limits.jmax_mm_s3[None, :]
    share = np.where(tangent[:, None], TANGENT_STEP_SHARE * (1.0 - np.clip(turn, 0.0, 0.5)), CURVATURE_STEP_SHARE)
    with np.errstate(divide="ignore"):
        v2 = np.where(jump > 1e-12, share * jt / np.maximum(jump, 1e-300), np.inf).min(axis=1)
    out: FloatArray = np.sqrt(v2)
    return out


def reduce_accel(seg: Segments, limits: AxisLimits, period_s: float) -> FloatArray:
    """Segment path-acceleration caps left after the velocity steps' share."""
    du = seg.turn()
    if du.size == 0:
        return seg.acap
    caps = np.minimum(np.minimum(seg.vvert[1:-1], seg.vcap[:-1]), seg.vcap[1:])
    load = du * caps[:, None] / period_s  # (k-1, 6), jump of vertex m (between segments m-1 and m)
    reach = _reach_mm(seg, caps, period_s)
    xv = seg.s0[1:-1]
    first = np.arange(1, xv.size + 1)  # the segment after vertex m
    last = np.searchsorted(seg.s0[:-1], xv + reach, side="right")  # segments starting before x + reach
    diff = np.zeros((seg.count + 1, 6))
    np.add.at(diff, first, load)
    np.add.at(diff, np.maximum(last, first), -load)
    n_load = np.cumsum(diff, axis=0)[:-1]
    left = np.maximum(limits.amax_mm_s2[None, :] - n_load, 1e-6 * limits.amax_mm_s2[None, :])
    if seg.a_normal is not None:  # arcs: the centripetal part is orthogonal to the tangential one
        left = np.maximum(np.sqrt(np.maximum(left**2 - seg.a_normal**2, 0.0)), 1e-6 * limits.amax_mm_s2[None, :])
    au = np.abs(seg.u)
    with np.errstate(divide="ignore"):
        acap = np.where(au > 1e-12, left / np.maximum(au, 1e-300), np.inf).min(axis=1)
    out: FloatArray = np.minimum(acap, seg.acap)
    return out
