"""-O2 on exact geometry (issue 14/26): arcs as one segment, every corner one blend arc (or a
biarc next to arcs), velocity continuous at every phase boundary — checked by sampling the
trajectory on both sides of each boundary, independently of the planner."""

from __future__ import annotations

import numpy as np

from cncc.diagnostics import DiagnosticSink
from cncc.machines import effective_corner_rule, load_machine
from cncc.passes.plan import plan_commands
from cncc.passes.verify import verify_trajectory
from tests.passes._motion import arc, line

GENERIC = load_machine("generic-mill")


def _plan(cmds: list) -> object:  # type: ignore[type-arg]
    sink = DiagnosticSink()
    traj = plan_commands(cmds, GENERIC, 2, sink)
    report = verify_trajectory(traj, cmds, GENERIC, sink, corner_rule=effective_corner_rule(GENERIC, 2),
                               check_soft_limits=False)
    assert report.count == 0, [d.message for d in sink]
    return traj


def _boundary_velocity_jumps(traj) -> np.ndarray:  # type: ignore[no-untyped-def]
    t_b = np.asarray(traj.t0_s[1:], float)
    _, v_after, _, _ = traj.sample(t_b)
    _, v_before, _, _ = traj.sample(np.nextafter(t_b, -np.inf))
    out: np.ndarray = np.abs(v_after - v_before).max(axis=1)
    return out


def test_a_full_circle_is_one_segment_on_the_circle() -> None:
    traj = _plan([arc((30, 10), (30, 10), (20, 10), 1, 3000)])
    assert traj.curved.all() and traj.phase_count <= 7  # one S-curve, no chords
    t = np.linspace(0, traj.duration_total_s, 5001)
    p, _, _, _ = traj.sample(t)
    assert np.allclose(np.hypot(p[:, 0] - 20, p[:, 1] - 10), 10.0, atol=1e-9)


def test_corners_of_lines_and_arcs_are_blended_without_velocity_steps() -> None:
    cmds = [line((0, 0), (10, 0), 3000), arc((10, 0), (20, 10), (10, 10), 1, 3000),  # tangent join
            line((20, 10), (20, 30), 3000),
            arc((20, 30), (10, 40), (10, 30), 1, 3000),  # tangent
            line((10, 40), (0, 50), 3000),  # 45 degree corner after an arc
            line((0, 50), (-7.660444, 56.427876), 3000)]  # 5 degree corner of two lines
    traj = _plan(cmds)
    jumps = _boundary_velocity_jumps(traj)
    assert jumps.max() < 1e-6  # no velocity step anywhere (blend machine, every corner blended)
    # the shallow corner of two lines at (0, 50) is passed within the blend tolerance, not through it
    t = np.linspace(0, traj.duration_total_s, 40001)
    p, v, _, _ = traj.sample(t)
    dist = np.hypot(p[:, 0] - 0.0, p[:, 1] - 50.0)
    assert GENERIC.blend_tolerance_mm * 0.9 <= dist.min() <= GENERIC.blend_tolerance_mm * 1.1
    assert np.linalg.norm(v[np.argmin(dist)]) > 1.0  # and without stopping
    # the corner after the arc at (10, 40): within the tolerance too (+ the arc tolerance)
    near = np.hypot(p[:, 0] - 10.0, p[:, 1] - 40.0).min()
    assert near <= GENERIC.blend_tolerance_mm + GENERIC.arc_tolerance_mm


def test_a_reversal_stops() -> None:
    traj = _plan([line((0, 0), (10, 0), 3000), line((10, 0), (0, 0), 3000)])
    jumps = _boundary_velocity_jumps(traj)
    assert jumps.max() < 1e-6
    t = np.linspace(0, traj.duration_total_s, 20001)
    p, v, _, _ = traj.sample(t)
    turn = np.argmax(p[:, 0])
    assert abs(p[turn, 0] - 10.0) < 1e-6  # the reversal point itself: nothing to blend
    assert np.linalg.norm(v[turn]) < 1e-3
