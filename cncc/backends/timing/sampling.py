"""How the HTML report reads a trajectory: samples at chosen times, and what ran then.

This is the only module of the report's pages that knows how a
:class:`~cncc.ir.trajectory.Trajectory` is laid out (``t0_s``, ``cmd_index``,
``limit`` per phase); everything else asks it for values at times through
:meth:`Trajectory.sample` and the lookups here.  If the planner's representation
changes, this module is the one to adapt.

* :func:`knot_times`: the times at which the motion law may change (phase starts and
  the end); speed extrema of a constant-jerk law lie on them or between them;
* :func:`at`: the command index and the limit in force at given times;
* :func:`command_starts`: the start time of every run of phases of one command.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import numpy as np
    import numpy.typing as npt

    from cncc.ir.trajectory import Trajectory

    F64 = npt.NDArray[np.float64]
    I64 = npt.NDArray[np.int64]


def knot_times(traj: Trajectory) -> F64:
    """Phase start times and the end time, ascending, shape ``(n + 1,)`` (empty without phases)."""
    import numpy as np

    if traj.phase_count == 0:
        return np.zeros(0)
    return np.append(np.asarray(traj.t0_s, dtype=np.float64), traj.duration_total_s)


def at(traj: Trajectory, t_s: F64) -> tuple[I64, I64]:
    """(command index, limit value) in force at each time of ``t_s`` (times past the end: the last phase)."""
    import numpy as np

    n = traj.phase_count
    if n == 0:
        z = np.zeros(len(t_s), dtype=np.int64)
        return z, z.copy()
    k = np.clip(np.searchsorted(traj.t0_s, t_s, side="right") - 1, 0, n - 1)
    return traj.cmd_index[k].astype(np.int64), traj.limit[k].astype(np.int64)


def command_starts(traj: Trajectory) -> tuple[F64, I64]:
    """(start time, command index) of each run of consecutive phases of one command."""
    import numpy as np

    if traj.phase_count == 0:
        return np.zeros(0), np.zeros(0, dtype=np.int64)
    ci = np.asarray(traj.cmd_index, dtype=np.int64)
    first = np.concatenate(([0], np.flatnonzero(ci[1:] != ci[:-1]) + 1))
    return np.asarray(traj.t0_s, dtype=np.float64)[first], ci[first]


def curve_times(traj: Trajectory, step_rad: float = 0.05) -> F64:
    """Times inside the curved phases (arcs, helices, blend arcs) at most ``step_rad`` of
    sweep apart, for drawing them (their phase knots alone would be long chords)."""
    import numpy as np

    bent = np.flatnonzero(traj.curved)
    if bent.size == 0 or traj.path is None:
        return np.zeros(0)
    law = traj.path
    s_end, _, _, _ = law.s_at(bent, traj.duration_s[bent])
    sweep = np.abs(law.geometry.kappa[law.seg[bent]] * (s_end - law.s0_mm[bent]))
    count = np.minimum(np.ceil(sweep / step_rad), 100_000).astype(np.int64)
    owner = np.repeat(np.arange(bent.size), count)
    first = np.cumsum(count) - count
    frac = (np.arange(owner.size) - first[owner] + 0.5) / np.maximum(count[owner], 1)
    # equal shares of time: the sweep is monotone in time within a phase
    out: F64 = traj.t0_s[bent][owner] + frac * traj.duration_s[bent][owner]
    return out
