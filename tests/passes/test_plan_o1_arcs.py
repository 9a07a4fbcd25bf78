"""Issue 14: -O1 plans arcs and helices on their path coordinate (one exact piece, as -O2),
not as chords; SZGH speed-step machines keep their chords (the controller model steps the
speed at chord vertices)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from cncc.diagnostics import DiagnosticSink
from cncc.ir.commands import Arc, Linear
from cncc.ir.frame import IDENTITY_FRAME, Plane
from cncc.machines import effective_corner_rule, load_machine
from cncc.passes.plan import plan_commands
from cncc.passes.verify import verify_trajectory
from cncc.source import NO_SPAN

C = (60.0, 60.0, -1.0, 0.0, 0.0, 0.0)
R = 10.0


def _helix(turns: int, feed: float, dz: float = -3.0) -> list[Arc | Linear]:
    start = (C[0] + R, C[1], -1.0, 0.0, 0.0, 0.0)
    end = (C[0] + R, C[1], -1.0 + dz, 0.0, 0.0, 0.0)
    lead = Linear(NO_SPAN, IDENTITY_FRAME, (C[0] + R - 5, C[1], -1.0, 0.0, 0.0, 0.0), start, feed)
    return [lead, Arc(NO_SPAN, IDENTITY_FRAME, start, end, C, turns, Plane.XY, feed)]


def _verify_count(cmds: list[Arc | Linear], machine_name: str) -> int:
    machine = load_machine(machine_name)
    traj = plan_commands(cmds, machine, 1)
    report = verify_trajectory(traj, cmds, machine, DiagnosticSink(), corner_rule=effective_corner_rule(machine, 1),
                               check_dynamics=True, jerk_limited=False, check_soft_limits=False,
                               strict_continuity=True)
    return report.count


def test_o1_helix_is_one_exact_piece_on_its_circle() -> None:
    cmds = _helix(3, 3000.0)
    traj = plan_commands(cmds, load_machine("generic-mill"), 1)
    arc_phases = np.flatnonzero(traj.cmd_index == 1)
    assert traj.curved[arc_phases].all()
    assert arc_phases.size <= 3  # a trapezoid on the path coordinate, not hundreds of chords
    t0, t1 = traj.t0_s[arc_phases[0]], traj.t0_s[arc_phases[-1]] + traj.duration_s[arc_phases[-1]]
    t = np.linspace(t0, t1, 2001)
    p, v, _, _ = traj.sample(t)
    radius = np.hypot(p[:, 0] - C[0], p[:, 1] - C[1])
    np.testing.assert_allclose(radius, R, atol=1e-9)  # on the true circle, no sagitta
    length = math.hypot(3 * 2 * math.pi * R, 3.0)
    assert t1 - t0 >= length / (3000.0 / 60.0) * (1 - 1e-9)  # never above the feed
    # the axial rate is the helix' pitch times the path speed
    speed = np.linalg.norm(v[:, :3], axis=1)
    np.testing.assert_allclose(v[:, 2], -3.0 / length * speed, atol=1e-6)


def test_o1_arc_keeps_every_axis_within_its_limits_and_verifies() -> None:
    machine = load_machine("generic-mill")
    cmds = _helix(2, 9000.0)  # fast enough for the centripetal caps to bind
    traj = plan_commands(cmds, machine, 1)
    t = np.linspace(0.0, traj.duration_total_s, 20001)
    _, v, a, _ = traj.sample(t)
    vmax = np.array([ax.max_velocity_mm_min / 60 for ax in machine.axes])
    amax = np.array([ax.max_accel_mm_s2 for ax in machine.axes])
    assert (np.abs(v[:, :3]) <= vmax[:3] * (1 + 1e-6)).all()
    assert (np.abs(a[:, :3]) <= amax[:3] * (1 + 1e-6)).all()
    # centripetal acceleration of the cruise: v^2 / r within the plane axes' acceleration
    speed = np.linalg.norm(v[:, :2], axis=1)
    assert speed.max() ** 2 / R <= min(amax[0], amax[1]) * (1 + 1e-6)
    assert _verify_count(cmds, "generic-mill") == 0


def test_o1_arc_time_close_to_the_chorded_plan() -> None:
    # the chords -O1 planned before and the exact arc: the same cruise, within a few percent
    import cncc.passes.planning.geometry as geometry

    cmds = _helix(2, 3000.0)
    machine = load_machine("generic-mill")
    exact = plan_commands(cmds, machine, 1)
    old = geometry.O1_NATIVE_ARCS
    try:
        geometry.O1_NATIVE_ARCS = False
        chords = plan_commands(cmds, machine, 1)
    finally:
        geometry.O1_NATIVE_ARCS = old
    assert exact.phase_count * 20 < chords.phase_count
    assert exact.duration_total_s == pytest.approx(chords.duration_total_s, rel=0.05)


def test_szgh_o1_keeps_chords() -> None:
    cmds = _helix(1, 3000.0)
    traj = plan_commands(cmds, load_machine("szgh-990mdb"), 1)
    assert not traj.curved.any()
    assert (traj.cmd_index == 1).sum() > 20
