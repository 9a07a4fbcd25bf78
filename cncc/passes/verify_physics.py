"""Strict physics checks of ``verify`` that read a Trajectory only through its API.

Everything here uses ``traj.sample(t_s)``, ``traj.phase_count``, ``traj.duration_total_s``
and the phase boundary times ``t0_s`` / ``duration_s`` — never the per-axis row arrays —
so it judges any representation (per-axis cubic rows, or segment geometry with a time
law ``s(t)``).  The state just before a boundary ``t_b`` is ``sample(nextafter(t_b, -inf))``
(the previous phase evaluated one ulp before its end), the state after it ``sample(t_b)``.

* :func:`boundary_states` -- velocity and acceleration on both sides of every phase
  boundary, with rest before the start and after the end.
* :func:`velocity_steps_bad` -- strict velocity continuity (E0617 with
  ``strict_continuity``): a per-axis velocity step is allowed only where the machine
  declares one -- the SZGH speed-step corner rule (``max_speed_step_mm_min`` per axis),
  the take-off speed from or to rest and a stop through rest (``start_speed_mm_min``
  on both sides: one step down to rest, one step up from it) -- or where the plan's
  corner rule makes one (-O1's junction deviation, judged by the caller).  Everything
  else must be continuous to a floating-point slack.
* :func:`smeared_jerk_bad` -- the E0618 rule as the controller sees it: acceleration
  steps are spread over one interpolation period ``T`` (a moving average), so the
  averaged jerk ``(a(t) - a(t - T)) / T`` must stay within ``max_jerk`` at *every*
  ``t``, not only at each boundary alone (several steps inside one period add up).
  ``a(t) - a(t - T)`` is piecewise linear with breakpoints at the boundaries and the
  boundaries plus ``T``, so its extremes are among the one-sided limits there: exact.
* :func:`dense_extremes` -- per-phase maxima of ``|v|``, ``|a|``, ``|j|`` by dense
  sampling, for representations whose axes are not cubics within a phase (the caller
  uses the exact per-phase extremes when the rows are cubics).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from cncc.ir.trajectory import FloatArray, Trajectory

VEL_ABS_SLACK_MM_S = 1e-6  # floating point: a continuous plan's rows agree to ~1e-12
VEL_REL_SLACK = 1e-7
REL = 1e-6


@dataclass(frozen=True)
class Boundaries:
    """States on both sides of the ``n + 1`` boundaries (phase starts, then the end)."""

    t_s: FloatArray  # (n+1,)
    v_before: FloatArray  # (n+1, m)
    v_after: FloatArray
    a_before: FloatArray
    a_after: FloatArray


def _left(t: FloatArray) -> FloatArray:
    out: FloatArray = np.nextafter(t, -np.inf)
    return out


def boundary_states(traj: Trajectory) -> Boundaries:
    n = traj.phase_count
    t_b = np.append(np.asarray(traj.t0_s, float), traj.duration_total_s)
    _, v_r, a_r, _ = traj.sample(t_b)
    _, v_l, a_l, _ = traj.sample(_left(t_b))
    v_r, a_r, v_l, a_l = (np.array(x, float) for x in (v_r, a_r, v_l, a_l))
    v_l[0], a_l[0] = 0.0, 0.0  # rest before the start
    v_r[n], a_r[n] = 0.0, 0.0  # and after the end
    # a zero-duration phase has no interior: its start and end coincide with a neighbour's
    return Boundaries(t_b, v_l, v_r, a_l, a_r)


def velocity_steps_bad(b: Boundaries, step_mm_s: FloatArray, start_mm_s: FloatArray,
                       vmax_mm_s: FloatArray) -> np.ndarray:
    """Boundary flags (``n + 1``): a per-axis velocity step beyond what the machine declares.

    ``step_mm_s`` per axis is the declared corner step (0 when the machine declares
    none), ``start_mm_s`` the declared take-off speed.  A boundary is declared when every
    axis steps by at most ``step_mm_s`` (a corner), or when it is a stop: every axis runs
    at most at the take-off speed (or the corner step) on both sides, so that it stops in
    one declared step and starts in another (SZGH-990MDb §5.4: ramp down to the start
    speed, then stop in one step; motion starts at the start speed with no ramp; a stop
    from or to rest is the case with one side at rest)."""
    slack = VEL_ABS_SLACK_MM_S + VEL_REL_SLACK * vmax_mm_s[None, :]
    out: np.ndarray = ~steps_declared(b.v_before, b.v_after, step_mm_s, start_mm_s, slack)
    return out


def steps_declared(v_before: FloatArray, v_after: FloatArray, step_mm_s: FloatArray, start_mm_s: FloatArray,
                   slack: FloatArray | float) -> np.ndarray:
    """Per boundary (rows of ``v_before``/``v_after``): the velocity step is a declared corner
    step on every axis, or a stop through rest at the take-off speed (:func:`velocity_steps_bad`)."""
    corner = (np.abs(v_after - v_before) <= step_mm_s[None, :] * (1 + REL) + slack).all(axis=1)
    take_off = np.maximum(step_mm_s, start_mm_s)[None, :] * (1 + REL) + slack
    stop = ((np.abs(v_before) <= take_off) & (np.abs(v_after) <= take_off)).all(axis=1)
    out: np.ndarray = np.asarray(corner | stop)
    return out


def smeared_jerk_bad(traj: Trajectory, b: Boundaries, jmax_mm_s3: FloatArray, period_s: float,
                     chunk: int = 8192) -> np.ndarray:
    """Boundary flags (``n + 1``): ``|a(t) - a(t - T)| > jmax T`` at a breakpoint at or
    within one period after that boundary (``chunk`` boundaries at a time: bounded memory)."""
    t_b = b.t_s
    bad = np.zeros(t_b.size, bool)
    for lo in range(0, t_b.size, chunk):
        hi = min(t_b.size, lo + chunk)
        bad[lo:hi] = _smeared_chunk(traj, t_b[lo:hi], jmax_mm_s3, period_s)
    return bad


def _smeared_chunk(traj: Trajectory, t_b: FloatArray, jmax_mm_s3: FloatArray, period_s: float) -> np.ndarray:
    t_end = traj.duration_total_s
    # a(t) - a(t - T) at t = t_b (left and right) and at t = t_b + T (left and right)
    cand = np.concatenate([t_b, t_b + period_s])
    owner = np.concatenate([np.arange(t_b.size), np.arange(t_b.size)])

    def acc(t: FloatArray, side: str) -> FloatArray:
        tt = _left(t) if side == "left" else t
        inside = (tt >= 0) & (tt < t_end) if side == "right" else (tt > 0) & (tt <= t_end)
        _, _, a, _ = traj.sample(np.clip(tt, 0.0, t_end))
        out: FloatArray = np.where(inside[:, None], a, 0.0)
        return out

    limit = jmax_mm_s3[None, :] * period_s * (1 + REL) + 1e-6
    bad = np.zeros(t_b.size, bool)
    for side in ("left", "right"):
        g = acc(cand, side) - acc(cand - period_s, side)
        np.logical_or.at(bad, owner, (np.abs(g) > limit).any(axis=1))
    return bad


def dense_extremes(traj: Trajectory, per_phase: int = 16, chunk_phases: int = 1024,
                   phases: npt.NDArray[np.intp] | None = None) -> tuple[FloatArray, FloatArray, FloatArray]:
    """``(n, m)`` maxima of ``|v|``, ``|a|``, ``|j|`` over ``per_phase + 1`` samples of each phase
    (both ends by their one-sided limits), ``chunk_phases`` phases at a time (bounded memory).

    With ``phases`` (indices), only those phases are sampled and the rows are theirs, in order."""
    t0 = np.asarray(traj.t0_s, float)
    dur = np.asarray(traj.duration_s, float)
    if phases is not None:
        t0, dur = t0[phases], dur[phases]
    n = t0.size
    frac = np.linspace(0.0, 1.0, per_phase + 1)
    outs: list[list[FloatArray]] = [[], [], []]
    for lo in range(0, n, chunk_phases):
        hi = min(n, lo + chunk_phases)
        t = t0[lo:hi, None] + dur[lo:hi, None] * frac[None, :]
        t[:, -1] = np.maximum(_left(t0[lo:hi] + dur[lo:hi]), t0[lo:hi])  # the end of phase k, not the start of k + 1
        _, v, a, j = traj.sample(t.reshape(-1))
        shape = (hi - lo, per_phase + 1, v.shape[1])
        for dst, x in zip(outs, (v, a, j), strict=True):
            dst.append(np.abs(x).reshape(shape).max(axis=1))
    if n == 0:
        m = len(traj.axes)
        return np.zeros((0, m)), np.zeros((0, m)), np.zeros((0, m))
    return np.vstack(outs[0]), np.vstack(outs[1]), np.vstack(outs[2])
