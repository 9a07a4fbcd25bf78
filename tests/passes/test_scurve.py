"""The closed-form S-curve of -O2 (planning/scurve.py) against ruckig and its own formulas."""

from __future__ import annotations

import math

import numpy as np
import pytest

from cncc.passes.planning import scurve


def _ruckig_time(v0: float, v1: float, dist: float, v_max: float, a_max: float, j_max: float) -> float:
    from ruckig import InputParameter, Result, Ruckig, Trajectory

    otg, inp, traj = Ruckig(1), InputParameter(1), Trajectory(1)
    inp.current_position, inp.current_velocity, inp.current_acceleration = [0.0], [v0], [0.0]
    inp.target_position, inp.target_velocity, inp.target_acceleration = [dist], [v1], [0.0]
    inp.max_velocity, inp.max_acceleration, inp.max_jerk = [v_max], [a_max], [j_max]
    assert otg.calculate(inp, traj) in (Result.Working, Result.Finished)
    return float(traj.duration)


@pytest.mark.parametrize(("v0", "v1", "a_max", "j_max"), [
    (0.0, 50.0, 1500.0, 50000.0),  # reaches A (three phases)
    (0.0, 10.0, 1500.0, 50000.0),  # does not reach A (two phases)
    (40.0, 3.0, 800.0, 30000.0),  # braking
    (5.0, 5.0, 1500.0, 50000.0),  # no change
])
def test_ramp_is_rucking_time_optimal_between_zero_accelerations(v0: float, v1: float, a_max: float,
                                                                  j_max: float) -> None:
    # ruckig from (0, v0, 0) to (d, v1, 0) with d the ramp's own distance: nothing faster exists
    d = float(scurve.ramp_distance(np.array(v0), np.array(v1), np.array(a_max), np.array(j_max)))
    t = float(scurve.ramp_time(np.array(v0), np.array(v1), np.array(a_max), np.array(j_max)))
    if v0 == v1:
        assert t == 0.0
        return
    assert t == pytest.approx(_ruckig_time(v0, v1, d, max(v0, v1) * 1.5, a_max, j_max), rel=1e-6)


@pytest.mark.parametrize(("v0", "length"), [(0.0, 0.001), (0.0, 3.0), (12.0, 0.01), (30.0, 5.0), (200.0, 1e-4)])
def test_reach_inverts_the_ramp_distance(v0: float, length: float) -> None:
    a_max, j_max = 1500.0, 50000.0
    v1 = scurve.reach(v0, length, a_max, j_max)
    d = float(scurve.ramp_distance(np.array(v0), np.array(v1), np.array(a_max), np.array(j_max)))
    assert d == pytest.approx(length, rel=1e-6)  # v1 - v0 loses digits when dv << v0


@pytest.mark.parametrize(("length", "v_max"), [(50.0, 50.0), (0.5, 50.0), (0.002, 50.0), (20.0, 166.0)])
def test_single_move_matches_ruckig_rest_to_rest(length: float, v_max: float) -> None:
    from cncc.passes.planning.segments import Segments

    a_max, j_max = 1500.0, 50000.0
    u = np.zeros((1, 6))
    u[0, 0] = 1.0
    seg = Segments(np.zeros((1, 6)), u, np.array([length]), np.array([0.0, length]), np.zeros(1, np.int64),
                   np.array([v_max]), np.zeros(1, np.int8), np.array([a_max]), np.array([j_max]),
                   np.array([0.0, 0.0]))
    ph = scurve.scurve_profile(seg)
    assert ph.end_time == pytest.approx(_ruckig_time(0.0, 0.0, length, v_max, a_max, j_max), rel=1e-6)
    assert ph.dur.size <= 7
    # continuity of s, v, a at every join and the end at rest at ``length``
    d = ph.dur
    s1 = ph.s0 + ph.v0 * d + ph.a0 * d**2 / 2 + ph.j * d**3 / 6
    v1 = ph.v0 + ph.a0 * d + ph.j * d**2 / 2
    a1 = ph.a0 + ph.j * d
    assert np.allclose(s1[:-1], ph.s0[1:], atol=1e-12) and s1[-1] == pytest.approx(length, rel=1e-12)
    assert np.allclose(v1[:-1], ph.v0[1:], atol=1e-9) and abs(v1[-1]) < 1e-9
    assert np.allclose(a1[:-1], ph.a0[1:], atol=1e-7) and abs(a1[-1]) < 1e-7
    assert np.all(np.abs(ph.a0) <= a_max * (1 + 1e-12)) and np.all(np.abs(ph.j) <= j_max)
    assert v1.max() <= v_max * (1 + 1e-12)
    if length == 50.0:  # the closed form L/v + v/A + A/J
        assert ph.end_time == pytest.approx(length / v_max + v_max / a_max + a_max / j_max, rel=1e-12)
    if length == 0.002:  # too short to reach A: 4 (L / 2J)^(1/3)
        assert ph.end_time == pytest.approx(4 * (length / (2 * j_max)) ** (1 / 3), rel=1e-9)
    assert math.isfinite(ph.end_time)


def test_phase_info_looks_up_command_and_limit_by_time() -> None:
    from cncc.ir.trajectory import Limit
    from cncc.machines import load_machine
    from cncc.passes.plan import plan_commands
    from tests.passes._motion import line

    cmds = [line((10, 10), (40, 10), 3000), line((40, 10), (40, 40), 600)]
    traj = plan_commands(cmds, load_machine("generic-mill"), 2)
    mid = traj.t0_s + traj.duration_s / 2
    cmd, lim = traj.phase_info(mid)
    assert cmd.tolist() == traj.cmd_index.tolist() and lim.tolist() == traj.limit.tolist()
    cmd_end, _ = traj.phase_info(np.array([traj.duration_total_s + 1.0]))
    assert cmd_end.tolist() == [1]
    assert int(Limit.FEED) in lim.tolist()


def test_tiny_zigzag_is_smoothed_within_tolerance() -> None:
    # 1000 moves of 0.01 mm zig-zagging by 2 um (issue 26): within the 0.01 mm blend
    # tolerance they are one straight 10 mm move; its ramps do not reach A (v/A < A/J),
    # each lasts 2 sqrt(v/J) and covers v sqrt(v/J), so the S-curve takes L/v + 2 sqrt(v/J)
    from cncc.diagnostics import DiagnosticSink
    from cncc.machines import effective_corner_rule, load_machine
    from cncc.passes.plan import plan_commands
    from cncc.passes.verify import verify_trajectory
    from tests.passes._motion import polyline

    machine = load_machine("generic-mill")
    pts = [(20 + 0.01 * i, 20 + 0.002 * (i % 2)) for i in range(1001)]
    cmds = polyline(pts, 2000)
    traj = plan_commands(cmds, machine, 2)
    sink = DiagnosticSink()
    report = verify_trajectory(traj, cmds, machine, sink, corner_rule=effective_corner_rule(machine, 2),
                               check_dynamics=True, jerk_limited=True)
    assert report.count == 0, [d.message for d in sink]
    length = math.hypot(10.0, 0.0)  # end points (20, 20) and (30, 20)
    v, a, j = 2000 / 60, 1500.0, 50000.0
    assert v / a < a / j
    straight = length / v + 2 * math.sqrt(v / j)
    assert straight * (1 - 1e-9) <= traj.duration_total_s <= 1.02 * straight
    # every sampled point within the tolerance of the zig-zag (its two lines y = 20 and 20.002)
    p, _, _, _ = traj.sample(np.linspace(0, traj.duration_total_s, 5001))
    assert np.all(p[:, 1] >= 20 - machine.blend_tolerance_mm)
    assert np.all(p[:, 1] <= 20.002 + machine.blend_tolerance_mm)


def test_planning_bar_on_a_terminal_only_and_not_with_quiet() -> None:
    import io

    from cncc.backends.timing.progress import PLAN_MIN_ITEMS, planning_bar

    class Tty(io.StringIO):
        def isatty(self) -> bool:
            return True

    for stream, quiet, drawn in ((Tty(), False, True), (Tty(), True, False), (io.StringIO(), False, False)):
        with planning_bar("planning -O2", PLAN_MIN_ITEMS, quiet, stream) as update:
            for k in range(0, PLAN_MIN_ITEMS + 1, PLAN_MIN_ITEMS // 4):
                update(k)
        assert (len(stream.getvalue()) > 0) is drawn
    small = Tty()
    with planning_bar("planning -O2", PLAN_MIN_ITEMS - 1, False, small) as update:
        update(1)
    assert small.getvalue() == ""


def test_coast_time_from_the_step_and_the_turning_jerk() -> None:
    # b = w^2 |dp''| / (j T) per axis, r = w^3 kappa^2 / j: c = T b / (1 - r), at most T
    jmax = np.array([50000.0, 50000.0, 30000.0, 1.0, 1.0, 1.0])
    period = 0.001
    jump = np.zeros((3, 6))
    jump[0, 0] = 1.0  # line -> arc of radius 1 along X: |dp''| = 1/mm
    jump[1, 1] = 0.5
    w = np.array([4.0, 4.0, 20.0])
    kappa = np.array([1.0, 0.5, 1.0])
    c = scurve.coast_times(w, jump, kappa, jmax, period)
    b0, r0 = 16.0 / 50.0, 64.0 / 50000.0
    b1, r1 = 8.0 / 50.0, 64.0 * 0.25 / 50000.0
    assert c[0] == pytest.approx(period * b0 / (1 - r0), rel=1e-12)
    assert c[1] == pytest.approx(period * b1 / (1 - r1), rel=1e-12)
    assert c[2] == 0.0  # no curvature jump: no coast


def _strict_jerk_codes(cmds: list, machine_name: str = "generic-mill") -> dict[str, int]:  # type: ignore[type-arg]
    from cncc.diagnostics import DiagnosticSink
    from cncc.machines import effective_corner_rule, load_machine
    from cncc.passes.plan import plan_commands
    from cncc.passes.verify import verify_trajectory

    machine = load_machine(machine_name)
    traj = plan_commands(cmds, machine, 2)
    report = verify_trajectory(traj, cmds, machine, DiagnosticSink(), corner_rule=effective_corner_rule(machine, 2),
                               check_dynamics=True, jerk_limited=True, check_soft_limits=False,
                               strict_continuity=True, strict_jerk=True)
    return report.counts


@pytest.mark.parametrize("kind", ["raster", "random walk", "0.01 mm", "arcs"])
def test_curvature_steps_keep_the_averaged_jerk(kind: str) -> None:
    # blend arcs and tangent arcs: the centripetal acceleration steps at their joints; with the
    # path's jerk of the neighbouring ramps inside the same period the step alone within j T is
    # not enough (E0618 under strict_jerk without the coasts)
    import sys
    from pathlib import Path

    from cncc.api import compile_commands

    sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bench"))
    from pathgen import KINDS

    cmds, _ = compile_commands(KINDS[kind](300), emit="timing")
    assert "E0618" not in _strict_jerk_codes(list(cmds))


def test_contour_example_keeps_the_averaged_jerk() -> None:
    from pathlib import Path

    from cncc.api import compile_commands

    text = (Path(__file__).resolve().parents[2] / "examples" / "contour.nc").read_text()
    cmds, _ = compile_commands(text, emit="timing")
    assert "E0618" not in _strict_jerk_codes(list(cmds))


def test_tangent_joint_speed_is_the_closed_form_curvature_step_cap() -> None:
    # a line into a tangent arc of radius r: the centripetal acceleration steps by v^2 / r on
    # the axis of the normal (Y); the joint is crossed at sqrt(b j_Y T r) (below the arc's
    # own caps sqrt(A r / 2) and (j r^2 / 4)^(1/3)), and both sides coast around it
    from cncc.machines import load_machine
    from cncc.passes.plan import plan_commands
    from tests.passes._motion import arc, line

    machine = load_machine("generic-mill")
    r, j_y, period = 2.0, 50000.0, machine.interpolation_period_s
    cmds = [line((0, 0), (20, 0), 6000.0), arc((20, 0), (22, 2), (20, 2), 1, 6000.0)]
    traj = plan_commands(cmds, machine, 2)
    law = traj.path
    assert law is not None
    k = int(np.flatnonzero(law.seg == law.seg.max())[0])  # the first phase on the arc
    from cncc.passes.planning.blending import TANGENT_STEP_SHARE as share

    # the joint speed: the step b = v^2 / (r j_Y T) within share * (1 - rho) with rho = v^3 / (r^2 j_Y)
    # the turning share, taken at the first estimate sqrt(share j_Y T r) (above the final speed)
    first = math.sqrt(share * j_y * period * r)
    expected = math.sqrt(share * (1 - first**3 / (r * r * j_y)) * j_y * period * r)
    assert expected < min(math.sqrt(0.5 * 1500.0 * r), (0.25 * j_y * r * r) ** (1 / 3))
    assert law.v_mm_s[k] == pytest.approx(expected, rel=1e-6)
    # the coasts: zero path jerk for c = T b / (1 - rho) on both sides, at most T
    b = expected**2 / r / (j_y * period)
    turn = expected**3 / (r * r) / j_y
    coast = period * b / (1 - turn)
    assert coast < period
    assert law.j_mm_s3[k] == 0.0 and law.j_mm_s3[k - 1] == 0.0
    assert traj.duration_s[k] == pytest.approx(coast, rel=1e-6)
    assert traj.duration_s[k - 1] == pytest.approx(coast, rel=1e-6)


# three tangent arcs of the 10k arc bench kind (lines 7765-7767 of bench/pathgen.py's arcs(10000)):
# the joint of the last two sits inside the block's acceleration ramp, where the centripetal step
# plus the ramp's own jerk within one period exceeded j T (E0618 under strict_jerk before the
# block was ended there)
THREE_ARCS = """G21 G90 G17 G94
G0 X158.1517 Y190.0863 Z5
G1 Z-1 F600
F2000
G2 X157.5530 Y191.5262 I4.0404 J2.5244
G2 X158.1194 Y192.3811 I1.9925 J-0.7050
G2 X159.8908 Y192.8556 I1.3426 J-1.4686
G0 Z5
M30
"""


def _averaged_jerk_excess(traj, machine, per_period: int = 40) -> float:  # type: ignore[no-untyped-def]
    """max over a dense grid (``per_period`` samples per period, over the whole motion) of
    ``|a(t) - a(t - T)| / (j_i T)``: an independent look at the averaged jerk, not at verify's
    sampled instants."""
    period = machine.interpolation_period_s
    jmax = np.array([machine.axis(n).max_jerk_mm_s3 if machine.axis(n) is not None else np.inf
                     for n in ("X", "Y", "Z", "A", "B", "C")])[: traj.p0_mm.shape[1]]
    t = np.arange(0.0, traj.duration_total_s, period / per_period)
    _, _, a, _ = traj.sample(t)
    _, _, a_prev, _ = traj.sample(np.clip(t - period, 0.0, None))
    a_prev = np.where((t - period < 0)[:, None], 0.0, a_prev)
    return float((np.abs(a - a_prev) / (jmax[None, :] * period)).max())


def test_curvature_step_inside_a_ramp_ends_a_block() -> None:
    from cncc.api import compile_commands
    from cncc.machines import load_machine
    from cncc.passes.plan import plan_commands
    from cncc.passes.planning import scurve

    cmds, _ = compile_commands(THREE_ARCS, emit="timing")
    assert "E0618" not in _strict_jerk_codes(list(cmds))
    machine = load_machine("generic-mill")
    motion = list(cmds)
    traj = plan_commands(motion, machine, 2)
    assert _averaged_jerk_excess(traj, machine) <= 1.0 + 1e-6
    # without the re-planning (no vertex inside a block is ever unsafe) the same path breaks it
    real = scurve.unsafe_steps
    try:
        scurve.unsafe_steps = lambda seg, starts, ph, cand, *a: cand[:0]  # type: ignore[assignment]
        loose = plan_commands(motion, machine, 2)
    finally:
        scurve.unsafe_steps = real  # type: ignore[assignment]
    assert _averaged_jerk_excess(loose, machine) > 1.0 + 1e-3
    assert loose.duration_total_s <= traj.duration_total_s * 1.02  # the ended block costs little


@pytest.mark.parametrize("kind", ["raster", "arcs"])
def test_vertices_declared_safe_keep_the_dense_averaged_jerk(kind: str) -> None:
    # every vertex left inside a block (the bound or the sampled check said safe) keeps the
    # averaged jerk within j T on a dense grid, not only at verify's instants
    import sys
    from pathlib import Path

    from cncc.api import compile_commands
    from cncc.machines import load_machine
    from cncc.passes.plan import plan_commands

    sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bench"))
    from pathgen import KINDS

    cmds, _ = compile_commands(KINDS[kind](120), emit="timing")
    machine = load_machine("generic-mill")
    traj = plan_commands(list(cmds), machine, 2)
    assert _averaged_jerk_excess(traj, machine, per_period=10) <= 1.0 + 1e-3
