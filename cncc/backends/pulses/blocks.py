"""Whole-trajectory bounds computed a block of phases at a time, so their temporaries stay small.

:func:`cncc.ir.trajectory.axis_bounds` and :func:`~cncc.ir.trajectory.position_bounds`
make a few dozen ``(n, m)`` temporaries: on a 200k-phase trajectory about 200 MB at
once.  :func:`blockwise` runs such a per-phase function on slices of
:data:`BLOCK_PHASES` phases (:func:`phase_slice`) and stacks the results, which are
the same row for row (each phase's bounds depend on that phase only).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import numpy.typing as npt

from cncc.ir.trajectory import PathLaw, Trajectory

F64 = npt.NDArray[np.float64]
BLOCK_PHASES = 16_384


def phase_slice(traj: Trajectory, a: int, b: int) -> Trajectory:
    """Phases ``[a, b)`` of ``traj`` (views; the path geometry is shared)."""
    law = traj.path
    if law is not None:
        law = PathLaw(law.seg[a:b], law.s0_mm[a:b], law.v_mm_s[a:b], law.a_mm_s2[a:b], law.j_mm_s3[a:b],
                      law.geometry)
    return Trajectory(traj.t0_s[a:b], traj.duration_s[a:b], traj.p0_mm[a:b], traj.v0_mm_s[a:b],
                      traj.a0_mm_s2[a:b], traj.j_mm_s3[a:b], traj.cmd_index[a:b], traj.limit[a:b], traj.axes, law)


def blockwise(fn: Callable[[Trajectory], tuple[F64, ...]], traj: Trajectory,
              size: int = BLOCK_PHASES) -> tuple[F64, ...]:
    """``fn(traj)`` for a per-phase ``fn`` returning ``(n, ...)`` arrays, computed ``size`` phases at a time."""
    n = traj.phase_count
    if n <= size:
        return fn(traj)
    parts = [fn(phase_slice(traj, a, min(a + size, n))) for a in range(0, n, size)]
    return tuple(np.concatenate([p[k] for p in parts]) for k in range(len(parts[0])))
