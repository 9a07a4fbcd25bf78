"""One-dimensional profiles: a single move on the path coordinate or on one axis.

Consumes a distance and limits; produces :class:`Phases` (starting at ``s = 0``) or,
for independent-axis rapids, one :class:`AxisProfile` per axis.  The jerk-limited
profile comes from ruckig (time-optimal, 7 phases); the trapezoid from ``profile.py``;
the nominal one is a single constant-speed phase.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from cncc.ir.trajectory import FloatArray, Limit
from cncc.passes.planning.emit import AxisProfile
from cncc.passes.planning.profile import Phases, trapezoids


def empty_phases() -> Phases:
    z = np.zeros(0)
    return Phases(z, z, z, z, z, z, np.zeros(0, dtype=np.int8))


def ruckig_move(distance: float, v_max: float, a_max: float, j_max: float, limit: int) -> Phases | None:
    """Time-optimal jerk-limited rest-to-rest move of ``distance`` >= 0 (None if ruckig fails).

    Programs repeat the same move many times (drilling cycles, step-downs): the profile of
    each argument tuple is computed once (:func:`_cached_move`) and copied out."""
    if distance <= 1e-12:
        return empty_phases()
    if not all(math.isfinite(x) and x > 0 for x in (distance, v_max, a_max, j_max)):
        return None
    ph = _cached_move(distance, v_max, a_max, j_max, limit)
    if ph is None:
        return None
    return Phases(ph.t0.copy(), ph.dur.copy(), ph.s0.copy(), ph.v0.copy(), ph.a0.copy(), ph.j.copy(), ph.limit.copy())


@functools.lru_cache(maxsize=4096)
def _cached_move(distance: float, v_max: float, a_max: float, j_max: float, limit: int) -> Phases | None:
    from ruckig import InputParameter, Result, Ruckig, RuckigError, Trajectory

    inp = InputParameter(1)
    inp.current_position = [0.0]
    inp.target_position = [distance]
    inp.max_velocity = [v_max]
    inp.max_acceleration = [a_max]
    inp.max_jerk = [j_max]
    traj = Trajectory(1)
    try:
        result = Ruckig(1).calculate(inp, traj)
    except RuckigError:
        return None
    if result not in (Result.Working, Result.Finished):
        return None
    prof = traj.profiles[0][0]
    dur = np.array(prof.t, float)
    keep = dur > 1e-13
    a = np.array(prof.a[:-1], float)
    lim = np.where(np.abs(a) + np.abs(np.array(prof.j)) > 0, Limit.JERK, limit)
    return Phases(np.concatenate([[0.0], np.cumsum(dur)[:-1]])[keep], dur[keep], np.array(prof.p[:-1])[keep],
                  np.array(prof.v[:-1])[keep], a[keep], np.array(prof.j, float)[keep], lim[keep].astype(np.int8))


def trapezoid_move(distance: float, v_max: float, a_max: float, v_start: float, limit: int) -> Phases:
    """Trapezoid from and to ``v_start`` (an instant take-off/stop speed, SZGH)."""
    if distance <= 1e-12:
        return empty_phases()
    vs2 = min(v_start, v_max) ** 2
    return trapezoids(np.array([distance]), np.array([v_max]), np.array([a_max]), np.array([vs2, vs2]),
                      np.array([limit], dtype=np.int8), int(Limit.ACCEL))


def nominal_move(distance: float, v_max: float, limit: int) -> Phases:
    if distance <= 1e-12:
        return empty_phases()
    return Phases(np.zeros(1), np.array([distance / v_max]), np.zeros(1), np.array([v_max]), np.zeros(1),
                  np.zeros(1), np.array([limit], dtype=np.int8))


def axis_profile(ph: Phases, start: float, sign: float) -> AxisProfile:
    return AxisProfile(ph.t0, ph.dur, start + sign * ph.s0, sign * ph.v0, sign * ph.a0, sign * ph.j)


def independent_axes(start: FloatArray, end: FloatArray, level: int, rapid: FloatArray, accel: FloatArray,
                     jerk: FloatArray, take_off: FloatArray) -> list[AxisProfile]:
    """Each axis moves alone at its own rapid rate (dog-leg G00)."""
    out = []
    for i in range(start.shape[0]):
        d = float(end[i] - start[i])
        dist, sign = abs(d), (1.0 if d >= 0 else -1.0)
        if level <= 0:
            ph = nominal_move(dist, float(rapid[i]), int(Limit.RAPID))
        elif level == 1:
            ph = trapezoid_move(dist, float(rapid[i]), float(accel[i]), float(take_off[i]), int(Limit.RAPID))
        else:
            ph = jerk_limited_move(dist, float(rapid[i]), float(accel[i]), float(jerk[i]), int(Limit.RAPID))
        out.append(axis_profile(ph, float(start[i]), sign))
    return out


def jerk_limited_move(distance: float, v_max: float, a_max: float, j_max: float, limit: int) -> Phases:
    """ruckig's time-optimal move, or (should ruckig fail) the 7-phase filtered S-curve."""
    ph = ruckig_move(distance, v_max, a_max, j_max, limit)
    if ph is not None:
        return ph
    from cncc.passes.planning.fir import fir_profile
    from cncc.passes.planning.segments import Segments

    one, u = np.ones(1), np.zeros((1, 6))
    u[0, 0] = 1.0
    seg = Segments(np.zeros((1, 6)), u, one * distance, np.array([0.0, distance]), np.zeros(1, np.int64),
                   one * v_max, np.array([limit], np.int8), one * a_max, one * j_max, np.zeros(2))
    return fir_profile(seg)
