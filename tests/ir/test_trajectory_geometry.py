"""The trajectory's exact geometry (issue 14): arcs and helices sampled on the circle,
with the centripetal terms, checked against independent formulas and finite differences."""

from __future__ import annotations

import math

import numpy as np

from cncc.ir.trajectory import Geometry, Limit, PathLaw, Trajectory


def _circle_traj(r: float, v: float, a: float, dur: float, pitch_mm_per_rad: float = 0.0) -> Trajectory:
    """One phase on a circle (or helix) of radius r about (10, 20), starting at angle 0.3."""
    length = math.hypot(r, pitch_mm_per_rad) * 10.0  # 10 rad of sweep
    e1, e2, w = np.zeros((1, 6)), np.zeros((1, 6)), np.zeros((1, 6))
    e1[0, 0] = e2[0, 1] = 1.0
    w[0, 2] = pitch_mm_per_rad * 10.0 / length
    c = np.array([[10.0, 20.0, -1.0, 0, 0, 0]])
    geo = Geometry(c, e1, e2, w, np.array([r]), np.zeros(1), np.array([0.3]), np.array([10.0 / length]),
                   np.array([length]))
    law = PathLaw(np.zeros(1, np.int64), np.zeros(1), np.array([v]), np.array([a]), np.array([0.0]), geo)
    return Trajectory.on_path(np.zeros(1), np.array([dur]), np.zeros(1, np.int64),
                              np.full(1, Limit.FEED, np.int8), law)


def test_arc_positions_lie_on_the_circle_at_the_right_angle() -> None:
    r, v = 4.0, 30.0
    traj = _circle_traj(r, v, 0.0, 0.5)
    t = np.linspace(0, 0.5, 101)
    p, vel, acc, _ = traj.sample(t)
    ang = 0.3 + v * t / r  # independent: uniform motion on the circle
    assert np.allclose(p[:, 0], 10 + r * np.cos(ang), atol=1e-12)
    assert np.allclose(p[:, 1], 20 + r * np.sin(ang), atol=1e-12)
    assert np.allclose(np.linalg.norm(vel, axis=1), v)
    # centripetal: |a| = v^2 / r, pointing at the centre
    assert np.allclose(np.linalg.norm(acc, axis=1), v * v / r)
    to_centre = np.array([10.0, 20.0]) - p[:, :2]
    assert np.allclose(np.einsum("ij,ij->i", acc[:, :2], to_centre), v * v / r * r)
    assert traj.curved.tolist() == [True]


def test_helix_derivatives_match_finite_differences() -> None:
    traj = _circle_traj(3.0, 5.0, 40.0, 0.2, pitch_mm_per_rad=0.2 / (2 * math.pi))
    t = np.linspace(0.01, 0.19, 7)
    h = 1e-5
    p0, v0, a0, j0 = traj.sample(t)
    pp, vp, ap, _ = traj.sample(t + h)
    pm, vm, am, _ = traj.sample(t - h)
    assert np.allclose((pp - pm) / (2 * h), v0, atol=1e-6)
    assert np.allclose((vp - vm) / (2 * h), a0, atol=1e-4)
    assert np.allclose((ap - am) / (2 * h), j0, rtol=1e-5, atol=1e-2)
    # the path speed is the law's: v + a t
    assert np.allclose(np.linalg.norm(v0, axis=1), 5.0 + 40.0 * t)
    # Z descends linearly in s
    s = 5.0 * t + 20.0 * t * t
    length = math.hypot(3.0, 0.2 / (2 * math.pi)) * 10
    assert np.allclose(p0[:, 2], -1.0 + s * (0.2 / (2 * math.pi)) * 10 / length)


def test_start_and_end_states_are_exact_and_lines_are_cubics() -> None:
    traj = _circle_traj(2.0, 10.0, 0.0, 0.3)
    p, v, _, _ = traj.end_states()
    ang = 0.3 + 10.0 * 0.3 / 2.0
    assert np.allclose(p[0, :2], [10 + 2 * math.cos(ang), 20 + 2 * math.sin(ang)])
    assert np.allclose(v[0, :2], [-10 * math.sin(ang), 10 * math.cos(ang)])
    assert np.allclose(traj.p0_mm[0, :2], [10 + 2 * math.cos(0.3), 20 + 2 * math.sin(0.3)])
    # a line: the per-axis rows are the motion, equal to the geometry's
    u = np.array([[0.6, 0.8, 0, 0, 0, 0]])
    geo = Geometry.lines(np.array([[1.0, 2, 3, 0, 0, 0]]), u, np.array([5.0]))
    law = PathLaw(np.zeros(1, np.int64), np.array([1.0]), np.array([2.0]), np.array([3.0]), np.array([4.0]), geo)
    line = Trajectory.on_path(np.zeros(1), np.ones(1), np.zeros(1, np.int64), np.zeros(1, np.int8), law)
    assert not line.curved.any()
    t = np.linspace(0, 1, 5)
    s = 1 + 2 * t + 1.5 * t**2 + 4 * t**3 / 6
    p, vel, _, _ = line.sample(t)
    assert np.allclose(p, np.array([1.0, 2, 3, 0, 0, 0]) + s[:, None] * u)
    assert np.allclose(vel, (2 + 3 * t + 2 * t**2)[:, None] * u)
    sub = line.select_axes([1])
    assert np.allclose(sub.sample(t)[0][:, 0], p[:, 1])
