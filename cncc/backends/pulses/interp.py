"""SZGH-style interpolation mode: pulses counted per period and spread evenly.

Consumes a :class:`~cncc.ir.trajectory.Trajectory` and produces :class:`RawSteps`
per window of interpolation periods, as the SZGH 990MDb's 2 ms interpolator does
(spec §5.1): at every period boundary ``t_k = k * period_s`` the commanded position
is sampled, the motor step count ``N(p(t_k))`` is taken (so fractional pulses carry
over and no rounding error accumulates), and the ``N_k - N_(k-1)`` pulses of
period ``k`` are spread evenly inside it, at ``t_(k-1) + (i + 1/2) period / count``.
A reversal inside one period shows only as the net count, as on the controller.
"""

from __future__ import annotations

import numpy as np

from cncc.backends.pulses.solve import F64, I8, I32, I64, RawSteps
from cncc.backends.pulses.spec import AxisPulseSpec
from cncc.ir.trajectory import Trajectory

SZGH_PERIOD_S = 0.002


def period_count(traj: Trajectory, period_s: float) -> int:
    """Number of periods covering the trajectory (the last one may be partial)."""
    return int(np.ceil(traj.duration_total_s / period_s - 1e-9)) if traj.phase_count else 0


def sample_positions(traj: Trajectory, t_s: F64) -> F64:
    """Commanded positions ``(q, m)`` at times ``t_s`` (clamped to the trajectory)."""
    k = np.clip(np.searchsorted(traj.t0_s, t_s, side="right") - 1, 0, traj.phase_count - 1)
    tau = np.clip(t_s - traj.t0_s[k], 0.0, traj.duration_s[k])
    return traj.states(k, tau)[0]  # exact on arcs too


def phase_at(traj: Trajectory, t_s: F64) -> F64:
    return np.clip(np.searchsorted(traj.t0_s, t_s, side="right") - 1, 0, traj.phase_count - 1)


def period_runs(traj: Trajectory, specs: tuple[AxisPulseSpec, ...], k0: int, k1: int,
                period_s: float) -> tuple[F64, I32, list[tuple[I64, I64, I8]]]:
    """Period start times ``(k1 - k0 + 1,)``, the phase at each period's middle ``(k1 - k0,)``, and
    per axis the periods that step (index from ``k0``), their pulse counts and directions."""
    t = np.arange(k0, k1 + 1, dtype=np.float64) * period_s
    pos = sample_positions(traj, t)
    mid_phase = phase_at(traj, t[:-1] + period_s / 2).astype(np.int32)
    out: list[tuple[I64, I64, I8]] = []
    for i, spec in enumerate(specs):
        dn = np.diff(spec.motor_steps(pos[:, i]))
        mv = np.flatnonzero(dn)
        out.append((mv, np.abs(dn[mv]), np.sign(dn[mv]).astype(np.int8)))
    return t, mid_phase, out


def interp_window(traj: Trajectory, specs: tuple[AxisPulseSpec, ...], k0: int, k1: int,
                  period_s: float) -> list[RawSteps]:
    """Steps of every axis for periods ``k0 .. k1 - 1`` (period ``k`` spans ``[k P, (k+1) P)``)."""
    t, mid_phase, runs = period_runs(traj, specs, k0, k1, period_s)
    out: list[RawSteps] = []
    for mv, counts, direction in runs:
        if mv.size == 0:
            out.append(RawSteps.empty())
            continue
        pidx = np.repeat(np.arange(mv.shape[0]), counts)
        off = np.arange(pidx.shape[0], dtype=np.int64) - np.repeat(np.cumsum(counts) - counts, counts)
        spacing = period_s / counts
        t_s = t[mv][pidx] + (off + 0.5) * spacing[pidx]
        phase = mid_phase[mv]
        out.append(RawSteps(t_s, direction[pidx], phase[pidx], t[mv], direction, phase,
                            np.cumsum(counts) - counts))
    return out
