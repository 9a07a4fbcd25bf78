"""Exact step times: where the polynomial phases cross the step boundaries.

Consumes a :class:`~cncc.ir.trajectory.Trajectory` and an :class:`AxisPulseSpec`;
produces, per time window, the (float-second) time, direction and phase of every
step of one axis (:class:`RawSteps`).  No sampling: each step time is the root of
``p(tau) = boundary`` inside a monotone piece of a phase.

1. :func:`segment` cuts the phases into segments small enough that a window of
   them holds about ``budget`` steps (a 10^8-step cruise is cut into many), and
   evaluates every axis at the segment boundaries once, so that neighbouring
   segments share their end values exactly (the step count telescopes).
2. :func:`exact_axis_steps` splits each segment of one axis at its velocity zeros
   into monotone pieces, counts the boundaries each piece crosses from the step
   counts at its ends, and solves for all crossing times at once: closed form for
   constant-acceleration pieces, safeguarded Newton (bracketed, vectorised) where
   the jerk is non-zero.
3. Curved phases (arcs, helices on the trajectory's exact geometry) take the same
   route with their own turning points and boundary crossings, through angles
   (:mod:`.curved`); their segments are at most a few degrees of sweep.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from cncc.backends.pulses.blocks import BLOCK_PHASES, phase_slice
from cncc.backends.pulses.curved import (
    MAX_SEGMENT_SWEEP_RAD,
    all_positions,
    axis_positions,
    curved_step_times,
    turning_times,
)
from cncc.backends.pulses.roots import piece_times
from cncc.backends.pulses.spec import AxisPulseSpec
from cncc.ir.trajectory import Trajectory, axis_bounds

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
    bent: npt.NDArray[np.bool_] | None = None  # (S,) segments on curved phases (None: found from the phase)

    def curved(self, traj: Trajectory, lo: int, hi: int) -> npt.NDArray[np.bool_]:
        """Whether segments ``[lo, hi)`` lie on curved phases."""
        if self.bent is not None:
            return self.bent[lo:hi]
        out: npt.NDArray[np.bool_] = traj.curved[self.phase[lo:hi]]
        return out


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
    """Cut phases so that no segment holds more than about ``budget`` steps (a block of
    :data:`.blocks.BLOCK_PHASES` phases at a time, so the temporaries stay small)."""
    n = traj.phase_count
    parts = [_segment_block(phase_slice(traj, a, min(a + BLOCK_PHASES, n)), a, steps_per_mm, budget)
             for a in range(0, n, BLOCK_PHASES)]
    if n:
        end, _, _ = traj.end_state(n - 1)
        values = np.vstack([*(p[4] for p in parts), end[None, :]])
    else:
        values = np.zeros((1, len(traj.axes)))
    if not parts:
        z = np.zeros(0)
        return Segments(np.zeros(0, np.int64), z, z.copy(), z.copy(), values, np.zeros(0, bool))
    phase, ta, tb, est, _, bent = (np.concatenate([p[k] for p in parts]) for k in range(6))
    return Segments(phase, ta, tb, est, values, bent)


def _segment_block(traj: Trajectory, offset: int, steps_per_mm: F64, budget: int
                   ) -> tuple[I64, F64, F64, F64, F64, npt.NDArray[np.bool_]]:
    """:func:`segment` of the phases of ``traj`` (a slice starting at phase ``offset``): phase,
    start, end, estimated steps, start positions and curvedness of each segment."""
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
        values[cb] = all_positions(traj, k[cb], ta[cb])
    values = np.where((sub == 0)[:, None], traj.p0_mm[k], values)
    return phase + offset, ta, tb, (est / nsub)[phase], values, bent[phase]


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
    bent: npt.NDArray[np.bool_]  # on a curved phase


def _pieces(traj: Trajectory, seg: Segments, lo: int, hi: int, i: int, spec: AxisPulseSpec) -> _Pieces | None:
    """Split segments ``[lo, hi)`` of axis ``i`` at its velocity zeros; keep the pieces that step."""
    ph = seg.phase[lo:hi]
    p0, v0 = traj.p0_mm[ph, i], traj.v0_mm_s[ph, i]
    a0, jk = traj.a0_mm_s2[ph, i], traj.j_mm_s3[ph, i]
    ta, tb = seg.ta_s[lo:hi], seg.tb_s[lo:hi]
    r1, r2 = velocity_roots(v0, a0, jk, ta, tb)
    bent = seg.curved(traj, lo, hi)
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
        ystart[inner] = axis_positions(traj, ph[c[inner]], pstart[inner], i)
    y_all = np.append(ystart, seg.value_mm[hi, i])
    y_all = settle_tiny(y_all)
    n_all = spec.motor_steps(y_all)
    dn = np.diff(n_all)
    mv = np.flatnonzero(dn)
    if mv.size == 0:
        return None
    c, tau_a = c[mv], pstart[mv]
    return _Pieces(c, tau_a, pend[mv], np.abs(dn[mv]), np.sign(dn[mv]).astype(np.int8), n_all[mv], y_all[mv],
                   y_all[mv + 1], traj.t0_s[ph[c]] + tau_a, ph[c].astype(np.int32), bent[c])


SETTLE_MM = 1e-9  # a piece that moves less is rounding noise (phases join a few ulp apart)


def settle_tiny(y_all: F64) -> F64:
    """Piece boundary positions with sub-nanometre pieces folded into their neighbours.

    ``y_all`` (``q + 1``) holds the start of each of ``q`` monotone pieces and the end of the
    last.  Consecutive phases may join a few ulp apart, and a jerk phase that stops on a
    position may pass it by 1e-13 mm, so an axis standing exactly on a step boundary (a half
    step) could count a step it cannot make (no time solves it on a still piece: E0701 at
    1 GHz) or step there and back within microseconds.  A piece that moves at most
    :data:`SETTLE_MM` ends where it starts (forward), and a run of such pieces at the end of
    the range takes the range's end value (backward), so the neighbouring piece that really
    moves makes the step; the first and the last values, shared with the neighbouring
    ranges, never change, so the total count is kept.
    """
    q = y_all.shape[0] - 1
    tiny = np.abs(np.diff(y_all)) <= SETTLE_MM
    if not tiny.any():
        return y_all
    take = np.arange(q + 1, dtype=np.int64)
    fill = np.zeros(q + 1, dtype=bool)
    fill[1:q] = tiny[:q - 1]  # the end of a tiny piece (never the range's last value)
    take[fill] = 0
    np.maximum.accumulate(take, out=take)
    out: F64 = y_all[take]
    if tiny[-1]:
        moving = np.flatnonzero(~tiny)
        r = int(moving[-1]) + 1 if moving.size else 0  # first piece of the trailing tiny run
        if r > 0:
            out[r:q] = y_all[q]
    return out


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
    """All steps of axis ``i`` over segments ``[lo, hi)``.

    Straight pieces solve their own cubic (:func:`.roots.piece_times`); pieces on curved
    phases go through their angles (:func:`.curved.curved_step_times`); each step is solved once.
    """
    pc = _pieces(traj, seg, lo, hi, i, spec)
    if pc is None:
        return RawSteps.empty()
    counts, direction = pc.counts, pc.direction
    d = _distances(spec, counts, direction, pc.na, pc.pa)
    bent = pc.bent
    if bent.all():
        u = _curved(traj, seg, lo, pc, i, d)
    elif not bent.any():
        u = _straight(traj, seg, lo, pc, i, d)
    else:
        u = np.empty(d.shape[0])
        first = np.cumsum(counts) - counts
        for kind in (bent, ~bent):
            sel = np.flatnonzero(kind)
            cc = counts[sel]
            idx = np.arange(int(cc.sum()), dtype=np.int64) + np.repeat(first[sel] - (np.cumsum(cc) - cc), cc)
            part = _take(pc, sel)
            u[idx] = (_curved(traj, seg, lo, part, i, d[idx]) if kind is bent
                      else _straight(traj, seg, lo, part, i, d[idx]))
    u += np.repeat(pc.t_abs, counts)
    return RawSteps(u, np.repeat(direction, counts), np.repeat(pc.phase, counts), pc.t_abs, direction, pc.phase,
                    np.cumsum(counts) - counts)


def _take(pc: _Pieces, sel: I64) -> _Pieces:
    return _Pieces(pc.c[sel], pc.tau_a[sel], pc.tau_e[sel], pc.counts[sel], pc.direction[sel], pc.na[sel],
                   pc.pa[sel], pc.pe[sel], pc.t_abs[sel], pc.phase[sel], pc.bent[sel])


def _straight(traj: Trajectory, seg: Segments, lo: int, pc: _Pieces, i: int, d: F64) -> F64:
    """Local step times of pieces on straight phases: the roots of the axis' own cubic."""
    k = seg.phase[lo + pc.c]
    v0, a0, jj = traj.v0_mm_s[k, i], traj.a0_mm_s2[k, i], traj.j_mm_s3[k, i]
    tau_a, tau_e = pc.tau_a, pc.tau_e
    va = v0 + tau_a * (a0 + tau_a * jj / 2)
    aa = a0 + tau_a * jj
    dirf = pc.direction.astype(np.float64)
    ends = ((pc.pe - pc.pa) * dirf, (v0 + tau_e * (a0 + tau_e * jj / 2)) * dirf, (a0 + tau_e * jj) * dirf)
    return piece_times(d, pc.counts, va * dirf, aa * dirf, jj * dirf, tau_e - tau_a, ends)


def _curved(traj: Trajectory, seg: Segments, lo: int, pc: _Pieces, i: int, d: F64) -> F64:
    """Local step times of pieces on curved phases, through the boundaries' positions on the path."""
    k = seg.phase[lo + pc.c]
    y = d * np.repeat(pc.direction.astype(np.float64), pc.counts)
    y += np.repeat(pc.pa, pc.counts)
    return curved_step_times(traj, k, i, pc.tau_a, pc.tau_e, pc.counts, y)


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
