"""Trajectories with known closed forms, built directly (no planner), for the pulse tests."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from cncc.ir.trajectory import Trajectory

Row = tuple[float, Sequence[float], Sequence[float]]  # duration, a0 per axis, j per axis


def build(rows: Sequence[tuple[float, Sequence[float], Sequence[float], Sequence[float]]],
          p_start: Sequence[float], axes: tuple[str, ...], cmd: Sequence[int] | None = None) -> Trajectory:
    """Contiguous phases from (duration, v0?, a0, j): positions and velocities are chained.

    Each row is ``(duration, v0_or_nan, a0, j)``; a NaN ``v0`` continues the previous
    phase's end velocity (so only the first row needs a velocity).
    """
    n, m = len(rows), len(axes)
    dur = np.array([r[0] for r in rows], dtype=np.float64)
    t0 = np.concatenate([[0.0], np.cumsum(dur)[:-1]])
    p0 = np.zeros((n, m))
    v0 = np.zeros((n, m))
    a0 = np.array([r[2] for r in rows], dtype=np.float64).reshape(n, m)
    jk = np.array([r[3] for r in rows], dtype=np.float64).reshape(n, m)
    p = np.array(p_start, dtype=np.float64)
    v = np.zeros(m)
    for k, r in enumerate(rows):
        given = np.array(r[1], dtype=np.float64)
        v = np.where(np.isnan(given), v, given)
        p0[k], v0[k] = p, v
        t = dur[k]
        p = p + v * t + a0[k] * t * t / 2 + jk[k] * t**3 / 6
        v = v + a0[k] * t + jk[k] * t * t / 2
    cmd_index = np.arange(n, dtype=np.int64) if cmd is None else np.array(cmd, dtype=np.int64)
    return Trajectory(t0, dur, p0, v0, a0, jk, cmd_index, np.zeros(n, np.int8), axes)


NAN = float("nan")


def constant_velocity(v_mm_s: float, t_s: float, p0: float = 0.0) -> Trajectory:
    return build([(t_s, [v_mm_s], [0.0], [0.0])], [p0], ("X",))


def trapezoid(dist_mm: float, v_mm_s: float, a_mm_s2: float) -> Trajectory:
    """Rest to rest: accelerate, cruise, decelerate."""
    ta = v_mm_s / a_mm_s2
    tc = dist_mm / v_mm_s - ta
    return build([(ta, [0.0], [a_mm_s2], [0.0]), (tc, [NAN], [0.0], [0.0]), (ta, [NAN], [-a_mm_s2], [0.0])],
                 [0.0], ("X",))


def s_curve(v_mm_s: float, a_mm_s2: float, j_mm_s3: float, cruise_s: float, sign: float = 1.0) -> Trajectory:
    """Seven-phase jerk-limited rest-to-rest move (reaches ``a`` and ``v``)."""
    tj = a_mm_s2 / j_mm_s3
    ta = v_mm_s / a_mm_s2 - tj
    s = sign
    rows = [
        (tj, [0.0], [0.0], [s * j_mm_s3]),
        (ta, [NAN], [s * a_mm_s2], [0.0]),
        (tj, [NAN], [s * a_mm_s2], [-s * j_mm_s3]),
        (cruise_s, [NAN], [0.0], [0.0]),
        (tj, [NAN], [0.0], [-s * j_mm_s3]),
        (ta, [NAN], [-s * a_mm_s2], [0.0]),
        (tj, [NAN], [-s * a_mm_s2], [s * j_mm_s3]),
    ]
    return build(rows, [0.0], ("X",))


def concat(*trajs: Trajectory) -> Trajectory:
    """Run trajectories one after the other (each continues from the previous end position)."""
    rows: list[tuple[float, list[float], list[float], list[float]]] = []
    for tr in trajs:
        for k in range(tr.phase_count):
            rows.append((float(tr.duration_s[k]), list(tr.v0_mm_s[k]), list(tr.a0_mm_s2[k]), list(tr.j_mm_s3[k])))
    return build(rows, list(trajs[0].p0_mm[0]), trajs[0].axes)


def phase_end_positions(traj: Trajectory) -> np.ndarray:
    """Position of every axis at the end of every phase, ``(n, m)``: the next phase's start."""
    n = traj.phase_count
    ends = np.empty_like(traj.p0_mm)
    ends[:-1] = traj.p0_mm[1:]
    ends[-1] = traj.end_state(n - 1)[0]
    return ends


def crossing_times_bisect(traj: Trajectory, axis: int, boundaries_mm: np.ndarray, phases: np.ndarray,
                          lo: np.ndarray, hi: np.ndarray, iters: int = 200) -> np.ndarray:
    """Independent reference: bisection on each phase's cubic for the boundary crossing (local time)."""
    p0 = traj.p0_mm[phases, axis]
    v0 = traj.v0_mm_s[phases, axis]
    a0 = traj.a0_mm_s2[phases, axis]
    j = traj.j_mm_s3[phases, axis]
    lo, hi = lo.astype(np.float64).copy(), hi.astype(np.float64).copy()
    f_lo = p0 + v0 * lo + a0 * lo**2 / 2 + j * lo**3 / 6 - boundaries_mm
    for _ in range(iters):
        mid = 0.5 * (lo + hi)
        f = p0 + v0 * mid + a0 * mid**2 / 2 + j * mid**3 / 6 - boundaries_mm
        same = np.sign(f) == np.sign(f_lo)
        lo = np.where(same, mid, lo)
        f_lo = np.where(same, f, f_lo)
        hi = np.where(same, hi, mid)
    return 0.5 * (lo + hi)
