"""The exact step-time algorithm as it was before the vectorised fast path (session
2026-12-02 c), frozen here as the oracle of tests/backends/test_pulses_fast.py.

A verbatim copy of ``roots.py``, ``curved.py``, the step-solving part of ``solve.py`` and
the compressor of ``queue.py`` at 77dee82 (imports merged).  Do not "improve" it: its job is to stay what the fast path
is compared with.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from cncc.backends.pulses.spec import AxisPulseSpec
from cncc.ir.trajectory import Trajectory, axis_bounds

F64 = npt.NDArray[np.float64]
I64 = npt.NDArray[np.int64]

ACCEPT_STEP_S = 1e-9
FALLBACK_TOL_S = 1e-13
FALLBACK_MAX_ITER = 100


def piece_times(d: F64, counts: I64, v: F64, a: F64, j: F64, length: F64,
                ends: tuple[F64, F64, F64]) -> F64:
    """Local time of every step; ``d`` (per step) and ``v a j length ends`` (per piece) in the direction frame.

    ``ends`` = (distance from the piece start to its end, velocity and acceleration at the end).
    """
    cruise = (j == 0) & (a == 0)
    with np.errstate(divide="ignore", over="ignore"):
        inv_v = np.where(cruise, 1.0 / v, 0.0)
    u: F64 = d * np.repeat(inv_v, counts)  # cruise steps; the others are overwritten below
    if not cruise.all():
        first = np.cumsum(counts) - counts
        for kind, solver in ((~cruise & (j == 0), _accel), (j != 0, _jerk)):
            if kind.any():
                k_counts = counts[kind]
                idx = _step_index(first[kind], k_counts)
                u[idx] = solver(d[idx], k_counts, v[kind], a[kind], j[kind], length[kind],
                                tuple(e[kind] for e in ends))
    np.minimum(u, np.repeat(length, counts), out=u)
    return u


def _step_index(first: I64, counts: I64) -> I64:
    """Indices of the steps of the pieces starting at ``first`` with ``counts`` steps."""
    total = int(counts.sum())
    idx = np.arange(total, dtype=np.int64)
    idx += np.repeat(first - (np.cumsum(counts) - counts), counts)
    return idx


def _accel(d: F64, counts: I64, v: F64, a: F64, j: F64, length: F64, ends: tuple[F64, ...]) -> F64:
    w = np.repeat(0.5 * v, counts)
    root = d * np.repeat(0.5 * a, counts)
    root += w * w
    np.maximum(root, 0.0, out=root)
    np.sqrt(root, out=root)
    root += w
    with np.errstate(divide="ignore", invalid="ignore"):
        u = np.divide(d, root, out=root)
    return _clamp(u, np.repeat(length, counts))


def _clamp(u: F64, lim: F64) -> F64:
    u = np.where(np.isfinite(u), u, lim)
    np.clip(u, 0.0, lim, out=u)
    return u


def _jerk(d: F64, counts: I64, v: F64, a: F64, j: F64, length: F64, ends: tuple[F64, ...]) -> F64:
    span, ve, ae = ends
    rest = np.repeat(span, counts) - d  # distance from the boundary to the piece end
    near_end = rest < d
    vs, acc, jk, lim = (np.repeat(x, counts) for x in (v, a, j, length))
    u = _guess(d, vs, acc, jk, lim)
    if near_end.any():
        sel = np.flatnonzero(near_end)
        # backwards in time from the end: Ve w - Ae w^2/2 + J w^3/6 = rest
        w = _guess(rest[sel], np.repeat(ve, counts)[sel], -np.repeat(ae, counts)[sel], jk[sel], lim[sel])
        u[sel] = lim[sel] - w
    return _refine(u, d, vs, acc, jk, lim)


def _guess(d: F64, v: F64, a: F64, j: F64, lim: F64) -> F64:
    """Root of the no-jerk part (``V u + A u^2/2 = d``), else the pure-jerk cube root, clamped to the piece."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        w = 0.5 * v
        root = w * w + 0.5 * a * d
        u = d / (w + np.sqrt(root))
        bad = ~((root >= 0) & (u <= lim))  # NaN compares False: bad
        if bad.any():
            cube = np.cbrt(6.0 * d / j)
            u = np.where(bad, np.where(cube <= lim, cube, 0.5 * lim), u)
    u = np.where(u >= 0, u, 0.0)
    return u


def _refine(u: F64, d: F64, v: F64, a: F64, j: F64, lim: F64) -> F64:
    """One Halley and one Newton step; roots whose Newton step is large go to :func:`_bracketed`."""
    j6, j2, a2 = j / 6.0, j / 2.0, a / 2.0
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        f = ((j6 * u + a2) * u + v) * u - d
        fp = (j2 * u + a) * u + v
        fpp = j * u + a
        u = u - 2.0 * f * fp / (2.0 * fp * fp - f * fpp)
        f = ((j6 * u + a2) * u + v) * u - d
        fp = (j2 * u + a) * u + v
        step = f / fp
        u -= step
        ok = (np.abs(step) <= ACCEPT_STEP_S) & (u >= -ACCEPT_STEP_S) & (u <= lim + ACCEPT_STEP_S)
    if not ok.all():
        sel = np.flatnonzero(~ok)
        u[sel] = _bracketed(u[sel], d[sel], v[sel], a[sel], j[sel], lim[sel])
    np.clip(u, 0.0, lim, out=u)
    return u


def _bracketed(u: F64, d: F64, v: F64, a: F64, j: F64, lim: F64) -> F64:
    """Roots of ``v u + a u^2/2 + j u^3/6 = d`` in ``[0, lim]`` (increasing there): Newton kept in a bracket."""
    out = np.empty_like(u)
    lo = np.zeros_like(u)
    hi = lim.copy()
    u = np.where(np.isfinite(u) & (u > 0) & (u < lim), u, 0.5 * lim)
    idx = np.arange(u.shape[0])
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for _ in range(FALLBACK_MAX_ITER):
            f = u * (v + u * (a / 2 + u * j / 6)) - d
            lo = np.where(f < 0, u, lo)
            hi = np.where(f > 0, u, hi)
            un = u - f / (v + u * (a + u * j / 2))
            un = np.where((un > lo) & (un < hi), un, 0.5 * (lo + hi))
            done = (np.abs(un - u) <= FALLBACK_TOL_S) | (f == 0) | (hi - lo <= FALLBACK_TOL_S)
            if done.any():
                out[idx[done]] = un[done]
                keep = ~done
                idx, u, d, v, a, j, lo, hi = (x[keep] for x in (idx, un, d, v, a, j, lo, hi))
                if idx.size == 0:
                    return out
            else:
                u = un
    out[idx] = u
    return out

# ---- curved.py





F64 = npt.NDArray[np.float64]
I64 = npt.NDArray[np.int64]

MAX_SEGMENT_SWEEP_RAD = np.pi / 12
"""Curved phases are cut into segments of at most this mean sweep (at most one turning
point of any axis per segment, even where the speed changes within the phase)."""


def _axis_kind(traj: Trajectory, g: I64, i: int) -> tuple[F64, F64]:
    """Amplitude ``A`` and phase ``phi`` of axis ``i`` on geometry rows ``g`` (``A = 0``: axial)."""
    assert traj.path is not None
    geo = traj.path.geometry
    return np.hypot(geo.e1[g, i], geo.e2[g, i]), np.arctan2(geo.e2[g, i], geo.e1[g, i])


def _tau_at(traj: Trajectory, k: I64, s_target: F64, ta: F64, tb: F64) -> F64:
    """Local times in ``[ta, tb]`` of phases ``k`` where ``s`` reaches ``s_target`` (one per entry)."""
    assert traj.path is not None
    law = traj.path
    s_a, v_a, a_a, j = law.s_at(k, ta)
    s_b, v_b, a_b, _ = law.s_at(k, tb)
    d = np.clip(s_target - s_a, 0.0, np.maximum(s_b - s_a, 0.0))
    ones = np.ones(k.size, np.int64)
    u = piece_times(d, ones, v_a, a_a, j, tb - ta, (s_b - s_a, v_b, a_b))
    return ta + u


def turning_times(traj: Trajectory, k: I64, ta: F64, tb: F64, i: int) -> F64:
    """Per segment (phase ``k``, local ``[ta, tb]``): the time where axis ``i`` turns inside, NaN if none."""
    assert traj.path is not None
    law, geo = traj.path, traj.path.geometry
    g = law.seg[k]
    amp, shift = _axis_kind(traj, g, i)
    s_a, _, _, _ = law.s_at(k, ta)
    s_b, _, _, _ = law.s_at(k, tb)
    th_a = geo.theta0[g] + geo.kappa[g] * s_a
    th_b = geo.theta0[g] + geo.kappa[g] * s_b
    lo, hi = np.minimum(th_a, th_b), np.maximum(th_a, th_b)
    m = np.ceil((lo - shift) / np.pi)  # zeros of the axis' derivative: th = phi + m pi
    th = shift + m * np.pi
    inside = (amp > 1e-12) & (th > lo) & (th < hi)
    out = np.full(k.size, np.nan)
    if inside.any():
        sel = np.flatnonzero(inside)
        kap = geo.kappa[g[sel]]
        s_t = (th[sel] - geo.theta0[g[sel]]) / kap
        out[sel] = _tau_at(traj, k[sel], s_t, ta[sel], tb[sel])
        out[sel] = np.where((out[sel] > ta[sel]) & (out[sel] < tb[sel]), out[sel], np.nan)
    return out


def curved_step_times(traj: Trajectory, k: I64, i: int, tau_a: F64, tau_e: F64, counts: I64, y: F64) -> F64:
    """Local times (from each piece start) of the steps of monotone pieces of axis ``i``.

    Pieces: phase ``k``, local interval ``[tau_a, tau_e]``, ``counts`` steps; ``y`` the
    axis positions of the step boundaries (all pieces concatenated)."""
    assert traj.path is not None
    law, geo = traj.path, traj.path.geometry
    kk = np.repeat(k, counts)
    g = law.seg[kk]
    amp, shift = _axis_kind(traj, g, i)
    s_a, _, _, _ = law.s_at(k, tau_a)
    s_e, _, _, _ = law.s_at(k, tau_e)
    sa, se = np.repeat(s_a, counts), np.repeat(s_e, counts)
    kap = geo.kappa[g]
    c = geo.c[g, i]
    # the monotone branch of each piece: its angles lie in [phi + m pi, phi + (m + 1) pi]
    th_mid = geo.theta0[g] + kap * (sa + se) / 2
    m = np.floor((th_mid - shift) / np.pi)
    sign = np.where(m % 2 == 0, 1.0, -1.0)
    base = shift + m * np.pi
    s = (sa + se) / 2
    plane = amp > 1e-12
    with np.errstate(divide="ignore", invalid="ignore"):
        for _ in range(3 if np.any(geo.dr[g] != 0) else 1):
            rho = np.maximum((geo.r0[g] + geo.dr[g] * s) * amp, 1e-300)
            # cos(th - phi) = cos(base - phi + psi) = sign cos(psi)
            psi = np.arccos(np.clip(sign * (y - c) / rho, -1.0, 1.0))
            s_plane = (base + psi - geo.theta0[g]) / np.where(kap != 0, kap, 1.0)
            s_axial = (y - c) / np.where(geo.w[g, i] != 0, geo.w[g, i], 1.0)
            s = np.where(plane, s_plane, s_axial)
    lo, hi = np.minimum(sa, se), np.maximum(sa, se)
    s = np.clip(np.nan_to_num(s, nan=0.0), lo, hi)
    # s -> time: the phase's cubic from the piece start
    v_a, a_a, j = (np.asarray(x) for x in law.s_at(k, tau_a)[1:])
    _, v_e, a_e, _ = law.s_at(k, tau_e)
    u = piece_times(s - sa, counts, v_a, a_a, j, tau_e - tau_a, (s_e - s_a, v_e, a_e))
    return u

# ---- solve.py






F64 = npt.NDArray[np.float64]
I64 = npt.NDArray[np.int64]
I8 = npt.NDArray[np.int8]
I32 = npt.NDArray[np.int32]

JERK_SEGMENT_STEPS = 64  # a jerk phase is cut into segments of about this many steps (all axes)


@dataclass(frozen=True, slots=True)
class RawSteps:
    """Steps of one axis in one window, before time warping and ns rounding.

    ``t_s``, ``direction``, ``phase``: shape ``(c,)``, sorted by time.
    ``run_t_s``, ``run_dir``, ``run_phase``, ``run_first``: shape ``(r,)``, the start of
    each stretch of motion that makes steps (a monotone piece, or an interpolation
    period) and the index of its first step, used to find reversals and direction
    changes without looking at every step.
    """

    t_s: F64
    direction: I8
    phase: I32
    run_t_s: F64
    run_dir: I8
    run_phase: I32
    run_first: I64

    @staticmethod
    def empty() -> RawSteps:
        z = np.zeros(0)
        return RawSteps(z, np.zeros(0, np.int8), np.zeros(0, np.int32), z.copy(),
                        np.zeros(0, np.int8), np.zeros(0, np.int32), np.zeros(0, np.int64))


@dataclass(frozen=True, slots=True)
class Segments:
    """Phases cut into segments; arrays ``(S,)`` except ``value_mm`` ``(S + 1, m)``."""

    phase: I64
    ta_s: F64  # segment start, local time within its phase
    tb_s: F64
    est_steps: F64  # estimated steps of all axes
    value_mm: F64  # every axis' position at each segment boundary


def poly(p0: F64, v0: F64, a0: F64, j: F64, tau: F64) -> F64:
    return p0 + tau * (v0 + tau * (a0 / 2 + tau * j / 6))


def velocity_roots(v0: F64, a0: F64, j: F64, ta: F64, tb: F64) -> tuple[F64, F64]:
    """Zeros of ``v0 + a0 tau + j tau^2/2`` strictly inside ``(ta, tb)``, NaN elsewhere; lo <= hi."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        big_a = j / 2
        disc = a0 * a0 - 4 * big_a * v0
        sq = np.sqrt(np.where(disc >= 0, disc, np.nan))
        q = -0.5 * (a0 + np.where(a0 >= 0, sq, -sq))
        r1 = np.where(j != 0, q / big_a, np.where(a0 != 0, -v0 / a0, np.nan))
        r2 = np.where(j != 0, v0 / q, np.nan)
    lo = np.fmin(r1, r2)
    hi = np.fmax(r1, r2)
    hi = np.where(hi == lo, np.nan, hi)
    lo = np.where((lo > ta) & (lo < tb), lo, np.nan)
    hi = np.where((hi > ta) & (hi < tb), hi, np.nan)
    return lo, hi


def speed_max(v0: F64, a0: F64, j: F64, t: F64) -> F64:
    """Largest ``|v|`` over ``[0, t]`` (elementwise)."""
    v_end = v0 + t * (a0 + t * j / 2)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        ts = np.where(j != 0, -a0 / j, np.nan)
    inside = (ts > 0) & (ts < t)
    ts = np.where(inside, ts, 0.0)
    v_mid = np.where(inside, v0 + ts * (a0 + ts * j / 2), 0.0)
    return np.maximum(np.maximum(np.abs(v0), np.abs(v_end)), np.abs(v_mid))


def segment(traj: Trajectory, steps_per_mm: F64, budget: int) -> Segments:
    """Cut phases so that no segment holds more than about ``budget`` steps."""
    n = traj.phase_count
    dur = traj.duration_s
    bent = traj.curved
    vmax = axis_bounds(traj)[0] if bent.any() else speed_max(traj.v0_mm_s, traj.a0_mm_s2, traj.j_mm_s3, dur[:, None])
    est = (vmax * dur[:, None] * steps_per_mm[None, :]).sum(axis=1) + 1.0
    jerky = np.any(traj.j_mm_s3 != 0, axis=1)
    per_seg = np.where(jerky, float(min(budget, JERK_SEGMENT_STEPS)), float(budget))
    nsub = np.clip(np.ceil(est / per_seg), 1, 1 << 30).astype(np.int64)
    if bent.any() and traj.path is not None:
        law = traj.path
        kb = np.flatnonzero(bent)
        s_end, _, _, _ = law.s_at(kb, dur[kb])
        sweep = np.abs(law.geometry.kappa[law.seg[kb]] * (s_end - law.s0_mm[kb]))
        nsub[kb] = np.maximum(nsub[kb], np.ceil(sweep / MAX_SEGMENT_SWEEP_RAD).astype(np.int64))
    phase = np.repeat(np.arange(n, dtype=np.int64), nsub)
    first = np.cumsum(nsub) - nsub
    sub = np.arange(phase.shape[0], dtype=np.int64) - first[phase]
    frac = 1.0 / nsub[phase]
    ta = dur[phase] * (sub * frac)
    tb = np.where(sub + 1 == nsub[phase], dur[phase], dur[phase] * ((sub + 1) * frac))
    k = phase
    tcol = ta[:, None]
    values = poly(traj.p0_mm[k], traj.v0_mm_s[k], traj.a0_mm_s2[k], traj.j_mm_s3[k], tcol)
    if bent.any():
        cb = np.flatnonzero(bent[k])
        values[cb] = traj.states(k[cb], ta[cb])[0]
    values = np.where((sub == 0)[:, None], traj.p0_mm[k], values)
    if n:
        end, _, _ = traj.end_state(n - 1)
        values = np.vstack([values, end[None, :]])
    else:
        values = np.zeros((1, len(traj.axes)))
    return Segments(phase, ta, tb, (est / nsub)[phase], values)


def windows(seg: Segments, budget: int) -> list[tuple[int, int]]:
    """Consecutive segment ranges ``[lo, hi)`` holding about ``budget`` steps each."""
    s = seg.phase.shape[0]
    if s == 0:
        return []
    before = np.cumsum(seg.est_steps) - seg.est_steps
    wid = np.floor(before / budget).astype(np.int64)
    cuts = np.flatnonzero(np.diff(wid)) + 1
    edges = [0, *cuts.tolist(), s]
    return list(itertools.pairwise(edges))


@dataclass(frozen=True, slots=True)
class _Pieces:
    """The monotone pieces of one axis over some segments that make steps; arrays ``(q,)``."""

    c: I64  # segment (relative to ``lo``) of each piece
    tau_a: F64  # piece start, local time in its phase
    tau_e: F64  # piece end
    counts: I64
    direction: I8
    na: I64  # motor step count at the piece start
    pa: F64  # position at the piece start
    pe: F64  # position at the piece end
    t_abs: F64  # piece start, trajectory time
    phase: I32


def _pieces(traj: Trajectory, seg: Segments, lo: int, hi: int, i: int, spec: AxisPulseSpec) -> _Pieces | None:
    """Split segments ``[lo, hi)`` of axis ``i`` at its velocity zeros; keep the pieces that step."""
    ph = seg.phase[lo:hi]
    p0, v0 = traj.p0_mm[ph, i], traj.v0_mm_s[ph, i]
    a0, jk = traj.a0_mm_s2[ph, i], traj.j_mm_s3[ph, i]
    ta, tb = seg.ta_s[lo:hi], seg.tb_s[lo:hi]
    r1, r2 = velocity_roots(v0, a0, jk, ta, tb)
    bent = traj.curved[ph]
    if bent.any():
        cb = np.flatnonzero(bent)
        r1[cb] = turning_times(traj, ph[cb], ta[cb], tb[cb], i)
        r2[cb] = np.nan
    valid = np.stack([np.ones_like(ta, dtype=bool), np.isfinite(r1), np.isfinite(r2)], axis=1)
    pstart = np.stack([ta, r1, r2], axis=1)[valid]
    c = np.nonzero(valid)[0]
    is_first = np.ones(c.shape[0], dtype=bool)
    is_first[1:] = c[1:] != c[:-1]
    is_last = np.ones(c.shape[0], dtype=bool)
    is_last[:-1] = c[1:] != c[:-1]
    pend = np.where(is_last, tb[c], np.append(pstart[1:], 0.0))
    ystart = np.where(is_first, seg.value_mm[lo:hi, i][c], poly(p0[c], v0[c], a0[c], jk[c], pstart))
    if bent.any():
        inner = np.flatnonzero(bent[c] & ~is_first)
        ystart[inner] = traj.states(ph[c[inner]], pstart[inner])[0][:, i]
    y_all = np.append(ystart, seg.value_mm[hi, i])
    n_all = spec.motor_steps(y_all)
    dn = np.diff(n_all)
    mv = np.flatnonzero(dn)
    if mv.size == 0:
        return None
    c, tau_a = c[mv], pstart[mv]
    return _Pieces(c, tau_a, pend[mv], np.abs(dn[mv]), np.sign(dn[mv]).astype(np.int8), n_all[mv], ystart[mv],
                   y_all[mv + 1], traj.t0_s[ph[c]] + tau_a, ph[c].astype(np.int32))


def axis_runs(traj: Trajectory, seg: Segments, lo: int, hi: int, i: int, spec: AxisPulseSpec) -> tuple[F64, I8, I32]:
    """Start time, direction and phase of each stepping piece of axis ``i`` in segments ``[lo, hi)``.

    The same runs as :func:`exact_axis_steps` returns (``run_t_s``, ``run_dir``, ``run_phase``),
    without solving for the step times.
    """
    pc = _pieces(traj, seg, lo, hi, i, spec)
    if pc is None:
        return np.zeros(0), np.zeros(0, np.int8), np.zeros(0, np.int32)
    return pc.t_abs, pc.direction, pc.phase


def exact_axis_steps(traj: Trajectory, seg: Segments, lo: int, hi: int, i: int, spec: AxisPulseSpec) -> RawSteps:
    """All steps of axis ``i`` over segments ``[lo, hi)``."""
    pc = _pieces(traj, seg, lo, hi, i, spec)
    if pc is None:
        return RawSteps.empty()
    ph = seg.phase[lo:hi]
    k = ph[pc.c]
    v0, a0, jj = traj.v0_mm_s[k, i], traj.a0_mm_s2[k, i], traj.j_mm_s3[k, i]
    tau_a, tau_e, counts, direction = pc.tau_a, pc.tau_e, pc.counts, pc.direction
    va = v0 + tau_a * (a0 + tau_a * jj / 2)
    aa = a0 + tau_a * jj
    length = tau_e - tau_a
    end_state = (pc.pe - pc.pa, v0 + tau_e * (a0 + tau_e * jj / 2), a0 + tau_e * jj)
    dirf = direction.astype(np.float64)
    d = _distances(spec, counts, direction, pc.na, pc.pa)
    ends = (end_state[0] * dirf, end_state[1] * dirf, end_state[2] * dirf)
    u = piece_times(d, counts, va * dirf, aa * dirf, jj * dirf, length, ends)
    bent = traj.curved[k]
    if bent.any():  # arcs: through their angles (curved.py)
        cb = np.flatnonzero(bent)
        first = np.cumsum(counts) - counts
        cc = counts[cb]
        idx = np.arange(int(cc.sum()), dtype=np.int64) + np.repeat(first[cb] - (np.cumsum(cc) - cc), cc)
        y = np.repeat(pc.pa, counts)[idx] + d[idx] * np.repeat(dirf, counts)[idx]
        u[idx] = curved_step_times(traj, k[cb], i, tau_a[cb], tau_e[cb], counts[cb], y)
    u += np.repeat(pc.t_abs, counts)
    return RawSteps(u, np.repeat(direction, counts), np.repeat(pc.phase, counts), pc.t_abs, direction, pc.phase,
                    np.cumsum(counts) - counts)


def _distances(spec: AxisPulseSpec, counts: I64, direction: I8, na: I64, pa: F64) -> F64:
    """Distance (direction frame, mm) from each piece start to each of its step boundaries."""
    total = int(counts.sum())
    first = np.cumsum(counts) - counts
    dirf = direction.astype(np.float64)
    if spec.pitch is None:
        h = spec.steps_den / spec.steps_num
        d0 = ((na + 0.5 * dirf) * h - pa) * dirf  # to the first boundary
        d = np.arange(total, dtype=np.float64)
        d *= h
        d += np.repeat(d0 - h * first, counts)
        return d
    off = np.arange(total, dtype=np.int64) - np.repeat(first, counts) + 1
    s_new = np.repeat(na, counts) + np.repeat(direction.astype(np.int64), counts) * off
    dir_steps = np.repeat(direction, counts)
    return (spec.boundary_mm(s_new, dir_steps) - np.repeat(pa, counts)) * dir_steps


# ---- queue.py (the compressor)
MAX_WINDOW = 0xFFFF
MIN_WINDOW = 32
QUADRATIC_DEV = 11  # Klipper: the largest deviation between two quadratic sequences, in units of e / count^2
ADD_MIN, ADD_MAX = -0x8000, 0x7FFF  # 'add' is a signed 16-bit field, as in Klipper
LONG_ENOUGH = 0x200  # a sequence this long is not improved by another 'add'


def _cdiv(n: int, d: int) -> int:
    return -((-n) // d)


def _bounds(rel_t: I64, e: int) -> tuple[I64, I64]:
    """Allowed reproduced times: ``[t - min(e, gap/2), t]`` (Klipper's ``minmax_point``)."""
    gap = np.diff(rel_t, prepend=0)
    return rel_t - np.minimum(gap // 2, e), rel_t


def _longest(minp: I64, maxp: I64, add: int, outer: tuple[int, int]) -> tuple[int, int, int, int]:
    """Longest prefix one ``(interval, count, add)`` reproduces, starting from the interval range ``outer``.

    Returns ``(count, interval, lo, hi)`` where ``lo, hi`` is the interval range after the
    first point that fails (``count == len`` when none does).
    """
    k = np.arange(1, minp.shape[0] + 1, dtype=np.int64)
    q = add * (k * (k - 1) // 2)
    low = -((q - minp) // k)  # ceil((minp - q) / k)
    if add < 0:  # the last interval, interval + add (count - 1), stays >= 1
        low = np.maximum(low, 1 - add * (k - 1))
    lo = np.maximum.accumulate(np.maximum(low, outer[0]))
    hi = np.minimum.accumulate(np.minimum((maxp - q) // k, outer[1]))
    bad = lo > hi
    c = int(np.argmax(bad)) if bad.any() else int(minp.shape[0])
    if c == minp.shape[0]:
        return c, int(hi[-1]), 0, 0
    return c, int(hi[c - 1]) if c else 0, int(lo[c]), int(hi[c])


def bisect_add(minp: I64, maxp: I64, e: int) -> tuple[int, int, int]:
    """One ``(interval, count, add)`` covering a prefix of the points: Klipper's ``compress_bisect_add``.

    Tries ``add = 0`` first, then bisects the range of ``add`` values that could still
    extend the sequence, using which side of its window the first failing point falls on.
    """
    outer_min, outer_max = max(int(minp[0]), 1), int(maxp[0])
    add, min_add, max_add = 0, ADD_MIN, ADD_MAX
    best = (0, 1, 1, -(1 << 62))  # interval, count, add, reach
    zero = (0, 0)
    n = minp.shape[0]
    while True:
        count, interval, next_lo, next_hi = _longest(minp, maxp, add, (outer_min, outer_max))
        if count == n:
            return interval, count, add
        reach = add * (count * (count - 1) // 2) + interval * count
        if reach > best[3] or (reach == best[3] and interval > best[0]):
            best = (interval, count, add, reach)
            if add == 0:
                zero = (interval, count)
            if count > LONG_ENOUGH:
                break
        nc = count + 1
        nf = nc * (nc - 1) // 2
        point_min, point_max = int(minp[count]), int(maxp[count])
        if add * nf + interval * nc < point_min:
            min_add, outer_max = add + 1, next_hi
        else:
            max_add, outer_min = add - 1, next_lo
        if count > 1:
            err = e * QUADRATIC_DEV // (count * count)
            min_add, max_add = max(min_add, add - err), min(max_add, add + err)
        min_add = max(min_add, _cdiv(point_min - outer_max * nc, nf))
        max_add = min(max_add, (point_max - outer_min * nc) // nf)
        if min_add > max_add or count == 0:
            break
        add = max_add - (max_add - min_add) // 4
    if zero[1] + zero[1] // 16 >= best[1]:
        return zero[0], zero[1], 0
    return best[0], best[1], best[2]


def compress_run(t: I64, last: int, e: int, final: bool) -> tuple[list[tuple[int, int, int]], int, int]:
    """Commands covering a prefix of ``t`` (one direction); returns (commands, new last, steps used).

    When not ``final``, a command whose run reaches the end of ``t`` is left for later
    (more steps may extend it).  The points are examined in growing windows (up to
    :data:`MAX_WINDOW`, Klipper's limit), so a short command does not cost a long scan.
    """
    cmds: list[tuple[int, int, int]] = []
    i = 0
    n = t.shape[0]
    window = MIN_WINDOW
    while i < n:
        while True:
            minp, maxp = _bounds(t[i:i + window] - last, e)
            iv, c, add = bisect_add(minp, maxp, e)
            if c < minp.shape[0] or i + window >= n or window >= MAX_WINDOW:
                break
            window *= 2
        if not final and i + c >= n:
            break
        if c == 0:  # cannot happen for increasing times; guard against a stall
            iv, c, add = max(int(t[i]) - last, 1), 1, 0
        cmds.append((iv, c, add))
        last += c * iv + add * (c * (c - 1) // 2)
        i += c
        window = max(MIN_WINDOW, min(MAX_WINDOW, 2 * c))
    return cmds, last, i
