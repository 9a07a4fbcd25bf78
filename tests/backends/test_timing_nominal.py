"""Nominal (-O0) trajectories: constant-velocity phases with length / feed times."""

from __future__ import annotations

import math

import numpy as np

from cncc.backends.nominal import nominal_timing, nominal_trajectory
from cncc.ir import IDENTITY_FRAME, Arc, Dwell, Linear, Plane, Rapid
from cncc.ir.machine import Axis, MachineModel, RapidMode
from cncc.ir.trajectory import Limit
from cncc.source import Span

SP = Span(0, 0, 1)


def v6(x: float = 0.0, y: float = 0.0, z: float = 0.0) -> tuple[float, float, float, float, float, float]:
    return (x, y, z, 0.0, 0.0, 0.0)


def machine(mode: RapidMode = RapidMode.INTERPOLATED) -> MachineModel:
    return MachineModel("m", (Axis("X", rapid_mm_min=6000.0), Axis("Y", rapid_mm_min=3000.0),
                              Axis("Z", rapid_mm_min=3000.0)), rapid_mode=mode)


def test_line_takes_length_over_feed() -> None:
    cmds = [Linear(SP, IDENTITY_FRAME, v6(), v6(30.0, 40.0), 600.0)]  # 50 mm at 10 mm/s
    t = nominal_trajectory(cmds, machine())
    assert t.phase_count == 1
    assert math.isclose(t.duration_total_s, 5.0)
    assert np.allclose(t.v0_mm_s[0, :2], [6.0, 8.0])
    assert t.limit[0] == Limit.FEED


def test_quarter_arc_time_and_end_point() -> None:
    # G02 from (10,0) to (0,-10) about the origin: a clockwise quarter of r = 10
    arc = Arc(SP, IDENTITY_FRAME, v6(10.0), v6(0.0, -10.0), v6(), -1, Plane.XY, 600.0)
    t = nominal_trajectory([arc], machine())
    assert math.isclose(t.duration_total_s, (math.pi * 10 / 2) / 10.0)
    assert t.phase_count == 9  # 90 degrees in chords of at most 10 degrees
    end, _, _ = t.end_state(t.phase_count - 1)
    assert np.allclose(end[:2], [0.0, -10.0])
    mid, _, _ = t.end_state(3)  # after 4 of 9 chords: 40 degrees clockwise from +X
    assert np.allclose(mid[:2], [10 * math.cos(math.radians(-40)), 10 * math.sin(math.radians(-40))])


def test_interpolated_rapid_is_one_straight_phase() -> None:
    cmds = [Rapid(SP, IDENTITY_FRAME, v6(), v6(10.0, 10.0))]
    t = nominal_trajectory(cmds, machine())
    assert t.phase_count == 1
    assert math.isclose(t.duration_total_s, 10 / 50.0)  # Y at 50 mm/s is the slowest axis


def test_independent_rapid_is_a_dog_leg() -> None:
    cmds = [Rapid(SP, IDENTITY_FRAME, v6(), v6(10.0, 10.0))]
    t = nominal_trajectory(cmds, machine(RapidMode.INDEPENDENT))
    assert t.phase_count == 2
    assert np.allclose(t.duration_s, [0.1, 0.1])  # X arrives after 10/100 s, Y after 10/50 s
    assert np.allclose(t.p0_mm[1, :2], [10.0, 5.0])
    assert np.allclose(t.v0_mm_s[1, :2], [0.0, 50.0])


def test_phases_are_contiguous_and_match_the_plain_sums() -> None:
    cmds = [Rapid(SP, IDENTITY_FRAME, v6(), v6(0, 0, 5.0)),
            Linear(SP, IDENTITY_FRAME, v6(0, 0, 5.0), v6(20.0, 0, 5.0), 1200.0),
            Dwell(SP, IDENTITY_FRAME, 1.5),
            Arc(SP, IDENTITY_FRAME, v6(20.0, 0, 5.0), v6(20.0, 0, 5.0), v6(30.0, 0, 5.0), 1, Plane.XY, 600.0)]
    t = nominal_trajectory(cmds, machine(RapidMode.INDEPENDENT))
    for k in range(t.phase_count - 1):
        p, _, _ = t.end_state(k)
        assert np.allclose(p, t.p0_mm[k + 1])
        assert math.isclose(t.t0_s[k] + t.duration_s[k], t.t0_s[k + 1])
    motion_s = nominal_timing(cmds, machine()).total_s - 1.5
    assert math.isclose(t.duration_total_s, motion_s)
    assert set(t.cmd_index.tolist()) == {0, 1, 3}  # the dwell is an event, not a phase
