"""The step solver beside the frozen reference (tests/backends/pulses_reference.py), axis by axis.

Shared by test_pulses_fast.py and test_pulses_mixed_reference.py: both cut the trajectory the
same way with both implementations, walk the same windows, and compare the steps of every axis.
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np
import numpy.typing as npt

from cncc.backends.pulses import solve
from cncc.backends.pulses.generate import _steps_per_mm, build_specs
from cncc.ir.trajectory import Trajectory
from cncc.machines import load_machine
from tests.backends import pulses_reference as ref


def axis_pairs(traj: Trajectory, budget: int) -> Iterator[tuple[str, int, float, solve.RawSteps, solve.RawSteps]]:
    """(axis name, column, steps per mm, new steps, reference steps) of every window and axis on
    generic-mill, after asserting that both cut the same segments and windows and that the steps
    have the same directions, phases and runs."""
    specs, cols = build_specs(traj, load_machine("generic-mill"), None)
    rate = _steps_per_mm(traj, specs, cols)
    seg, seg_ref = solve.segment(traj, rate, budget), ref.segment(traj, rate, budget)
    np.testing.assert_array_equal(seg.value_mm, seg_ref.value_mm)  # same positions at the segment ends
    wins = solve.windows(seg, budget)
    assert wins == ref.windows(seg_ref, budget)
    for lo, hi in wins:
        for spec, i in zip(specs, cols, strict=True):
            new = solve.exact_axis_steps(traj, seg, lo, hi, i, spec)
            old = ref.exact_axis_steps(traj, seg_ref, lo, hi, i, spec)
            np.testing.assert_array_equal(new.direction, old.direction)
            np.testing.assert_array_equal(new.phase, old.phase)
            np.testing.assert_array_equal(new.run_first, old.run_first)
            yield spec.name, i, float(rate[i]), new, old


def assert_same_ns(new_t_s: npt.NDArray[np.float64], old_t_s: npt.NDArray[np.float64], name: str) -> None:
    """The rounded nanoseconds are equal except where the reference sits within the two
    implementations' agreement of a half nanosecond."""
    ns_new, ns_old = np.rint(new_t_s * 1e9), np.rint(old_t_s * 1e9)
    tie = np.abs(old_t_s * 1e9 - np.floor(old_t_s * 1e9) - 0.5) < 1e-2
    assert np.all((ns_new == ns_old) | tie), name
