"""Exact-mode step times against closed forms; positions reconstructed from pulses."""

from __future__ import annotations

import math

import numpy as np
import pytest

from cncc.backends.pulses import StepChunk, generate_pulses
from cncc.backends.pulses.spec import axis_spec
from cncc.diagnostics import DiagnosticSink
from cncc.ir.machine import Axis, AxisKind, MachineModel, StepOutput
from cncc.ir.trajectory import Trajectory
from tests.backends.pulse_trajectories import (
    NAN,
    build,
    concat,
    constant_velocity,
    crossing_times_bisect,
    phase_end_positions,
    s_curve,
    trapezoid,
)


def machine(*axes: Axis) -> MachineModel:
    return MachineModel("test", axes)


def collect(chunks: list[StepChunk], i: int = 0) -> dict[str, np.ndarray]:
    return {
        "t_ns": np.concatenate([c.axes[i].t_ns for c in chunks]),
        "dir": np.concatenate([c.axes[i].direction for c in chunks]).astype(np.int64),
        "phase": np.concatenate([c.axes[i].phase for c in chunks]),
        "backlash": np.concatenate([c.axes[i].backlash for c in chunks]),
        "dir_t_ns": np.concatenate([c.axes[i].dir_t_ns for c in chunks]),
        "dir_level": np.concatenate([c.axes[i].dir_level for c in chunks]),
    }


def run(traj: Trajectory, m: MachineModel, **kw: object) -> tuple[list[StepChunk], DiagnosticSink]:
    sink = DiagnosticSink()
    chunks = list(generate_pulses(traj, m, sink=sink, **kw))  # type: ignore[arg-type]
    return chunks, sink


def assert_positions_at_phase_ends(traj: Trajectory, m: MachineModel, chunks: list[StepChunk]) -> None:
    """Motor steps at each phase end == N(commanded end) + backlash, exactly."""
    ends = phase_end_positions(traj)
    for i, spec in enumerate(chunks[0].layout.specs):
        col = traj.axes.index(spec.name)
        s = collect(chunks, i)
        start = int(spec.motor_steps(traj.p0_mm[:1, col])[0])
        motion = np.where(s["backlash"], 0, s["dir"])
        blash = np.where(s["backlash"], s["dir"], 0)
        for k in range(traj.phase_count):
            upto = s["phase"] <= k
            got = start + int(motion[upto].sum())
            want_cmd = int(spec.commanded_steps(ends[k : k + 1, col])[0])
            want_pitch = int(spec.pitch_steps(ends[k : k + 1, col])[0])
            assert got == want_cmd + want_pitch, (spec.name, k)
            assert int(blash[upto].sum()) in (0, -spec.backlash_steps)


def test_constant_velocity_matches_closed_form() -> None:
    v, r = 37.0, 800.0
    traj = constant_velocity(v, 2.0, p0=1.234)
    m = machine(Axis("X", step=StepOutput(steps_per_mm=r)))
    chunks, sink = run(traj, m, chunk_steps=5000)
    s = collect(chunks)
    n0 = math.floor(1.234 * r + 0.5)
    k = np.arange(1, s["t_ns"].size + 1)
    t_true = ((n0 + k - 0.5) / r - 1.234) / v
    assert s["t_ns"].size == math.floor((1.234 + v * 2.0) * r + 0.5) - n0
    assert np.abs(s["t_ns"] - t_true * 1e9).max() <= 1.0
    assert len(chunks) > 5 and not sink.has_errors


def test_trapezoid_matches_closed_form() -> None:
    d, v, a, r = 30.0, 50.0, 400.0, 1000.0
    traj = trapezoid(d, v, a)
    m = machine(Axis("X", step=StepOutput(steps_per_mm=r)))
    chunks, _ = run(traj, m, chunk_steps=4096)
    s = collect(chunks)
    x = (np.arange(1, s["t_ns"].size + 1) - 0.5) / r
    ta, tc = v / a, d / v - v / a
    xa = v * ta / 2
    t_true = np.where(x <= xa, np.sqrt(2 * x / a),
                      np.where(x <= d - xa, ta + (x - xa) / v, 2 * ta + tc - np.sqrt(2 * np.maximum(d - x, 0) / a)))
    assert s["t_ns"].size == round(d * r)
    assert np.abs(s["t_ns"] - t_true * 1e9).max() <= 1.0


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_s_curve_matches_reference_roots(sign: float) -> None:
    traj = s_curve(80.0, 800.0, 20000.0, 0.05, sign)
    r = 500.0
    m = machine(Axis("X", step=StepOutput(steps_per_mm=r)))
    chunks, sink = run(traj, m, chunk_steps=3000)
    s = collect(chunks)
    k = np.arange(1, s["t_ns"].size + 1)
    boundary = sign * (k - 0.5) / r
    ph = s["phase"]
    local = crossing_times_bisect(traj, 0, boundary, ph, np.zeros(k.size), traj.duration_s[ph])
    t_true = traj.t0_s[ph] + local
    assert np.all(s["dir"] == sign)
    assert np.abs(s["t_ns"] - t_true * 1e9).max() <= 1.0
    assert_positions_at_phase_ends(traj, m, chunks)
    assert not sink.has_errors


def test_reversal_positions_direction_setup_and_rate() -> None:
    # out and back and out again, with jerk, on two axes
    rows = [
        (0.02, [0.0, 0.0], [0.0, 0.0], [30000.0, -20000.0]),
        (0.04, [NAN, NAN], [600.0, -400.0], [-30000.0, 20000.0]),
        (0.03, [NAN, NAN], [-600.0, 400.0], [10000.0, 0.0]),
        (0.05, [NAN, NAN], [-300.0, 400.0], [0.0, -16000.0]),
    ]
    traj = build(rows, [5.0, -2.0], ("X", "Y"))
    st = StepOutput(steps_per_mm=2000.0, max_step_rate_hz=200_000.0, pulse_width_ns=1500, dir_setup_ns=4000)
    m = machine(Axis("X", step=st), Axis("Y", step=st))
    chunks, sink = run(traj, m, chunk_steps=64)
    assert_positions_at_phase_ends(traj, m, chunks)
    for i in range(2):
        s = collect(chunks, i)
        assert np.all(np.diff(s["t_ns"]) > 0)
        changes = np.flatnonzero(np.diff(s["dir"]) != 0) + 1
        assert changes.size >= 1
        assert s["dir_t_ns"].size == changes.size + (1 if s["dir"][0] < 0 else 0)
        step_after = s["t_ns"][np.searchsorted(s["t_ns"], s["dir_t_ns"])]
        assert np.all(step_after - s["dir_t_ns"] >= st.dir_setup_ns)
        assert np.all(np.diff(s["t_ns"]) >= 1e9 / st.max_step_rate_hz - 1)
    assert not sink.has_errors


def test_chunking_does_not_change_steps() -> None:
    traj = concat(s_curve(60.0, 500.0, 9000.0, 0.02), s_curve(60.0, 500.0, 9000.0, 0.01, -1.0))
    m = machine(Axis("X", step=StepOutput(steps_per_mm=1000.0)))
    a = collect(run(traj, m, chunk_steps=1 << 20)[0])
    b = collect(run(traj, m, chunk_steps=100)[0])
    # the same steps; times may differ by the last rounding (cut points change the expansion points)
    assert np.array_equal(a["dir"], b["dir"]) and np.array_equal(a["phase"], b["phase"])
    assert np.abs(a["t_ns"] - b["t_ns"]).max() <= 1


def test_electronic_gear_carries_the_remainder() -> None:
    # SZGH: pulses = um * CMR / CMD; 10/12 is not a whole number of pulses per um
    moves = [0.0137, -0.0051, 0.0233, 0.0079, -0.0111] * 40
    rows = []
    for d in moves:
        t = 0.01
        rows.append((t, [d / t], [0.0], [0.0]))
    traj = build(rows, [0.0], ("X",))
    m = machine(Axis("X", step=StepOutput(steps_per_mm=1000.0, gear_cmr=10, gear_cmd=12)))
    chunks, _ = run(traj, m)
    s = collect(chunks)
    total_um = sum(moves) * 1000.0
    assert int(s["dir"].sum()) == math.floor(total_um * 10 / 12 + 0.5)
    per_move_rounding = sum(round(d * 1000 * 10 / 12) for d in moves)
    assert per_move_rounding != int(s["dir"].sum())  # naive rounding would drift
    assert_positions_at_phase_ends(traj, m, chunks)


def test_direction_invert_flips_the_level_only() -> None:
    traj = constant_velocity(-10.0, 0.1)
    plain = collect(run(traj, machine(Axis("X")))[0])
    inv = collect(run(traj, machine(Axis("X", step=StepOutput(direction_invert=True))))[0])
    assert np.array_equal(plain["t_ns"], inv["t_ns"])
    assert plain["dir_level"].tolist() == [0] and inv["dir_level"].tolist() == [1]


def test_rotary_axis_with_periodic_pitch_table() -> None:
    table = ((45.0, 0.01), (90.0, -0.02), (180.0, 0.015), (270.0, 0.0), (315.0, -0.01))
    ax = Axis("A", kind=AxisKind.ROTARY, step=StepOutput(steps_per_mm=100.0, pitch_table_mm=table))
    traj = build([(2.0, [400.0], [0.0], [0.0]), (1.0, [NAN], [-300.0], [0.0])], [10.0], ("A",))
    m = machine(ax)
    chunks, sink = run(traj, m, chunk_steps=500)
    assert_positions_at_phase_ends(traj, m, chunks)
    spec = chunks[0].layout.specs[0]
    x = np.array([10.0, 370.0, 730.0, 100.0 + 720.0])
    assert np.allclose(spec.pitch.offset_mm(x), spec.pitch.offset_mm(x - 360.0))  # type: ignore[union-attr]
    assert not sink.has_errors


def test_linear_pitch_table_relative_to_home() -> None:
    table = ((-50.0, 0.003), (50.0, -0.002), (100.0, 0.004))
    ax = Axis("X", home_mm=-20.0, step=StepOutput(steps_per_mm=1000.0, pitch_table_mm=table))
    spec, ok = axis_spec(ax)
    assert ok and spec.pitch is not None
    assert spec.pitch.offset_mm(np.array([-20.0]))[0] == 0.0  # home
    assert spec.pitch.offset_mm(np.array([5.0]))[0] == pytest.approx(-0.001)  # halfway home -> +50
    assert spec.pitch.offset_mm(np.array([500.0]))[0] == pytest.approx(0.004)  # held beyond the table
    q = np.linspace(-200, 200, 1001)
    assert np.allclose(spec.pitch.inverse(spec.pitch.forward(q)), q, atol=1e-12)
    traj = trapezoid(150.0, 100.0, 1000.0)
    chunks, _ = run(traj, machine(ax), chunk_steps=20000)
    assert_positions_at_phase_ends(traj, machine(ax), chunks)
    s = collect(chunks)
    # start 20 mm from home: c = -0.0008 mm -> N = -1; end 170 mm from home (past the table): c = +0.004 mm
    assert int(s["dir"].sum()) == (150_000 + 4) - (-1)


def test_non_monotone_pitch_table_is_rejected_with_a_diagnostic() -> None:
    ax = Axis("X", step=StepOutput(pitch_table_mm=((1.0, 0.01), (1.001, 0.0))))
    chunks, sink = run(constant_velocity(1.0, 0.01), machine(ax))
    assert [d.code for d in sink] == ["E0704"]
    assert chunks[0].layout.specs[0].pitch is None
