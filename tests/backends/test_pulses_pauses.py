"""Pauses in the pulse time line: events of commands without motion, reversal delays, and the
timing report counting the same time (``cncc.backends.pulses.pauses``)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import jsonschema
import numpy as np
import pytest

from cncc.api import compile_commands
from cncc.backends.pulses import StepChunk, generate_pulses, reversal_pauses
from cncc.backends.pulses.interp import period_count
from cncc.backends.timing import Run, event_pauses
from cncc.backends.timing.aggregate import build_report
from cncc.backends.timing.jsonout import report_dict, schema
from cncc.cli import main
from cncc.diagnostics import DiagnosticSink
from cncc.driver import Options, plan_trajectory, reversal_events
from cncc.ir.machine import Axis, BacklashMode, StepOutput
from cncc.ir.trajectory import Trajectory
from cncc.machines import load_machine
from tests.backends.pulse_trajectories import build, s_curve
from tests.backends.test_pulses_exact import collect, machine, run

DWELL = "G90 G17 G94\nG01 X1. F60\nG04 X2.\nG01 X2.\n"
STEPS_PER_MM = 800.0  # generic-mill


def assert_stream_guarantees(chunks: list[StepChunk]) -> None:
    """Per axis strictly increasing steps; nothing of a later chunk before a chunk's horizon."""
    for i in range(len(chunks[0].axes)):
        t = collect(chunks, i)["t_ns"]
        assert np.all(np.diff(t) > 0)
    for k, c in enumerate(chunks[:-1]):
        later = [a.t_ns for d in chunks[k + 1:] for a in d.axes] + [a.dir_t_ns for d in chunks[k + 1:] for a in d.axes]
        first = min((int(x.min()) for x in later if x.size), default=c.horizon_ns)
        assert first >= c.horizon_ns
    assert [c.t_start_ns for c in chunks[1:]] == [c.t_end_ns for c in chunks[:-1]]


# ---- the time line on trajectories built by hand --------------------------------------------
def two_moves() -> Trajectory:
    """X at 20 mm/s for 50 ms (command 0), then Y at 10 mm/s for 50 ms (command 2)."""
    return build([(0.05, [20.0, 0.0], [0.0, 0.0], [0.0, 0.0]), (0.05, [0.0, 10.0], [0.0, 0.0], [0.0, 0.0])],
                 [0.0, 0.0], ("X", "Y"), cmd=[0, 2])


@pytest.mark.parametrize("mode", ["exact", "interp"])
@pytest.mark.parametrize("chunk_steps", [16, 1 << 18])
def test_event_pause_moves_every_later_step_of_every_axis(mode: str, chunk_steps: int) -> None:
    traj = two_moves()
    m = machine(Axis("X"), Axis("Y"))
    base = run(traj, m, mode=mode, chunk_steps=chunk_steps)[0]
    # command 1 (a dwell between the moves), command -1 (before all motion), command 5 (after it)
    paused = run(traj, m, mode=mode, chunk_steps=chunk_steps,
                 pauses=[(1, 2_000_000_000), (-1, 7_000), (5, 300), (1, 0)])[0]
    for i in range(2):
        a, b = collect(base, i), collect(paused, i)
        assert np.array_equal(a["dir"], b["dir"]) and np.array_equal(a["phase"], b["phase"])
        shift = b["t_ns"] - a["t_ns"]
        assert np.all(shift == np.where(a["phase"] >= 1, 2_000_007_000, 7_000))
    assert paused[-1].t_end_ns == base[-1].t_end_ns + 2_000_007_300
    assert (paused[-1].event_ns, paused[-1].pause_ns) == (2_000_007_300, 0)
    assert_stream_guarantees(paused)


def test_step_at_the_boundary_stays_with_its_command() -> None:
    # X ends command 0 exactly on a step boundary (0.0005 mm at 1000 steps/mm) and command 2 turns
    # back from it at once: the arrival step is before the dwell, the departure step after it
    traj = build([(0.05, [0.01], [0.0], [0.0]), (0.05, [-0.01], [0.0], [0.0])], [0.0], ("X",), cmd=[0, 2])
    m = machine(Axis("X", step=StepOutput(steps_per_mm=1000.0)))
    s = collect(run(traj, m, pauses=[(1, 1_000_000_000)])[0])
    assert s["dir"].tolist() == [1, -1] and s["phase"].tolist() == [0, 1]
    assert s["t_ns"][0] <= 50_000_000 < 1_050_000_000 <= s["t_ns"][1]


def test_pause_offset_is_exact_on_an_s_curve() -> None:
    """Step times minus the pause offset are the unpaused ones (closed forms, tested elsewhere) to the ns."""
    move = s_curve(50.0, 500.0, 10_000.0, 0.02)
    rows = [(float(move.duration_s[k]), list(move.v0_mm_s[k]), list(move.a0_mm_s2[k]), list(move.j_mm_s3[k]))
            for k in range(move.phase_count)]
    traj = build(rows + [(r[0], [-v for v in r[1]], [-a for a in r[2]], [-j for j in r[3]]) for r in rows],
                 [0.0], ("X",), cmd=[0] * 7 + [2] * 7)
    m = machine(Axis("X", step=StepOutput(steps_per_mm=1000.0, reversal_delay_s=0.0031)))
    base = collect(run(traj, machine(Axis("X", step=StepOutput(steps_per_mm=1000.0))))[0])
    chunks = run(traj, m, chunk_steps=64, pauses=[(1, 1_234_567_891)])[0]
    s = collect(chunks)
    second = s["phase"] >= 7
    assert np.array_equal(s["t_ns"] - np.where(second, 1_234_567_891 + 3_100_000, 0), base["t_ns"])
    assert chunks[-1].pause_ns == 3_100_000 and chunks[-1].event_ns == 1_234_567_891
    assert chunks[-1].t_end_ns == round(traj.duration_total_s * 1e9) + 1_234_567_891 + 3_100_000
    assert_stream_guarantees(chunks)


def test_program_without_motion_still_ends_after_its_pauses() -> None:
    traj = Trajectory.empty(("X",))
    chunks = run(traj, machine(Axis("X")), pauses=[(0, 5), (1, 7)])[0]
    assert len(chunks) == 1 and chunks[0].t_end_ns == 12 and chunks[0].step_count == 0


@pytest.mark.parametrize("mode", ["exact", "interp"])
def test_backlash_burst_and_reversal_pause_with_a_dwell_at_the_reversal(mode: str) -> None:
    traj = build([(0.05, [20.0], [0.0], [0.0]), (0.05, [-20.0], [0.0], [0.0]), (0.05, [20.0], [0.0], [0.0])],
                 [0.0], ("X",), cmd=[0, 2, 4])
    so = StepOutput(steps_per_mm=1000.0, backlash_mm=0.05, backlash_mode=BacklashMode.B, reversal_delay_s=0.002)
    m = machine(Axis("X", step=so))
    rev = reversal_pauses(traj, m, mode=mode, chunk_steps=64)
    assert rev.t_s.size == 2 and rev.total_ns == 4_000_000
    for chunk_steps in (64, 1 << 18):
        chunks = run(traj, m, mode=mode, chunk_steps=chunk_steps, pauses=[(1, 500_000_000), (3, 250_000_000)],
                     reversals=rev if chunk_steps == 64 else None)[0]
        assert_stream_guarantees(chunks)
        s = collect(chunks)
        assert int(s["backlash"].sum()) == 100 and int(s["dir"].sum()) == 1000
        assert chunks[-1].t_end_ns == 150_000_000 + 750_000_000 + 4_000_000
        # nothing of command 2 before the dwell and the reversal pause are over
        assert s["t_ns"][s["phase"] >= 1].min() >= 50_000_000 + 500_000_000


def test_reversals_for_other_options_are_found_again() -> None:
    traj = build([(0.05, [20.0], [0.0], [0.0]), (0.05, [-20.0], [0.0], [0.0])], [0.0], ("X",))
    m = machine(Axis("X", step=StepOutput(reversal_delay_s=0.001)))
    other = reversal_pauses(traj, m, mode="interp")
    chunks = run(traj, m, reversals=other)[0]
    assert chunks[-1].pause_ns == 1_000_000
    assert reversal_pauses(traj, machine(Axis("X"))).t_s.size == 0


# ---- whole programs: pulses against the timing report ----------------------------------------
def planned(text: str, level: int, machine_name: str = "generic-mill") -> tuple[list[Any], Any, Trajectory, Any]:
    cmds, res = compile_commands(text, emit="pulses", machine=machine_name, opt_level=level)
    assert res.ok, [d.message for d in res.sink]
    m = load_machine(machine_name)
    traj, _ = plan_trajectory(cmds, m, level, DiagnosticSink())
    return cmds, res, traj, m


def pulses_and_report(text: str, level: int, machine_name: str = "generic-mill", mode: str = "exact",
                      chunk_steps: int = 1 << 18) -> tuple[list[StepChunk], Any, Trajectory]:
    """What --emit=pulses and --emit=timing compute for ``text`` (the driver's own functions)."""
    cmds, res, traj, m = planned(text, level, machine_name)
    chunks = list(generate_pulses(traj, m, mode=mode, chunk_steps=chunk_steps,
                                  pauses=event_pauses(cmds, traj.cmd_index, m),
                                  reversals=reversal_pauses(traj, m, mode=mode, chunk_steps=chunk_steps)))
    opts = Options(machine=machine_name, opt_level=level, pulse_mode=mode)
    rep = build_report(cmds, [Run(f"O{level}", m, level, traj, "", reversals=reversal_events(traj, m, opts))],
                       res.sources, "<text>", "syntec")
    return chunks, rep, traj


def crossing_s(traj: Trajectory, axis: str, phases: np.ndarray, level_mm: float) -> float:
    """Independent reference: bisection for where the (rising) axis reaches ``level_mm`` in ``phases``."""
    col = traj.axes.index(axis)
    lo = float(traj.t0_s[phases[0]])
    hi = float(traj.t0_s[phases[-1]] + traj.duration_s[phases[-1]])
    for _ in range(200):
        mid = (lo + hi) / 2
        if traj.sample(np.array([mid]))[0][0, col] >= level_mm:
            hi = mid
        else:
            lo = mid
    return hi


def test_dwell_gap_at_O0_closed_form(tmp_path: Path) -> None:
    """At -O0 both moves run at 1 mm/s: step k of a move at (k - 1/2) / 800 s, the second after the 2 s."""
    prog = tmp_path / "dwell.nc"
    prog.write_text(DWELL)
    out = tmp_path / "dwell.npz"
    assert main(["-x", "syntec", "--emit=pulses", "--pulse-format=npz", "-O0", "-o", str(out), str(prog)]) == 0
    t = np.load(out)["X_t_ns"]
    k = np.arange(1, 801)
    want = np.concatenate([(k - 0.5) / STEPS_PER_MM, 3.0 + (k - 0.5) / STEPS_PER_MM]) * 1e9
    assert t.size == 1600 and np.abs(t - want).max() <= 1
    assert t[800] - t[799] == 2_000_000_000 + 1_250_000  # the dwell plus half a step period on each side


def test_dwell_gap_planned_and_end_equals_timing_total() -> None:
    chunks, rep, traj = pulses_and_report(DWELL, 2)
    s = collect(chunks, chunks[0].layout.axes.index("X"))
    cmd = traj.cmd_index[s["phase"]]
    first_move, second_move = np.unique(cmd)
    last1, first2 = s["t_ns"][cmd == first_move][-1], s["t_ns"][cmd == second_move][0]
    ph1 = np.flatnonzero(traj.cmd_index == first_move)
    ph2 = np.flatnonzero(traj.cmd_index == second_move)
    ref_last1 = round(crossing_s(traj, "X", ph1, 799.5 / STEPS_PER_MM) * 1e9)
    ref_first2 = round(crossing_s(traj, "X", ph2, 800.5 / STEPS_PER_MM) * 1e9)
    ref_last2 = round(crossing_s(traj, "X", ph2, 1599.5 / STEPS_PER_MM) * 1e9)
    assert abs(int(last1) - ref_last1) <= 1
    assert abs(int(first2) - (ref_first2 + 2_000_000_000)) <= 1
    assert abs(int(s["t_ns"][-1]) - (ref_last2 + 2_000_000_000)) <= 1
    col = rep.primary
    assert col.event_ns == 2_000_000_000 and col.total_ns == round(traj.duration_total_s * 1e9) + 2_000_000_000
    assert chunks[-1].t_end_ns == col.total_ns and chunks[-1].event_ns == col.event_ns


def rev_machine(tmp_path: Path) -> str:
    """generic-mill with reversal delays (X 4 ms, Y 6 ms) and a 3 s M00/M01."""
    text = (Path(load_machine.__code__.co_filename).parent / "generic-mill.toml").read_text()
    text = text.replace('name = "generic-mill"', 'name = "rev-mill"').replace("optional_stop_s = 0.0",
                                                                                "optional_stop_s = 3.0")
    parts = text.split("[axes.step]\n")
    assert len(parts) == 4
    text = (parts[0] + "[axes.step]\nreversal_delay_s = 0.004\n" + parts[1] + "[axes.step]\nreversal_delay_s = 0.006\n"
            + parts[2] + "[axes.step]\n" + parts[3])
    path = tmp_path / "rev-mill.toml"
    path.write_text(text)
    return str(path)


REVERSING = """G90 G17 G94
T1 M06
S3000 M03
G01 X10. F1200
X0.
X10. Y10.
G04 X0.5
X0. Y0.
M00
X5.
M30
"""


@pytest.mark.parametrize(("level", "mode", "chunk_steps"), [(2, "exact", 1 << 18), (1, "exact", 256),
                                                           (2, "interp", 4096), (0, "exact", 1 << 18)])
def test_reversal_pauses_are_a_timing_category_and_the_pulses_end_at_the_total(
        tmp_path: Path, level: int, mode: str, chunk_steps: int) -> None:
    path = rev_machine(tmp_path)
    chunks, rep, traj = pulses_and_report(REVERSING, level, path, mode, chunk_steps)
    m = load_machine(path)
    col = rep.primary
    # X reverses into X0 (+ to -) and into X10 Y10 (- to +; Y starts in +, its initial direction);
    # X and Y reverse together into X0 Y0 after the dwell (one pause, the longer 6 ms); X into X5
    assert col.category_ns["reversal"] == 4_000_000 + 4_000_000 + 6_000_000 + 4_000_000
    events = [round(e * 1e9) for e in (m.tool_change_s, m.spindle_ramp_s, 0.5, 3.0)]
    assert col.event_ns == sum(events) + col.category_ns["reversal"]
    assert col.total_ns == round(traj.duration_total_s * 1e9) + col.event_ns
    assert sum(col.category_ns.values()) == col.total_ns == int(col.line_ns.sum())
    # the interpolation mode's stream ends with its last (whole) period
    tail_ns = period_count(traj, 0.002) * 2_000_000 - round(traj.duration_total_s * 1e9) if mode == "interp" else 0
    assert chunks[-1].t_end_ns == col.total_ns + tail_ns
    assert chunks[-1].pause_ns == col.category_ns["reversal"] and chunks[-1].event_ns == sum(events)
    assert_stream_guarantees(chunks)
    rows = {r.text: r for r in rep.lines}
    assert rows["X0."].limits_ns.get("machine") == 4_000_000
    assert rows["X10. Y10."].limits_ns.get("machine") == 4_000_000
    whats = [what for _, _, cat, _, what in col.event_list if cat == "reversal"]
    assert "reversal Y" in whats or "reversal X Y" in whats or "reversal Y X" in whats
    doc = report_dict(rep)
    jsonschema.validate(doc, schema())
    assert doc["columns"][0]["by_category"]["reversal"]["time_ns"] == 18_000_000


def test_timing_cli_counts_the_reversals(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    import json

    prog = tmp_path / "rev.nc"
    prog.write_text(REVERSING)
    path = rev_machine(tmp_path)
    args = ["-x", "syntec", "--emit=timing", "-m", path, str(prog)]
    assert main([*args, "--report-format=json", "--compare=O2,O0"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert [c["by_category"]["reversal"]["time_ns"] for c in doc["columns"]] == [18_000_000, 18_000_000]
    assert main(args) == 0
    assert "reversal" in capsys.readouterr().out
