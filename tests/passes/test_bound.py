"""bench/bound.py: the independent lower bound is below every admissible motion (ruckig, an
LP, the planners) and adds up its terms as its docstring proves."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

from cncc.machines import load_machine
from cncc.passes.plan import plan_commands
from tests.passes._motion import arc, dwell, line

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench"))
import bound  # noqa: E402
from pathgen import KINDS  # noqa: E402

GENERIC = load_machine("generic-mill")
D_TOL = GENERIC.blend_tolerance_mm + GENERIC.arc_tolerance_mm  # (A3) of the bound


def _ruckig_s(dist: float, v: float, a: float, j: float, a_start: float = 0.0, a_end: float = 0.0) -> float:
    from ruckig import InputParameter, Result, Ruckig, Trajectory

    otg, inp, traj = Ruckig(1), InputParameter(1), Trajectory(1)
    inp.current_position, inp.current_velocity, inp.current_acceleration = [0.0], [0.0], [a_start]
    inp.target_position, inp.target_velocity, inp.target_acceleration = [dist], [0.0], [a_end]
    inp.max_velocity, inp.max_acceleration, inp.max_jerk = [v], [a], [j]
    assert otg.calculate(inp, traj) in (Result.Working, Result.Finished)
    return float(traj.duration)


def _leg(dist: float, v: float, a: float, j: float) -> float:
    return float(bound.leg_time_s(np.array([dist]), np.array([v]), np.array([a]), np.array([j]))[0])


def test_leg_time_closed_forms() -> None:
    # jerk only: a(t) = J T / 2 - J t covers J T^3 / 12; acceleration only: 2 sqrt(D / A);
    # long: cruise plus the two ramps at A from and to rest
    assert _leg(0.01, 1e9, 1e9, 50000.0) == pytest.approx((12 * 0.01 / 50000.0) ** (1 / 3), rel=1e-9)
    assert _leg(0.5, 1e9, 1500.0, math.inf) == pytest.approx(2 * math.sqrt(0.5 / 1500.0), rel=1e-9)
    assert _leg(100.0, 50.0, 1500.0, math.inf) == pytest.approx(100.0 / 50.0 + 50.0 / 1500.0, rel=1e-9)
    assert _leg(0.0, 50.0, 1500.0, 50000.0) == 0.0


@pytest.mark.parametrize(("dist", "v", "a", "j"), [
    (0.01, 50.0, 1500.0, 50000.0), (1.0, 50.0, 1500.0, 50000.0), (1.0, 250.0, 1500.0, 50000.0),
    (30.0, 50.0, 1500.0, 50000.0), (5.0, 133.0, 800.0, 30000.0), (200.0, 250.0, 3000.0, 20000.0)])
def test_leg_time_is_below_ruckig_for_any_end_accelerations(dist: float, v: float, a: float, j: float) -> None:
    # the legs leave the accelerations at the extremes free: below ruckig's optimum for every
    # start/end acceleration, and close to the best of them
    t = _leg(dist, v, a, j)
    times = [_ruckig_s(dist, v, a, j, alpha, -alpha) for alpha in np.linspace(0.0, a, 9)]
    assert t <= min(times) * (1 + 1e-9)
    assert t >= 0.85 * min(times)


def test_reach_is_an_upper_bound_of_a_linear_programme() -> None:
    # E(T) against the largest distance of a discretised motion: v(0) = v(T) = 0, |v| <= V,
    # |dv| <= A h, |d2v| <= J h^2 (an independent LP; scipy)
    from scipy.optimize import linprog

    v_max, a_max, j_max, n = 50.0, 1500.0, 50000.0, 400
    for t in (0.02, 0.06, 0.15, 0.5):
        h = t / n
        rows, rhs = [], []
        for k in range(n):  # first differences
            r = np.zeros(n + 1)
            r[k + 1], r[k] = 1.0, -1.0
            rows += [r, -r]
            rhs += [a_max * h] * 2
        for k in range(1, n):  # second differences
            r = np.zeros(n + 1)
            r[k + 1], r[k], r[k - 1] = 1.0, -2.0, 1.0
            rows += [r, -r]
            rhs += [j_max * h * h] * 2
        bounds = [(0.0, 0.0)] + [(-v_max, v_max)] * (n - 1) + [(0.0, 0.0)]
        res = linprog(-np.full(n + 1, h), A_ub=np.array(rows), b_ub=np.array(rhs), bounds=bounds, method="highs")
        assert res.status == 0
        lp = -res.fun
        e = float(bound.reach_mm(np.array([t]), np.array([v_max]), np.array([a_max]), np.array([j_max]))[0])
        assert e >= lp * (1 - 2e-3), (t, e, lp)  # an upper bound (up to the discretisation)
        assert e <= lp * 1.15, (t, e, lp)  # and not a loose one


def test_a_dwell_splits_the_run_into_two_rest_to_rest_moves() -> None:
    f = 6000.0
    straight = [line((0, 0), (10, 0), f), line((10, 0), (20, 0), f)]
    stopped = [straight[0], dwell(0.5), straight[1]]
    v = f / 60
    a, j = 1500.0, 50000.0  # X of generic-mill
    jerk_s, _ = bound.lower_bounds_s(straight, GENERIC)
    stop_s, _ = bound.lower_bounds_s(stopped, GENERIC)
    # the X chain: rest at (0 +- d), rest at (20 +- d); with the dwell also rest at (10 +- d)
    assert jerk_s == pytest.approx(max(_leg(20 - 2 * D_TOL, v, a, j), 20 / v), rel=1e-9)
    assert stop_s == pytest.approx(2 * max(_leg(10 - 2 * D_TOL, v, a, j), 10 / v), rel=1e-9)
    assert stop_s > jerk_s


def test_circle_term_when_the_centripetal_acceleration_binds() -> None:
    r, f = 2.0, 10000.0
    circle = [arc((12, 10), (12, 10), (10, 10), 1, f)]
    jerk_s, _ = bound.lower_bounds_s(circle, GENERIC)
    v, a_pl = f / 60, math.hypot(1500.0, 1500.0)
    phi = 2 * math.pi - 2 * math.asin(D_TOL / r)
    expected = (-v + math.sqrt(v * v + a_pl * (r - D_TOL) * phi * phi)) / a_pl
    assert jerk_s >= expected * (1 - 1e-9)
    assert expected > 2 * math.pi * r / v  # the centripetal term is the larger one here
    planned = plan_commands(circle, GENERIC, 2).duration_total_s
    assert jerk_s <= planned


def _planner_cmds(kind: str, n: int) -> list:  # type: ignore[type-arg]
    from cncc.api import compile_commands

    cmds, _ = compile_commands(KINDS[kind](n), emit="timing")
    return list(cmds)


@pytest.mark.parametrize("kind", sorted(KINDS))
def test_no_plan_is_faster_than_the_bound(kind: str) -> None:
    cmds = _planner_cmds(kind, 60)
    jerk_s, accel_s = bound.lower_bounds_s(cmds, GENERIC)
    assert 0 < accel_s <= jerk_s
    t1 = plan_commands(cmds, GENERIC, 1).duration_total_s
    t2 = plan_commands(cmds, GENERIC, 2).duration_total_s
    assert accel_s <= t1 * (1 + 1e-9), (accel_s, t1)  # -O1 has no jerk limit: the acceleration-only bound
    assert jerk_s <= t2 * (1 + 1e-9), (jerk_s, t2)


def test_corner_term_of_a_square_corner() -> None:
    # two 10 mm lines at 100 mm/s meeting at 90 degrees: between the visits of the two
    # midpoints (5 mm from the corner) the projection on the bisector w = (1, -1)/sqrt2 has
    # a maximum; each side brakes over 5 sin(45 deg) - 2 d with A_w = sqrt2 * 1500
    f = 6000.0
    corner = [line((0, 10), (10, 10), f), line((10, 10), (10, 0), f)]
    jerk_s, accel_s = bound.lower_bounds_s(corner, GENERIC)
    v, a_w = f / 60, math.sqrt(2) * 1500.0
    dist = 5 * math.sin(math.pi / 4) - 2 * D_TOL
    brake = math.sqrt(2 * dist / a_w) if dist <= v * v / (2 * a_w) else dist / v + v / (2 * a_w)
    # rest -> first midpoint and last midpoint -> rest add their feed terms 5 - 2 d each at v
    expected = 2 * brake + 2 * (5 - 2 * D_TOL) / v
    assert accel_s >= expected * (1 - 1e-9)
    assert jerk_s <= plan_commands(corner, GENERIC, 2).duration_total_s
    assert accel_s <= plan_commands(corner, GENERIC, 1).duration_total_s


@pytest.mark.parametrize(("tau", "gamma"), [(0.01, 0.0), (0.03, -1500.0), (0.03, 800.0), (0.06, -400.0), (0.2, 0.0)])
def test_half_reach_is_an_upper_bound_of_a_linear_programme(tau: float, gamma: float) -> None:
    # (6): from an extreme (speed 0) to a point where the acceleration towards the extreme is
    # gamma, |v| <= V, |v'| <= A, |v''| <= J: the largest distance of a discretised motion
    # (an independent LP; scipy) is below E(tau, gamma) and not far below
    from scipy.optimize import linprog

    v_max, a_max, j_max, n = 50.0, 1500.0, 50000.0, 300
    h = tau / n
    rows, rhs, eq_rows, eq_rhs = [], [], [], []
    for k in range(n):  # accelerations (v[k+1] - v[k]) / h within A
        r = np.zeros(n + 1)
        r[k + 1], r[k] = 1.0, -1.0
        rows += [r, -r]
        rhs += [a_max * h] * 2
    for k in range(1, n):  # jerks within J
        r = np.zeros(n + 1)
        r[k + 1], r[k], r[k - 1] = 1.0, -2.0, 1.0
        rows += [r, -r]
        rhs += [j_max * h * h] * 2
    r = np.zeros(n + 1)  # the last acceleration away from the extreme is -gamma
    r[n], r[n - 1] = 1.0, -1.0
    eq_rows.append(r)
    eq_rhs.append(-gamma * h)
    bounds = [(0.0, 0.0)] + [(-v_max, v_max)] * n
    weight = np.full(n + 1, h)
    weight[0] = weight[-1] = h / 2  # the trapezoid rule (the end speed is not zero)
    res = linprog(-weight, A_ub=np.array(rows), b_ub=np.array(rhs), A_eq=np.array(eq_rows),
                  b_eq=np.array(eq_rhs), bounds=bounds, method="highs")
    assert res.status == 0
    lp = -res.fun
    e = float(bound.half_reach_mm(np.array([tau]), np.array([gamma]), np.array([v_max]), np.array([a_max]),
                                  np.array([j_max]))[0])
    assert e >= lp * (1 - 3e-3) - 1e-9, (e, lp)
    assert e <= lp * 1.1 + 1e-6, (e, lp)


def test_half_leg_inverts_half_reach_and_grows_with_gamma() -> None:
    dist = np.array([0.3, 0.3, 0.3, 2.0])
    gam = np.array([-1500.0, 0.0, 1500.0, 0.0])
    v, a, j = np.full(4, 50.0), np.full(4, 1500.0), np.full(4, 50000.0)
    t = bound.half_leg_s(dist, gam, v, a, j)
    assert np.allclose(bound.half_reach_mm(t, gam, v, a, j), dist, rtol=1e-6)
    assert t[0] < t[1] < t[2]
    # gamma = -A: no jerk needed at the end, the braking bound sqrt(2 D / A)
    assert t[0] == pytest.approx(math.sqrt(2 * 0.3 / 1500.0), rel=1e-6)


def test_jerk_couples_the_corners_of_a_random_walk(monkeypatch: pytest.MonkeyPatch) -> None:
    # sharp corners 1 mm apart: at each middle one acceleration must push away from the last
    # corner and brake towards the next one, which the jerk limit spreads (6); the bound rises
    # above what (1)-(5) give and stays below -O2
    cmds = _planner_cmds("random walk", 100)
    with_jerk, accel_s = bound.lower_bounds_s(cmds, GENERIC)
    monkeypatch.setattr(bound, "_corner_chain_s", lambda *args: 0.0)
    without, _ = bound.lower_bounds_s(cmds, GENERIC)
    assert with_jerk > without * 1.02
    assert accel_s == pytest.approx(without, rel=1e-12)  # the acceleration-only bound has no (6)
    assert with_jerk <= plan_commands(cmds, GENERIC, 2).duration_total_s
