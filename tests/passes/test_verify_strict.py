"""verify{strict_continuity}: velocity continuity except declared steps, the averaged jerk,
and the API-only checks of ``verify_physics`` -- each with an injected violation."""

from __future__ import annotations

import math

import numpy as np
import pytest

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink
from cncc.ir.machine import CornerRule, MachineModel
from cncc.ir.trajectory import FloatArray, Trajectory
from cncc.machines import load_machine
from cncc.passes import verify_physics as vp
from cncc.passes.verify import verify_trajectory
from tests.passes._motion import line

GENERIC = load_machine("generic-mill")
SZGH = load_machine("szgh-990mdb")
X_ACCEL, X_JERK = 1500.0, 50000.0  # generic-mill.toml, axis X
PERIOD = 0.001  # generic-mill.toml interpolation_period_s


def _traj(phases: list[tuple[float, tuple[float, float], tuple[float, float], tuple[float, float]]],
          p_start: tuple[float, float] = (100.0, 100.0)) -> Trajectory:
    """Phases ``(duration, v0 (x, y), a0 (x, y), j (x, y))`` laid end to end; the start
    position of each phase is the exact end of the one before (continuous position)."""
    n = len(phases)
    t0, dur = np.zeros(n), np.array([p[0] for p in phases])
    p0, v0, a0, jj = (np.zeros((n, 6)) for _ in range(4))
    pos = np.array([*p_start, 0.0, 0.0, 0.0, 0.0])
    t = 0.0
    for k, (d, v, a, j) in enumerate(phases):
        t0[k] = t
        p0[k] = pos
        v0[k, :2], a0[k, :2], jj[k, :2] = v, a, j
        pos = pos + v0[k] * d + a0[k] * d * d / 2 + jj[k] * d**3 / 6
        t += d
    return Trajectory(t0, dur, p0, v0, a0, jj, np.zeros(n, np.int64), np.zeros(n, np.int8))


def _codes(traj: Trajectory, machine: MachineModel = GENERIC, **kw: object) -> dict[str, int]:
    sink = DiagnosticSink()
    p_end, _, _ = traj.end_state(traj.phase_count - 1)
    cmds = [line(tuple(traj.p0_mm[0, :3]), tuple(p_end[:3]), 60000.0)]
    report = verify_trajectory(traj, cmds, machine, sink, check_path=False, check_soft_limits=False,  # type: ignore[arg-type]
                               **kw)
    return report.counts


def _chord_vertex(speed: float, turn_deg: float) -> Trajectory:
    """From rest to ``speed`` along X, the direction turned by ``turn_deg`` (a chord vertex),
    back to rest: continuous velocity except at the vertex."""
    c, s, d = math.cos(math.radians(turn_deg)), math.sin(math.radians(turn_deg)), 0.05
    return _traj([(d, (0.0, 0.0), (speed / d, 0.0), (0.0, 0.0)),
                  (d, (speed * c, speed * s), (-speed * c / d, -speed * s / d), (0.0, 0.0))])


def test_chord_vertex_step_is_accepted_smeared_but_caught_strict() -> None:
    # 20 mm/s turned by 1.5 degrees: a per-axis step of 20 * sin(1.5 deg) = 0.52 mm/s, below
    # a * T = 1.5 mm/s, so the smeared-step model accepts it; strict continuity does not
    traj = _chord_vertex(20.0, 1.5)
    step = 20.0 * math.sin(math.radians(1.5))
    assert 0.5 < step < X_ACCEL * PERIOD
    lax = _codes(traj, corner_rule=CornerRule.BLEND, strict_continuity=False)
    strict = _codes(traj, corner_rule=CornerRule.BLEND, strict_continuity=True)
    assert dg.VERIFY_CORNER not in lax and strict.get(dg.VERIFY_CORNER) == 1, (lax, strict)
    assert dg.VERIFY_CORNER not in _codes(_chord_vertex(20.0, 0.0), corner_rule=CornerRule.BLEND,
                                          strict_continuity=True)


def _at_rest_ends(v: tuple[float, float], v2: tuple[float, float]) -> Trajectory:
    """Rest -> ramp to ``v`` -> step to ``v2`` -> ramp to rest, in X/Y with continuous velocity
    except at the middle boundary."""
    d = 0.05

    def ramp(vs: tuple[float, float], ve: tuple[float, float]) -> tuple[float, tuple[float, float],
                                                                        tuple[float, float], tuple[float, float]]:
        return (d, vs, ((ve[0] - vs[0]) / d, (ve[1] - vs[1]) / d), (0.0, 0.0))

    return _traj([ramp((0.0, 0.0), v), ramp(v2, (0.0, 0.0))])


def test_continuous_plan_passes_strict() -> None:
    traj = _at_rest_ends((10.0, 5.0), (10.0, 5.0))
    assert dg.VERIFY_CORNER not in _codes(traj, corner_rule=CornerRule.BLEND, strict_continuity=True,
                                          jerk_limited=False)


def test_strict_catches_a_small_injected_step() -> None:
    traj = _at_rest_ends((10.0, 5.0), (10.0, 5.001))  # 1 um/s, far above the float slack
    counts = _codes(traj, corner_rule=CornerRule.BLEND, strict_continuity=True, jerk_limited=False)
    assert counts.get(dg.VERIFY_CORNER) == 1
    assert dg.VERIFY_CORNER not in _codes(traj, corner_rule=CornerRule.BLEND, strict_continuity=False,
                                          jerk_limited=False)


def test_declared_speed_step_of_szgh_is_allowed_and_no_more() -> None:
    step = SZGH.axes[0].max_speed_step_mm_min / 60  # 500 mm/min = 8.33 mm/s
    assert step == pytest.approx(500 / 60)
    ok = _at_rest_ends((10.0, 0.0), (10.0 - 0.9 * step, 0.0))
    bad = _at_rest_ends((10.0, 0.0), (10.0 - 1.2 * step, 0.0))
    kw = {"corner_rule": CornerRule.BLEND, "strict_continuity": True, "jerk_limited": False}
    assert dg.VERIFY_CORNER not in _codes(ok, SZGH, **kw)
    assert _codes(bad, SZGH, **kw).get(dg.VERIFY_CORNER) == 1
    assert _codes(ok, GENERIC, **kw).get(dg.VERIFY_CORNER) == 1  # generic-mill declares no step


def test_take_off_from_rest_only_where_declared() -> None:
    take_off = SZGH.axes[0].start_speed_mm_min / 60  # 8.33 mm/s
    jump = 0.9 * take_off
    d = 0.05
    traj = _traj([(d, (jump, 0.0), (-jump / d, 0.0), (0.0, 0.0))])  # starts at 7.5 mm/s from rest
    kw = {"corner_rule": CornerRule.BLEND, "strict_continuity": True, "jerk_limited": False}
    assert dg.VERIFY_CORNER not in _codes(traj, SZGH, **kw)
    assert _codes(traj, GENERIC, **kw).get(dg.VERIFY_CORNER) == 1
    fast = _traj([(d, (1.5 * take_off, 0.0), (-1.5 * take_off / d, 0.0), (0.0, 0.0))])
    assert _codes(fast, SZGH, **kw).get(dg.VERIFY_CORNER) == 1


def _stop_between(v: tuple[float, float], v2: tuple[float, float]) -> Trajectory:
    """A ramp from rest to ``v``, then from ``v2`` down to rest: the middle boundary steps from
    ``v`` to ``v2`` with no time at rest."""
    return _at_rest_ends(v, v2)


@pytest.mark.parametrize("strict", [True, False])
def test_a_stop_through_rest_at_the_take_off_speed_is_declared(strict: bool) -> None:
    # SZGH-990MDb §5.4: ramp down to the start speed (P101-P104, 500 mm/min), stop in one step;
    # motion starts at the start speed with no ramp.  A G01 ending at -450 mm/min in X followed
    # by a G00 starting at +450 mm/min in X and Y is two declared steps (to rest, from rest),
    # though the X step, 900 mm/min, is beyond the corner step (500 mm/min).
    take_off = SZGH.axes[0].start_speed_mm_min / 60
    assert take_off == pytest.approx(500 / 60) and SZGH.axes[0].max_speed_step_mm_min / 60 == pytest.approx(take_off)
    v = 0.9 * take_off
    kw = {"corner_rule": CornerRule.SPEED_STEP, "strict_continuity": strict, "jerk_limited": False}
    assert dg.VERIFY_CORNER not in _codes(_stop_between((-v, 0.0), (v, v)), SZGH, **kw)
    # one side above the take-off speed: the step to rest is not declared
    assert _codes(_stop_between((-1.2 * take_off, 0.0), (v, v)), SZGH, **kw).get(dg.VERIFY_CORNER) == 1
    assert _codes(_stop_between((-v, 0.0), (v, 1.2 * take_off)), SZGH, **kw).get(dg.VERIFY_CORNER) == 1
    # generic-mill declares neither a take-off speed nor a corner step
    assert _codes(_stop_between((-v, 0.0), (v, v)), GENERIC, **{**kw, "corner_rule": CornerRule.BLEND,
                                                                "strict_continuity": True}).get(dg.VERIFY_CORNER)


def test_junction_deviation_corner_of_o1_is_allowed_strict() -> None:
    # grbl: v^2 = a delta sin(t/2) / (1 - sin(t/2)) with a the acceleration along the
    # junction vector; a 90-degree X -> Y corner, junction vector (-1, 1)/sqrt2
    delta = GENERIC.junction_deviation_mm
    a_j = X_ACCEL / (1 / math.sqrt(2))
    sh = math.sin(math.pi / 4)
    v_jd = math.sqrt(a_j * delta * sh / (1 - sh))
    d = 0.05

    def corner(v: float) -> Trajectory:
        return _traj([(d, (0.0, 0.0), (v / d, 0.0), (0.0, 0.0)), (d, (0.0, v), (0.0, -v / d), (0.0, 0.0))])

    kw = {"corner_rule": CornerRule.JUNCTION_DEVIATION, "strict_continuity": True, "jerk_limited": False}
    assert dg.VERIFY_CORNER not in _codes(corner(0.99 * v_jd), **kw)
    assert _codes(corner(1.5 * v_jd), **kw).get(dg.VERIFY_CORNER) == 1


def _two_steps(gap_s: float) -> Trajectory:
    """X accelerates in two steps of 0.6 * j * T, ``gap_s`` apart, and back down the same way."""
    a1 = 0.6 * X_JERK * PERIOD
    phases = [(0.01, (0.0, 0.0), (0.0, 0.0), (0.0, 0.0)),
              (gap_s, (0.0, 0.0), (a1, 0.0), (0.0, 0.0)),
              (0.005, (0.0, 0.0), (2 * a1, 0.0), (0.0, 0.0)),
              (gap_s, (0.0, 0.0), (a1, 0.0), (0.0, 0.0)),
              (0.01, (0.0, 0.0), (0.0, 0.0), (0.0, 0.0))]
    raw = _traj([(d, (10.0, 0.0), a, j) for d, _, a, j in phases])
    v = 10.0 + np.concatenate([[0.0], np.cumsum(raw.a0_mm_s2[:-1, 0] * raw.duration_s[:-1])])
    out = [(d, (float(v[k]), 0.0), a, j) for k, (d, _, a, j) in enumerate(phases)]
    return _traj(out)


def test_averaged_jerk_adds_up_steps_inside_one_period() -> None:
    close, apart = _two_steps(0.0003), _two_steps(0.002)  # 0.3 ms and 2 ms between the steps
    kw = {"corner_rule": CornerRule.BLEND, "jerk_limited": True}
    # each step alone is within j * T = 50 mm/s^2: the per-boundary rule accepts both
    assert dg.VERIFY_ACCEL_STEP not in _codes(close, strict_continuity=False, **kw)
    assert dg.VERIFY_ACCEL_STEP in _codes(close, strict_continuity=True, strict_jerk=True, **kw)  # 60 + ... > 50
    assert dg.VERIFY_ACCEL_STEP not in _codes(apart, strict_continuity=True, strict_jerk=True, **kw)
    # the averaged jerk is its own switch (off by default): strict continuity alone keeps the per-boundary rule
    assert dg.VERIFY_ACCEL_STEP not in _codes(close, strict_continuity=True, strict_jerk=False, **kw)


def test_boundary_states_read_both_sides_through_the_api() -> None:
    traj = _chord_vertex(20.0, 90.0)
    b = vp.boundary_states(traj)
    assert b.v_before[0] == pytest.approx(np.zeros(6))  # rest before the start
    assert b.v_after[0] == pytest.approx(np.zeros(6))  # the ramp starts from rest
    assert b.v_before[1, :2] == pytest.approx([20.0, 0.0])  # the end of phase 0
    assert b.v_after[1, :2] == pytest.approx([0.0, 20.0], abs=1e-9)  # the start of phase 1
    assert b.v_before[2] == pytest.approx(np.zeros(6), abs=1e-9)  # the ramp ends at rest
    assert b.v_after[2] == pytest.approx(np.zeros(6))  # rest after the end
    assert b.a_before[1, 0] == pytest.approx(400.0) and b.a_after[1, 1] == pytest.approx(-400.0)


class _Circle:
    """Not cubic rows: X, Y on a circle of radius ``r`` at angular speed ``w`` (one phase over
    half a turn).  Only the API that verify_physics reads."""

    def __init__(self, r: float, w: float) -> None:
        self.r, self.w = r, w
        self.t0_s = np.zeros(1)
        self.duration_s = np.array([math.pi / w])
        self.phase_count = 1
        self.duration_total_s = math.pi / w

    def sample(self, t_s: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        t = np.asarray(t_s, float)
        r, w = self.r, self.w
        z = np.zeros((t.size, 6))
        p, v, a, j = z.copy(), z.copy(), z.copy(), z.copy()
        p[:, 0], p[:, 1] = r * np.cos(w * t), r * np.sin(w * t)
        v[:, 0], v[:, 1] = -r * w * np.sin(w * t), r * w * np.cos(w * t)
        a[:, 0], a[:, 1] = -r * w * w * np.cos(w * t), -r * w * w * np.sin(w * t)
        j[:, 0], j[:, 1] = r * w**3 * np.sin(w * t), -r * w**3 * np.cos(w * t)
        return p, v, a, j


def test_dense_extremes_find_the_peak_inside_a_non_cubic_phase() -> None:
    circle = _Circle(10.0, 30.0)  # |v_x| = 300 sin(wt): 0 at both ends, 300 mm/s in the middle
    vmax, amax, jmax = vp.dense_extremes(circle, per_phase=16)  # type: ignore[arg-type]
    assert vmax[0, 0] == pytest.approx(300.0, rel=1e-9)  # the middle sample is the peak
    assert amax[0, 0] == pytest.approx(9000.0) and jmax[0, 1] == pytest.approx(270000.0)
    _, v_ends, _, _ = circle.sample(np.array([0.0, math.pi / 30.0]))
    assert np.abs(v_ends[:, 0]).max() < 1e-9  # the ends alone would see nothing


def test_dense_extremes_are_the_same_in_chunks() -> None:
    traj = _two_steps(0.0003)
    whole = vp.dense_extremes(traj)
    parts = vp.dense_extremes(traj, chunk_phases=2)
    for w, p in zip(whole, parts, strict=True):
        assert w.shape == (traj.phase_count, 6)
        assert np.array_equal(w, p)
    assert whole[1][2, 0] == pytest.approx(1.2 * X_JERK * PERIOD)  # the middle phase's acceleration


def test_dense_extremes_of_chosen_phases_are_their_rows_of_the_whole() -> None:
    traj = _two_steps(0.0003)
    whole = vp.dense_extremes(traj)
    rows = np.array([2, 0], dtype=np.intp)
    part = vp.dense_extremes(traj, phases=rows, chunk_phases=1)
    for w, p in zip(whole, part, strict=True):
        assert np.array_equal(w[rows], p)
