"""Closed-form checks of the planner (expected values computed here, independently)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from cncc.diagnostics import DiagnosticSink
from cncc.ir.trajectory import Trajectory
from cncc.machines import effective_corner_rule, load_machine
from cncc.passes.plan import plan_commands
from cncc.passes.verify import verify_trajectory
from tests.passes._motion import arc, dwell, line, polyline, rapid

GENERIC = load_machine("generic-mill")
SZGH = load_machine("szgh-990mdb")
A_X, J_X = 1500.0, 50000.0  # generic-mill X axis


def plan(cmds: list, machine=GENERIC, level: int = 2) -> Trajectory:  # type: ignore[no-untyped-def]
    sink = DiagnosticSink()
    traj = plan_commands(cmds, machine, level, sink)
    report = verify_trajectory(traj, cmds, machine, sink, corner_rule=effective_corner_rule(machine, level),
                               check_dynamics=level > 0, jerk_limited=level >= 2)
    assert report.count == 0, [d.message for d in sink]
    return traj


def speed_at_boundary(traj: Trajectory, first_cmd_of_next: int) -> float:
    k = int(np.flatnonzero(traj.cmd_index == first_cmd_of_next)[0])
    return float(np.linalg.norm(traj.v0_mm_s[k]))


def test_line_nominal_trapezoid_and_s_curve() -> None:
    cmds = [line((10, 10), (110, 10), 3000)]  # 100 mm at 50 mm/s
    v, length = 50.0, 100.0
    assert plan(cmds, level=0).duration_total_s == pytest.approx(length / v)
    assert plan(cmds, level=1).duration_total_s == pytest.approx(length / v + v / A_X)
    assert plan(cmds, level=2).duration_total_s == pytest.approx(length / v + v / A_X + A_X / J_X)


def test_move_too_short_to_reach_feed() -> None:
    length = 0.5
    cmds = [line((10, 10), (10 + length, 10), 3000)]
    assert plan(cmds, level=1).duration_total_s == pytest.approx(2 * math.sqrt(length / A_X))
    # jerk-limited, acceleration not reached (L < 2 A^3 / J^2): four jerk phases of equal length
    assert length < 2 * A_X**3 / J_X**2
    assert plan(cmds, level=2).duration_total_s == pytest.approx(4 * (length / (2 * J_X)) ** (1 / 3), rel=1e-6)


def test_circle_at_centripetal_limit() -> None:
    r = 20.0
    cmds = [arc((50, 30), (50, 30), (30, 30), 1, 10000)]  # full circle, feed 166.7 mm/s
    traj = plan(cmds, level=2)
    speed = np.linalg.norm(traj.v0_mm_s, axis=1)
    v_c = math.sqrt(0.5 * A_X * r)  # half the acceleration may be centripetal (NORMAL_SHARE)
    assert v_c < 10000 / 60
    assert speed.max() <= v_c * (1 + 1e-6)
    assert speed.max() >= 0.9 * v_c
    nominal = plan(cmds, level=0).duration_total_s
    assert nominal == pytest.approx(2 * math.pi * r / (10000 / 60), rel=1e-3)


def _corner() -> list:  # type: ignore[type-arg]
    return [line((10, 10), (60, 10), 3000), line((60, 10), (60, 60), 3000)]


def test_corner_junction_deviation() -> None:
    traj = plan(_corner(), GENERIC, level=1)
    delta, a_j = GENERIC.junction_deviation_mm, A_X * math.sqrt(2)  # junction unit (1, 1)/sqrt 2
    s = math.sin(math.pi / 4)
    expected = math.sqrt(a_j * delta * s / (1 - s))
    assert speed_at_boundary(traj, 1) == pytest.approx(expected, rel=1e-9)


def test_corner_speed_step_szgh() -> None:
    traj = plan(_corner(), SZGH, level=1)
    assert speed_at_boundary(traj, 1) == pytest.approx(500 / 60, rel=1e-9)  # spec §5.5: 500 mm/min


def test_corner_exact_stop() -> None:
    machine = load_machine("generic-mill", {"corner_rule": "exact-stop"})
    traj = plan(_corner(), machine, level=1)
    assert speed_at_boundary(traj, 1) == pytest.approx(0.0, abs=1e-12)
    traj2 = plan(_corner(), machine, level=2)
    assert speed_at_boundary(traj2, 1) == pytest.approx(0.0, abs=1e-12)


def test_corner_blend_within_tolerance() -> None:
    turn = math.radians(12)  # a shallow corner: rounding it is faster than stopping
    end = (60 + 50 * math.cos(turn), 10 + 50 * math.sin(turn))
    traj = plan([line((10, 10), (60, 10), 3000), line((60, 10), end, 3000)], GENERIC, level=2)
    t = np.linspace(0, traj.duration_total_s, 20001)
    p, v, _, _ = traj.sample(t)
    dist = np.linalg.norm(p[:, :2] - np.array([60.0, 10.0]), axis=1)
    delta = GENERIC.blend_tolerance_mm
    assert 0.95 * delta <= dist.min() <= 1.05 * delta
    # passes the corner without stopping: at least the speed at which the curvature step into
    # the blend arc (radius from the tolerance) takes half of j T (docs/planning.md, -O2 step 4)
    radius = delta * math.cos(turn / 2) / (1 - math.cos(turn / 2))
    jerk_t = GENERIC.axes[1].max_jerk_mm_s3 * GENERIC.interpolation_period_s
    assert np.linalg.norm(v[np.argmin(dist)]) > 0.9 * math.sqrt(0.5 * jerk_t * radius)


def test_sharp_corner_stops_when_that_is_faster() -> None:
    # 90 degrees within 0.01 mm: the rounded corner is nearly a stop, so -O2 stops and
    # each side becomes ruckig's time-optimal rest-to-rest move: the exact-stop time.
    stop_machine = load_machine("generic-mill", {"corner_rule": "exact-stop"})
    t_stop = plan(_corner(), stop_machine, level=2).duration_total_s
    traj = plan(_corner(), GENERIC, level=2)
    assert speed_at_boundary(traj, 1) == pytest.approx(0.0, abs=1e-9)
    assert traj.duration_total_s == pytest.approx(t_stop, rel=1e-9)
    v, a, j = 50.0, A_X, J_X  # each 50 mm side: a 7-phase S-curve (reaches A and the feed)
    assert v / a > a / j
    side = 50 / v + v / a + a / j
    assert t_stop == pytest.approx(2 * side, rel=1e-6)


def test_dwell_forces_a_stop() -> None:
    cmds = [line((10, 10), (40, 10)), dwell(1.0), line((40, 10), (70, 10))]
    traj = plan(cmds, level=2)
    assert speed_at_boundary(traj, 2) == pytest.approx(0.0, abs=1e-12)
    single = plan([line((10, 10), (40, 10))], level=2).duration_total_s
    assert traj.duration_total_s == pytest.approx(2 * single)


def test_independent_axis_rapid() -> None:
    start, end = (0.0, 0.0, 0.0), (30.0, 10.0, -5.0)
    rate, acc, v_s = 4000 / 60, 50000 / 60, 500 / 60  # SZGH P1-P4, P18-P21, P101-P104
    cmds = [rapid(start, end)]
    assert plan(cmds, SZGH, 0).duration_total_s == pytest.approx(30.0 / rate)

    def axis_time(d: float) -> float:  # trapezoid from and to the take-off speed
        d_ramp = (rate**2 - v_s**2) / acc
        if d >= d_ramp:
            return 2 * (rate - v_s) / acc + (d - d_ramp) / rate
        vp = math.sqrt(v_s**2 + acc * d)
        return 2 * (vp - v_s) / acc

    traj = plan(cmds, SZGH, 1)
    assert traj.duration_total_s == pytest.approx(max(axis_time(30), axis_time(10), axis_time(5)))
    last = traj.phase_count - 1
    assert traj.v0_mm_s[last, 1] == 0.0 and traj.v0_mm_s[last, 2] == 0.0  # Y and Z arrived: a dog-leg
    assert plan(cmds, SZGH, 2).duration_total_s > traj.duration_total_s


def test_levels_are_ordered() -> None:
    square = polyline([(10, 10), (30, 10), (30, 30), (10, 30), (10, 10)])
    t0, t1, t2 = (plan(square, level=lv).duration_total_s for lv in (0, 1, 2))
    assert t0 < t1 and t0 < t2


def test_boundary_speeds_match_a_sequential_pass() -> None:
    from cncc.passes.planning.profile import boundary_speeds

    rng = np.random.default_rng(1)
    n = 200
    length, vcap, acap = rng.uniform(0.1, 5, n), rng.uniform(5, 100, n), rng.uniform(100, 2000, n)
    xcap = np.concatenate([[0.0], rng.uniform(0, 80, n - 1) ** 2, [0.0]])
    x = boundary_speeds(length, vcap, acap, xcap)
    ref = np.minimum(xcap, np.concatenate([[np.inf], vcap**2]))
    ref = np.minimum(ref, np.concatenate([vcap**2, [np.inf]]))
    for i in range(n):  # forward
        ref[i + 1] = min(ref[i + 1], ref[i] + 2 * acap[i] * length[i])
    for i in range(n - 1, -1, -1):  # backward
        ref[i] = min(ref[i], ref[i + 1] + 2 * acap[i] * length[i])
    np.testing.assert_allclose(x, ref, rtol=1e-9, atol=1e-9)


@pytest.mark.parametrize("vcaps", [(50.0,), (50.0, 12.0, 40.0), (8.0, 30.0, 30.0, 5.0), (200.0, 150.0)])
def test_topp_scan_matches_toppra(vcaps: tuple[float, ...]) -> None:
    """The min-plus TOPP of profile.py against toppra on the same 1-D problem.

    A piecewise-straight path with per-segment caps is, on its path coordinate, the
    problem toppra solves for a one-joint path q(s) = s with a speed cap varying along s.
    toppra discretises (it checks the caps at its grid points only); the scan is exact.
    The times agree within 0.5 %, the speeds away from the cap changes within 2 % of the
    largest cap.
    """
    import toppra as ta
    import toppra.algorithm as algo
    import toppra.constraint as constraint

    from cncc.passes.planning.profile import boundary_speeds, trapezoids

    ta.setup_logging("WARNING")
    a_max = 1500.0
    bounds = np.concatenate([[0.0], np.cumsum(np.linspace(6.0, 9.0, len(vcaps)))])
    vc = np.array(vcaps)

    def vlim(s: float) -> np.ndarray:  # at a cap change both caps hold
        lo = min(max(int(np.searchsorted(bounds, s - 1e-9, side="right")) - 1, 0), len(vcaps) - 1)
        hi = min(int(np.searchsorted(bounds, s + 1e-9, side="right")) - 1, len(vcaps) - 1)
        v = min(vc[lo], vc[hi])
        return np.array([[-v, v]])

    grid = np.unique(np.concatenate([np.linspace(0, bounds[-1], 1501), bounds]))
    path = ta.SplineInterpolator(bounds, bounds[:, None])
    inst = algo.TOPPRA([constraint.JointVelocityConstraintVarying(vlim),
                        constraint.JointAccelerationConstraint(np.array([[-a_max, a_max]]))], path,
                       gridpoints=grid)
    _, sd, _ = inst.compute_parameterization(0, 0)
    t_toppra = float(np.sum(2 * np.diff(grid) / (sd[1:] + sd[:-1])))
    xcap = np.full(len(vcaps) + 1, np.inf)
    xcap[0] = xcap[-1] = 0.0
    length, acap = np.diff(bounds), np.full(len(vcaps), a_max)
    x = boundary_speeds(length, vc, acap, xcap)
    t_scan = trapezoids(length, vc, acap, x, np.zeros(len(vcaps), np.int8), 0).end_time
    assert t_scan == pytest.approx(t_toppra, rel=5e-3)
    # the speed profiles agree at toppra's grid points
    k = np.clip(np.searchsorted(bounds, grid, side="right") - 1, 0, len(vcaps) - 1)
    fwd = np.sqrt(np.maximum(x[k] + 2 * a_max * (grid - bounds[k]), 0))
    bwd = np.sqrt(np.maximum(x[k + 1] + 2 * a_max * (bounds[k + 1] - grid), 0))
    ours = np.minimum(np.minimum(fwd, bwd), vc[k])
    away = np.min(np.abs(grid[:, None] - bounds[None, 1:-1]), axis=1, initial=np.inf) > 2 * (grid[1] - grid[0])
    assert np.max(np.abs(ours - sd)[away]) <= 0.02 * vc.max()


def test_o3_is_never_slower_than_o2_and_verifies() -> None:
    cmds = [line((10, 10), (20, 10), 6000), arc((20, 10), (25, 15), (20, 15), 1, 6000), line((25, 15), (25, 30), 6000)]
    t2 = plan(cmds, level=2).duration_total_s
    t3 = plan(cmds, level=3).duration_total_s  # plan() asserts zero verify violations
    assert t3 <= t2 * (1 + 1e-12)


@pytest.mark.parametrize("feed", [1e-21, 0.0, -5.0, 1e12])
def test_absurd_feeds_give_diagnostics_not_exceptions(feed: float) -> None:
    cmds = polyline([(10, 10), (11, 10), (11, 11)], feed)
    sink = DiagnosticSink()
    for level in range(4):
        traj = plan_commands(cmds, GENERIC, level, sink)
        assert np.all(np.isfinite(traj.duration_s)) and traj.duration_total_s > 0
        report = verify_trajectory(traj, cmds, GENERIC, sink, corner_rule=effective_corner_rule(GENERIC, level),
                                   check_dynamics=level > 0, jerk_limited=level >= 2)
        assert report.count == 0
    codes = {d.code for d in sink}
    assert codes & {"W0606", "E0604", "N0603"}


def test_narrow_filter_where_speeds_change_little() -> None:
    # 0.3 mm zig-zag at 9000 mm/min: the speed moves between close corner caps, where a
    # narrow jerk filter (less acceleration, shorter forced cruises) is the faster one
    from cncc.passes import plan as plan_mod
    from cncc.passes.planning import fir, windows

    cmds = polyline([(20 + 0.3 * i, 30 + 0.05 * (i % 3)) for i in range(30)], 9000)
    shares, steps, most = fir.TF_SHARES, fir.REFINE_STEPS, windows.MAX_SEGMENTS
    plan_mod.O2_PROFILE = "filter"  # the filter planner that -O3 starts from
    try:
        windows.MAX_SEGMENTS = 0  # the filter alone, without the ruckig re-planning
        t_best = plan(cmds, level=2).duration_total_s
        fir.TF_SHARES, fir.REFINE_STEPS = (1.0,), ()
        t_wide = plan(cmds, level=2).duration_total_s
    finally:
        fir.TF_SHARES, fir.REFINE_STEPS, windows.MAX_SEGMENTS = shares, steps, most
        plan_mod.O2_PROFILE = "scurve"
    assert t_best < 0.95 * t_wide


def _bang_bang(v_start: float, steps: list[tuple[float, float]]) -> object:
    """Phases from ``v_start`` through ``(acceleration, end speed or cruise time)`` steps."""
    from cncc.passes.planning.profile import Phases

    t, s, v = 0.0, 0.0, v_start
    rows = []
    for acc, target in steps:
        dur = target if acc == 0 else (target - v) / acc
        rows.append((t, dur, s, v, acc))
        s += v * dur + acc * dur**2 / 2
        v += acc * dur
        t += dur
    t0, d, s0, v0, a0 = (np.array(c, float) for c in zip(*rows, strict=True))
    return Phases(t0, d, s0, v0, a0, np.zeros_like(d), np.zeros(d.size, np.int8))


def test_short_peak_cut_at_higher_minimum_between_the_minima() -> None:
    # minima at 10 and 11 mm/s, a peak of 12 mm/s between them far shorter than Tf: the
    # cut is flat at 11 from minimum to minimum, so neither neighbouring peak is touched
    from cncc.passes.planning.fir import peak_cuts

    a, tf = 1000.0, 0.01
    ph = _bang_bang(0.0, [(a, 40.0), (-a, 10.0), (0, 0.05), (a, 12.0), (-a, 11.0), (0, 0.05), (a, 40.0),
                          (0, 0.2), (-a, 0.0)])
    cuts = peak_cuts(ph, tf)  # type: ignore[arg-type]
    s_end = ph.s0 + ph.v0 * ph.dur + ph.a0 * ph.dur**2 / 2  # type: ignore[attr-defined]
    row = cuts[np.argmin(np.abs(cuts[:, 2] - 11.0))]
    assert row[2] == pytest.approx(11.0)
    assert row[0] == pytest.approx(s_end[1])  # end of the braking to 10 mm/s
    assert row[1] == pytest.approx(ph.s0[6])  # type: ignore[attr-defined]  # start of the ramp to 40 mm/s
    assert (cuts[:, 2] >= 10.0).all()  # nothing is cut below a neighbouring minimum


def test_ruckig_replanning_never_slower_and_verified() -> None:
    # the same zig-zag: each segment's piece re-timed by ruckig between the vertex states
    from cncc.passes import plan as plan_mod
    from cncc.passes.planning import windows

    cmds = polyline([(20 + 0.3 * i, 30 + 0.05 * (i % 3)) for i in range(30)], 9000)
    machine = load_machine("generic-mill")
    most = windows.MAX_SEGMENTS
    plan_mod.O2_PROFILE = "filter"  # the filter planner that -O3 starts from
    try:
        replanned = plan_commands(cmds, machine, 2)
        windows.MAX_SEGMENTS = 0
        filtered = plan_commands(cmds, machine, 2)
    finally:
        windows.MAX_SEGMENTS = most
        plan_mod.O2_PROFILE = "scurve"
    assert replanned.duration_total_s < filtered.duration_total_s
    sink = DiagnosticSink()
    report = verify_trajectory(replanned, cmds, machine, sink, corner_rule=effective_corner_rule(machine, 2),
                               check_dynamics=True, jerk_limited=True)
    assert report.count == 0, [d.message for d in sink]
