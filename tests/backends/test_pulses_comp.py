"""Backlash, reversal delay, limits and diagnostics, the 2 ms interpolation mode, properties."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from cncc.backends.pulses import generate_pulses
from cncc.backends.pulses.spec import axis_spec, backlash_offsets_s
from cncc.ir.machine import Axis, BacklashMode, MachineModel, StepOutput
from cncc.ir.trajectory import Trajectory
from cncc.source import Span
from tests.backends.pulse_trajectories import NAN, build, constant_velocity, trapezoid
from tests.backends.test_pulses_exact import assert_positions_at_phase_ends, collect, machine, run


def out_and_back(v: float = 20.0, t: float = 0.05) -> Trajectory:
    return build([(t, [v], [0.0], [0.0]), (t, [-v], [0.0], [0.0]), (t, [v], [0.0], [0.0])], [0.0], ("X",))


@pytest.mark.parametrize("mode", [BacklashMode.A, BacklashMode.B])
def test_backlash_pulses_on_each_reversal(mode: BacklashMode) -> None:
    traj = out_and_back()
    so = StepOutput(steps_per_mm=1000.0, backlash_mm=0.02, backlash_mode=mode)
    m = machine(Axis("X", step=so))
    chunks, sink = run(traj, m, chunk_steps=64)
    s = collect(chunks)
    bl = s["backlash"]
    assert int(bl.sum()) == 2 * 20  # two reversals, 20 um each
    assert s["dir"][bl].tolist() == [-1] * 20 + [1] * 20
    assert_positions_at_phase_ends(traj, m, chunks)
    # the burst starts at the reversal (+ direction set-up); superposed on the commanded steps, the
    # combined train steps at most at the sum of the two rates (no near-coincident pulses)
    first = s["t_ns"][bl][:20]
    assert first[0] >= 50_000_000 + so.dir_setup_ns
    offs, dur = backlash_offsets_s(axis_spec(Axis("X", step=so))[0])
    assert first[-1] <= 50_000_000 + dur * 1e9 + so.dir_setup_ns
    burst_rate_hz = 1.0 / np.diff(offs).min()
    assert np.diff(s["t_ns"]).min() >= 1e9 / (20_000.0 + burst_rate_hz) - 2
    if mode is BacklashMode.B:  # ramped: faster in the middle than at the ends
        gaps = np.diff(offs)
        assert gaps[len(gaps) // 2] < gaps[0]
    assert not sink.has_errors


def test_reversal_delay_pauses_every_axis() -> None:
    traj = build([(0.05, [20.0, 10.0], [0.0, 0.0], [0.0, 0.0]), (0.05, [-20.0, 10.0], [0.0, 0.0], [0.0, 0.0])],
                 [0.0, 0.0], ("X", "Y"))
    base = machine(Axis("X"), Axis("Y"))
    delayed = machine(Axis("X", step=StepOutput(reversal_delay_s=0.004)), Axis("Y"))
    a, b = run(traj, base)[0], run(traj, delayed)[0]
    for i in range(2):
        ta, tb = collect(a, i)["t_ns"], collect(b, i)["t_ns"]
        assert ta.size == tb.size
        shift = tb - ta
        before = ta < 50_000_000
        assert np.all(shift[before] == 0) and np.all(shift[~before] == 4_000_000)
    assert b[-1].t_end_ns == a[-1].t_end_ns + 4_000_000
    assert (a[-1].pause_ns, b[-1].pause_ns) == (0, 4_000_000)  # what the planner's timing leaves out


def test_step_rate_above_maximum_names_the_command() -> None:
    traj = build([(0.01, [10.0], [0.0], [0.0]), (0.01, [40.0], [0.0], [0.0]), (0.01, [10.0], [0.0], [0.0])],
                 [0.0], ("X",), cmd=[4, 7, 9])
    spans = [Span(0, 10 * k, 10 * k + 5) for k in range(10)]
    m = machine(Axis("X", step=StepOutput(steps_per_mm=1000.0, max_step_rate_hz=25_000.0)))
    sink = run(traj, m, spans=spans)[1]
    rate = [d for d in sink if d.code == "E0701"]
    assert len(rate) == 1 and rate[0].span == spans[7] and "command #7" in rate[0].message


def test_pulses_closer_than_minimum_spacing() -> None:
    traj = constant_velocity(300.0, 0.001)  # 300 kHz: 3333 ns apart
    m = machine(Axis("X", step=StepOutput(max_step_rate_hz=1e7, pulse_width_ns=2000)))
    sink = run(traj, m)[1]
    assert [d.code for d in sink] == ["E0702"]


def test_soft_limit_crossing_between_phase_ends_is_found() -> None:
    # goes to +2.5 mm and back to 0 inside one phase: the ends are inside the limits
    traj = build([(0.1, [0.0], [0.0], [0.0]), (1.0, [10.0], [-20.0], [0.0])], [0.0], ("X",), cmd=[1, 3])
    spans = [Span(0, k, k + 1) for k in range(5)]
    m = machine(Axis("X", soft_min_mm=-1.0, soft_max_mm=2.0))
    sink = run(traj, m, spans=spans)[1]
    assert [(d.code, d.span) for d in sink] == [("E0703", spans[3])]
    assert "2.5000" in sink.items[0].message


def test_interp_mode_counts_per_period_and_spreads_evenly() -> None:
    traj = trapezoid(20.0, 100.0, 1000.0)
    m = machine(Axis("X", step=StepOutput(steps_per_mm=1000.0)))
    chunks, sink = run(traj, m, mode="interp", chunk_steps=2000)
    s = collect(chunks)
    period_ns = 2_000_000
    k = s["t_ns"] // period_ns
    spec = chunks[0].layout.specs[0]
    t_grid = np.arange(0, math.ceil(traj.duration_total_s / 0.002) + 1, dtype=np.float64) * 0.002
    from cncc.backends.pulses.interp import sample_positions

    n = spec.motor_steps(sample_positions(traj, t_grid)[:, 0])
    counts = np.bincount(k, minlength=n.size - 1)[: n.size - 1]
    assert np.array_equal(counts, np.diff(n))
    assert int(s["dir"].sum()) == 20_000
    for kk in np.unique(k)[:50]:
        tt = s["t_ns"][k == kk]
        if tt.size > 2:
            assert np.ptp(np.diff(tt)) <= 1  # evenly spread (to the ns)
    assert not sink.has_errors


def test_interp_mode_rate_limit_per_period() -> None:
    traj = constant_velocity(3000.0, 0.01)  # 3 MHz at 1 um/pulse: over the SZGH 2 MHz
    m = machine(Axis("X", step=StepOutput(max_step_rate_hz=2e6, pulse_width_ns=100)))
    sink = run(traj, m, mode="interp")[1]
    assert {d.code for d in sink} == {"E0701"}


# --- properties -----------------------------------------------------------------

phase_rows = st.lists(
    st.tuples(
        st.floats(0.0, 0.05),
        st.floats(-40.0, 40.0),
        st.floats(-2000.0, 2000.0),
        st.floats(-1e5, 1e5),
        st.booleans(),
    ),
    min_size=1,
    max_size=8,
)


@settings(max_examples=60, deadline=None)
@given(phase_rows, st.sampled_from([(1000.0, 1, 1), (1000.0, 10, 12), (400.0, 3, 7)]),
       st.integers(16, 5000), st.floats(0.0, 0.05))
def test_positions_exact_at_every_phase_end(rows: list[tuple[float, float, float, float, bool]],
                                            gear: tuple[float, int, int], chunk: int, backlash: float) -> None:
    built = [(d, [v if reset else NAN], [a], [j]) for d, v, a, j, reset in rows]
    traj = build(built, [1.5], ("X",))
    so = StepOutput(steps_per_mm=gear[0], gear_cmr=gear[1], gear_cmd=gear[2], max_step_rate_hz=1e9,
                    pulse_width_ns=1, dir_setup_ns=1, backlash_mm=backlash,
                    backlash_mode=BacklashMode.A if backlash else BacklashMode.NONE,
                    backlash_a_speed_mm_min=60_000.0)
    m = MachineModel("p", (Axis("X", step=so),))
    chunks = list(generate_pulses(traj, m, chunk_steps=chunk))
    assert_positions_at_phase_ends(traj, m, chunks)
    t = np.concatenate([c.axes[0].t_ns for c in chunks])
    assert np.all(np.diff(t) > 0)
    ends = [c.t_end_ns for c in chunks]
    assert ends == sorted(ends)
