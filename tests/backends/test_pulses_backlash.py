"""Backlash across window ends, backlash in interpolation mode, and the jerk-phase solver's accuracy."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from cncc.backends.pulses.interp import sample_positions
from cncc.backends.pulses.spec import axis_spec, backlash_offsets_s
from cncc.ir.machine import Axis, BacklashMode, StepOutput
from cncc.ir.trajectory import Trajectory
from tests.backends.pulse_trajectories import build, crossing_times_bisect
from tests.backends.test_pulses_exact import assert_positions_at_phase_ends, collect, machine, run

SLOW_A = StepOutput(steps_per_mm=1000.0, backlash_mm=0.05, backlash_mode=BacklashMode.A,
                    backlash_a_speed_mm_min=60.0)  # 50 pulses at 1 kHz: a 50 ms burst


def zigzag() -> Trajectory:
    return build([(0.05, [10.0], [0.0], [0.0]), (0.08, [-10.0], [0.0], [0.0]), (0.08, [10.0], [0.0], [0.0])],
                 [0.0], ("X",))


def test_a_burst_across_window_ends_does_not_depend_on_the_windows() -> None:
    traj = zigzag()
    m = machine(Axis("X", step=SLOW_A))
    whole = collect(run(traj, m, chunk_steps=1 << 20)[0])
    chunks, sink = run(traj, m, chunk_steps=40)
    cut = collect(chunks)
    assert len(chunks) > 10
    np.testing.assert_array_equal(cut["t_ns"], whole["t_ns"])
    np.testing.assert_array_equal(cut["backlash"], whole["backlash"])
    np.testing.assert_array_equal(cut["dir"], whole["dir"])
    assert int(whole["backlash"].sum()) == 2 * 50
    assert_positions_at_phase_ends(traj, m, chunks)
    # superposed, not merged: the combined train never steps faster than the two rates together
    assert np.diff(whole["t_ns"]).min() >= 1e9 / (10_000.0 + 1_000.0) - 2
    assert not sink.has_errors


def test_held_back_events_keep_the_horizon_promise() -> None:
    traj = zigzag()
    chunks = run(traj, machine(Axis("X", step=SLOW_A)), chunk_steps=40)[0]
    for k, c in enumerate(chunks[:-1]):
        later = [int(a.t_ns.min()) - 200 for d in chunks[k + 1:] for a in d.axes if a.count]
        assert not later or min(later) >= c.horizon_ns


def test_interp_mode_adds_backlash_to_the_period_counts() -> None:
    traj = zigzag()
    so = SLOW_A
    m = machine(Axis("X", step=so))
    chunks, sink = run(traj, m, mode="interp", chunk_steps=30)
    s = collect(chunks)
    period_ns = 2_000_000
    spec = chunks[0].layout.specs[0]
    grid = np.arange(0, math.ceil(traj.duration_total_s / 0.002) + 1, dtype=np.float64) * 0.002
    commanded = np.diff(spec.motor_steps(sample_positions(traj, grid)[:, 0]))
    # the burst of each reversal, counted per period from the reversal period on
    offs, _ = backlash_offsets_s(axis_spec(Axis("X", step=so))[0])
    per_period = np.bincount(np.floor(offs / 0.002).astype(np.int64))
    expected = commanded.copy()
    for k_r, sign in ((25, -1), (65, 1)):  # reversals at 50 ms and 130 ms
        expected[k_r:k_r + per_period.size] += sign * per_period
    k = s["t_ns"] // period_ns
    got = np.zeros_like(expected)
    np.add.at(got, k, s["dir"])
    np.testing.assert_array_equal(got, expected)
    for kk in np.unique(k):  # one direction and evenly spread within every period
        sel = k == kk
        assert np.ptp(s["dir"][sel]) == 0
        if sel.sum() > 2:
            assert np.ptp(np.diff(s["t_ns"][sel])) <= 1
    assert int(s["backlash"].sum()) == 100
    assert int((s["dir"] * s["backlash"]).sum()) == 0  # one burst each way
    assert int(s["dir"].sum()) == int(spec.motor_steps(np.array([traj.end_state(2)[0][0]]))[0])
    assert not sink.has_errors


jerk_phase = st.tuples(st.floats(0.001, 0.08), st.floats(-50.0, 50.0), st.floats(-3000.0, 3000.0),
                       st.floats(-3e5, 3e5))


@settings(max_examples=50, deadline=None)
@given(st.lists(jerk_phase, min_size=1, max_size=4), st.booleans())
def test_jerk_phase_step_times_match_bisection(rows: list[tuple[float, float, float, float]], rest: bool) -> None:
    built = [(d, [0.0 if rest and k == 0 else v], [a], [j]) for k, (d, v, a, j) in enumerate(rows)]
    traj = build(built, [0.3], ("X",))
    r = 400.0
    m = machine(Axis("X", step=StepOutput(steps_per_mm=r, max_step_rate_hz=1e9, pulse_width_ns=0,
                                          dir_setup_ns=0)))
    s = collect(run(traj, m, chunk_steps=500)[0])
    if s["t_ns"].size == 0:
        return
    # the boundary each step crossed: between its step counts before and after
    n0 = math.floor(0.3 * r + 0.5)
    after = n0 + np.cumsum(s["dir"])
    boundary = (after - 0.5 * s["dir"]) / r
    ph = s["phase"]
    # the monotone stretch of its phase the step lies in (edges at the velocity zeros)
    edges = np.array([monotone_edges(float(traj.v0_mm_s[k, 0]), float(traj.a0_mm_s2[k, 0]),
                                     float(traj.j_mm_s3[k, 0]), float(traj.duration_s[k])) for k in ph])
    t_loc = s["t_ns"] / 1e9 - traj.t0_s[ph]
    col = np.clip((t_loc[:, None] > edges).sum(axis=1) - 1, 0, 2)
    lo, hi = edges[np.arange(ph.size), col], edges[np.arange(ph.size), col + 1]
    mid = 0.5 * (lo + hi)
    v_mid = traj.v0_mm_s[ph, 0] + traj.a0_mm_s2[ph, 0] * mid + traj.j_mm_s3[ph, 0] * mid**2 / 2
    assert np.all(np.sign(v_mid) == s["dir"])  # each step moves the way its stretch does
    t_true = traj.t0_s[ph] + crossing_times_bisect(traj, 0, boundary, ph, lo, hi)
    assert np.abs(s["t_ns"] - t_true * 1e9).max() <= 1.0


def monotone_edges(v: float, a: float, j: float, dur: float) -> list[float]:
    """``[0, z1, z2, dur]``: the velocity zeros inside the phase (repeated ends where there are fewer)."""
    if j:  # v + a t + (j/2) t^2 = 0, in the form without cancellation
        disc = a * a - 2 * j * v
        q = -0.5 * (a + math.copysign(math.sqrt(disc), a)) if disc >= 0 else 0.0
        cands = [2 * (q / j), v / q] if q else []
    else:
        cands = [-v / a] if a else []
    zs = sorted(z for z in cands if math.isfinite(z) and 0 < z < dur)
    return [0.0, *[*zs, dur, dur][:2], dur]
