"""verify: catches each kind of injected violation and passes every plan."""

from __future__ import annotations

import numpy as np
import pytest

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink
from cncc.ir.trajectory import Trajectory
from cncc.machines import effective_corner_rule, load_machine
from cncc.passes.plan import plan_commands
from cncc.passes.verify import verify_trajectory
from tests.passes._motion import arc, dwell, line, polyline, rapid

GENERIC = load_machine("generic-mill")

PROGRAMS = {
    "square": polyline([(10, 10), (30, 10), (30, 30), (10, 30), (10, 10)]),
    "circle": [arc((40, 30), (40, 30), (30, 30), 1, 2000)],
    "zigzag": polyline([(10 + 2 * i, 10 + 5 * (i % 2)) for i in range(12)], 4000),
    "fine": polyline([(30 + 10 * np.cos(t), 30 + 10 * np.sin(t)) for t in np.linspace(0, 3, 60)], 5000),
    "mixed": [rapid((0, 0, 0), (10, 10, -1)), line((10, 10, -1), (40, 10, -1)), dwell(0.5),
              line((40, 10, -1), (40, 40, -2)), arc((40, 40, -2), (20, 40, -2), (30, 40, -2), 1),
              rapid((20, 40, -2), (0, 0, 0))],
}


def _plan(name: str, machine_name: str, level: int) -> tuple[Trajectory, list, object]:  # type: ignore[type-arg]
    wide = {f"axes.{a}.soft_{e}_mm": v for a in "XYZ" for e, v in (("min", -1000.0), ("max", 1000.0))}
    machine = load_machine(machine_name, wide)  # the programs sit in +X +Y; SYNTEC works in -X -Y
    cmds = PROGRAMS[name]
    return plan_commands(cmds, machine, level), cmds, machine


@pytest.mark.parametrize("machine_name", ["generic-mill", "szgh-990mdb", "syntec-900m"])
@pytest.mark.parametrize("level", [0, 1, 2])
@pytest.mark.parametrize("name", sorted(PROGRAMS))
def test_verify_passes_planner_output(name: str, machine_name: str, level: int) -> None:
    traj, cmds, machine = _plan(name, machine_name, level)
    sink = DiagnosticSink()
    report = verify_trajectory(traj, cmds, machine, sink, corner_rule=effective_corner_rule(machine, level),  # type: ignore[arg-type]
                               check_dynamics=level > 0, jerk_limited=level >= 2)
    assert report.count == 0, [d.message for d in sink]


def _one_phase(v: float = 10.0, a: float = 0.0, j: float = 0.0, p: tuple[float, float] = (10.0, 10.0),
               dur: float = 0.1) -> Trajectory:
    z = np.zeros((1, 6))
    p0, v0, a0, jj = z.copy(), z.copy(), z.copy(), z.copy()
    p0[0, :2] = p
    v0[0, 0], a0[0, 0], jj[0, 0] = v, a, j
    return Trajectory(np.zeros(1), np.array([dur]), p0, v0, a0, jj, np.zeros(1, np.int64), np.zeros(1, np.int8))


def _codes(traj: Trajectory, cmds: list, **kw: object) -> set[str]:  # type: ignore[type-arg]
    sink = DiagnosticSink()
    verify_trajectory(traj, cmds, GENERIC, sink, **kw)  # type: ignore[arg-type]
    return {d.code for d in sink}


def _line_for(traj: Trajectory, feed: float = 60000.0) -> list:  # type: ignore[type-arg]
    p, _, _ = traj.end_state(traj.phase_count - 1)
    return [line(tuple(traj.p0_mm[0, :3]), tuple(p[:3]), feed)]


def test_catches_velocity() -> None:
    traj = _one_phase(v=400.0)  # X limit 250 mm/s
    assert dg.VERIFY_VELOCITY in _codes(traj, _line_for(traj))


def test_catches_accel_and_jerk() -> None:
    traj = _one_phase(v=0.0, a=2000.0, dur=0.01)
    assert dg.VERIFY_ACCEL in _codes(traj, _line_for(traj))
    traj = _one_phase(v=0.0, j=60000.0, dur=0.01)
    assert dg.VERIFY_JERK in _codes(traj, _line_for(traj))


def test_catches_feed() -> None:
    traj = _one_phase(v=50.0)
    assert dg.VERIFY_FEED in _codes(traj, _line_for(traj, feed=1200.0))


def test_catches_path_deviation() -> None:
    traj = _one_phase(v=10.0)
    cmds = [line((10, 10.5), (11, 10.5), 60000)]  # programmed 0.5 mm away
    assert dg.VERIFY_PATH in _codes(traj, cmds)


def test_catches_soft_limit() -> None:
    traj = _one_phase(v=-100.0, p=(1.0, 10.0), dur=0.1)  # X goes to -9, soft min -1
    assert dg.VERIFY_SOFT_LIMIT in _codes(traj, _line_for(traj))


def test_catches_continuity_and_corner() -> None:
    good, cmds, machine = _plan("square", "generic-mill", 2)
    p0 = good.p0_mm.copy()
    p0[5] += 0.01
    broken = Trajectory(good.t0_s, good.duration_s, p0, good.v0_mm_s, good.a0_mm_s2, good.j_mm_s3,
                        good.cmd_index, good.limit)
    assert dg.VERIFY_CONTINUITY in _codes(broken, cmds)
    v0 = good.v0_mm_s.copy()
    k = int(np.argmax(np.linalg.norm(v0, axis=1)))
    v0[k] = v0[k][[1, 0, 2, 3, 4, 5]]  # turn the velocity by 90 degrees at full speed
    turned = Trajectory(good.t0_s, good.duration_s, good.p0_mm, v0, good.a0_mm_s2, good.j_mm_s3,
                        good.cmd_index, good.limit)
    assert dg.VERIFY_CORNER in _codes(turned, cmds, corner_rule=effective_corner_rule(machine, 2))  # type: ignore[arg-type]


def _two_phases(a_second: float) -> Trajectory:
    """X moves at 10 mm/s for 10 ms, then keeps going with acceleration ``a_second``."""
    z = np.zeros((2, 6))
    p0, v0, a0 = z.copy(), z.copy(), z.copy()
    p0[:, :2] = [[10.0, 10.0], [10.1, 10.0]]
    v0[:, 0] = 10.0
    a0[1, 0] = a_second
    return Trajectory(np.array([0.0, 0.01]), np.array([0.01, 0.001]), p0, v0, a0, z.copy(),
                      np.zeros(2, np.int64), np.zeros(2, np.int8))


def test_catches_acceleration_step() -> None:
    jt = 50000.0 * GENERIC.interpolation_period_s  # X jerk limit times one period: 50 mm/s^2
    assert jt == pytest.approx(50.0)
    bad = _two_phases(4 * jt)  # steps 0 -> 200 at t = 10 ms (and 200 -> 0 at the end)
    ok = _two_phases(jt / 2)
    cmds = _line_for(bad)
    assert dg.VERIFY_ACCEL_STEP in _codes(bad, cmds)
    assert dg.VERIFY_ACCEL_STEP not in _codes(bad, cmds, jerk_limited=False)  # trapezoids step by design
    assert dg.VERIFY_ACCEL_STEP not in _codes(ok, _line_for(ok))


def test_catches_a_point_outside_the_arc_sweep() -> None:
    quarter = [arc((40, 30), (30, 40), (30, 30), 1, 60000)]  # counter-clockwise, 0 .. 90 degrees
    on_circle_outside = _one_phase(v=0.001, p=(20.0, 30.0), dur=0.001)  # 180 degrees: radial error 0
    assert dg.VERIFY_PATH in _codes(on_circle_outside, quarter)
    c45 = 30 + 10 * np.cos(np.pi / 4)
    inside = _one_phase(v=0.0, p=(c45, c45), dur=0.001)
    assert dg.VERIFY_PATH not in _codes(inside, quarter)
    clockwise = [arc((40, 30), (30, 40), (30, 30), -1, 60000)]  # the other 270 degrees
    assert dg.VERIFY_PATH not in _codes(on_circle_outside, clockwise)
    assert dg.VERIFY_PATH in _codes(inside, clockwise)
