"""Timing report: exact sums, events, limits, columns, JSON schema, annotation."""

from __future__ import annotations

import json
import math
import re
from typing import Any

import jsonschema
import numpy as np
import pytest

from cncc.api import compile_commands, compile_text
from cncc.backends.timing.aggregate import build_report
from cncc.backends.timing.jsonout import report_dict, schema
from cncc.backends.timing.model import Run
from cncc.driver import resolve_machine
from cncc.ir import MOTION_TYPES, Dwell
from cncc.ir.machine import MachineModel
from cncc.ir.trajectory import Limit, Trajectory

PROGRAM = """%
O1000 (timing test)
N10 G90 G17 G71 G94
N20 T3 M06
N30 S2000 M03
N40 G00 X10. Y0. Z5.
N50 G01 Z-1. F300
N60 X40. F600
N70 G02 X50. Y-10. R10. F400
N80 G04 X2.
N90 M00
N100 S2000 M03
N110 S2500
N120 G01 Y-30.
N130 T7 M06
N140 G00 Z20.
N150 M30
%
"""


def machine() -> MachineModel:
    m = resolve_machine("generic-mill", None)  # type: ignore[arg-type]
    assert m is not None
    return m


def synthetic_plan(cmds: list[Any]) -> Trajectory:
    """A planner-like trajectory: accel / cruise / decel phases of odd lengths per motion."""
    rows: list[tuple[float, int, int]] = []
    for i, c in enumerate(cmds):
        if isinstance(c, MOTION_TYPES):
            rows += [(0.0123456789 * (i + 1), i, int(Limit.ACCEL)), (0.3141592653 * (i + 1), i, int(Limit.FEED)),
                     (0.0271828182, i, int(Limit.JERK))]
    dur = np.array([r[0] for r in rows])
    t0 = np.concatenate(([0.0], np.cumsum(dur)[:-1]))
    z = np.zeros((len(rows), 6))
    return Trajectory(t0, dur, z, z.copy(), z.copy(), z.copy(), np.array([r[1] for r in rows], dtype=np.int64),
                      np.array([r[2] for r in rows], dtype=np.int8))


def report(program: str = PROGRAM, traj: Trajectory | None = None) -> tuple[Any, list[Any], Trajectory]:
    cmds, res = compile_commands(program)
    assert res.ok, [d.message for d in res.sink]
    t = traj if traj is not None else synthetic_plan(cmds)
    rep = build_report(cmds, [Run("O2", machine(), 2, t, "synthetic")], res.sources, "<text>", "syntec")
    return rep, cmds, t


def test_total_is_trajectory_plus_events_and_lines_add_up() -> None:
    rep, _cmds, traj = report()
    m = machine()
    # events of PROGRAM, from the machine model: two tool changes, the M03 start, the S2500
    # change while running (the repeated S2000 M03 costs nothing), the 2 s dwell, M00
    events_s = [m.tool_change_s, m.spindle_ramp_s, 2.0, m.optional_stop_s, m.spindle_ramp_s, m.tool_change_s]
    col = rep.primary
    assert col.total_ns == round(traj.duration_total_s * 1e9) + sum(round(e * 1e9) for e in events_s)
    assert col.event_ns == sum(round(e * 1e9) for e in events_s)
    assert sum(r.times_ns[0] for r in rep.lines) == col.total_ns
    assert sum(col.category_ns.values()) == col.total_ns
    assert sum(sum(v.values()) for v in col.tool_ns.values()) == col.total_ns
    assert sum(t[0] for _n, t in rep.blocks()) == col.total_ns
    assert math.isclose(col.total_ns / 1e9, math.fsum(traj.duration_s) + math.fsum(events_s), abs_tol=1e-8)


def test_lines_blocks_tools_and_limits() -> None:
    rep, cmds, traj = report()
    by_n = {r.n: r for r in rep.lines}
    m = machine()
    assert by_n["N20"].times_ns[0] == round(m.tool_change_s * 1e9)
    assert by_n["N20"].limited_by == "machine"
    assert by_n["N80"].limited_by == "program" and by_n["N80"].times_ns[0] == 2_000_000_000
    assert by_n["N90"].operator_dependent and by_n["N90"].limited_by in ("operator", "")
    assert by_n["N100"].times_ns[0] == 0  # spindle already at 2000 rpm clockwise
    assert by_n["N110"].times_ns[0] == round(m.spindle_ramp_s * 1e9)
    assert by_n["N60"].limited_by == "feed"  # the cruise phase is the longest
    assert set(by_n["N60"].limits_ns) == {"accel", "feed", "jerk"}
    i60 = [i for i, c in enumerate(cmds) if isinstance(c, MOTION_TYPES)][2]  # N40 G00, N50 G01, N60 G01
    k = np.flatnonzero(traj.cmd_index == i60)
    expected_ns = round((traj.t0_s[k[-1]] + traj.duration_s[k[-1]]) * 1e9) - round(traj.t0_s[k[0]] * 1e9)
    assert by_n["N60"].times_ns[0] == expected_ns
    assert by_n["N60"].limits_ns["feed"] == round(traj.duration_s[k[1]] * 1e9)
    tools = rep.primary.tool_ns
    assert tools[7]["tool_change"] == round(m.tool_change_s * 1e9)  # the change is charged to the new tool
    assert tools[7]["rapid"] > 0 and tools[3]["arc"] > 0
    assert rep.lines[-1].elapsed_ns == rep.primary.total_ns
    top = [r.times_ns[0] for r in rep.top()]
    assert len(top) == 10 and top == sorted(top, reverse=True)
    assert top[0] == max(r.times_ns[0] for r in rep.lines)


def test_a_command_the_planner_timed_is_not_an_event_too() -> None:
    cmds, res = compile_commands("G01 X10. F600\nG04 X2.\nG01 X20.\n")
    dwell = next(i for i, c in enumerate(cmds) if isinstance(c, Dwell))
    moves = [i for i, c in enumerate(cmds) if isinstance(c, MOTION_TYPES)]
    order = [moves[0], dwell, moves[1]]
    dur = np.array([1.0, 2.0, 1.0])
    z = np.zeros((3, 6))
    traj = Trajectory(np.array([0.0, 1.0, 3.0]), dur, z, z.copy(), z.copy(), z.copy(),
                      np.array(order, dtype=np.int64), np.array([1, 0, 1], dtype=np.int8))
    rep = build_report(cmds, [Run("O2", machine(), 2, traj)], res.sources, "<text>", "syntec")
    assert rep.primary.total_ns == 4_000_000_000
    assert rep.primary.event_ns == 0


def test_json_validates_against_the_schema() -> None:
    r = compile_text(PROGRAM, emit="timing", report_format="json", opt_level=1)
    assert r.ok
    doc = json.loads(r.output)
    validator = jsonschema.Draft202012Validator(schema())
    validator.validate(doc)
    assert doc["total_ns"] == sum(line["times_ns"][0] for line in doc["lines"])
    col = doc["columns"][0]
    assert col["total_ns"] == col["trajectory_ns"] + col["events_ns"]
    assert doc["columns"][doc["nominal_column"]]["nominal"] is True
    broken = dict(doc)
    del broken["lines"]
    assert not validator.is_valid(broken)
    broken = {**doc, "lines": [{**doc["lines"][0], "limited_by": "magic"}]}
    assert not validator.is_valid(broken)


def test_nominal_column_matches_length_over_feed() -> None:
    cmds, res = compile_commands("G00 Z5.\nG01 X30. Y40. F600\n")
    m = machine()
    from cncc.backends.nominal import nominal_trajectory

    rep = build_report(cmds, [Run("O0", m, 0, nominal_trajectory(cmds, m), nominal=True)], res.sources, "x",
                       "syntec")
    z_rapid_s = 5.0 / (m.axis("Z").rapid_mm_min / 60.0)  # type: ignore[union-attr]
    assert rep.primary.total_ns == round((z_rapid_s + 5.0) * 1e9)
    assert report_dict(rep)["columns"][0]["by_category"]["rapid"]["time_ns"] == round(z_rapid_s * 1e9)


def test_compare_columns_levels_and_machines() -> None:
    r = compile_text(PROGRAM, emit="timing", report_format="json", compare="O0,O1")
    doc = json.loads(r.output)
    assert [c["label"] for c in doc["columns"]] == ["O0", "O1"]
    assert all(len(line["times_ns"]) == 2 for line in doc["lines"])
    r = compile_text(PROGRAM, emit="timing", report_format="json", compare="generic-mill@O0,szgh-990mdb@O0")
    doc = json.loads(r.output)
    assert [c["machine"] for c in doc["columns"]] == ["generic-mill", "szgh-990mdb"]
    gm, sz = (resolve_machine(n, None) for n in ("generic-mill", "szgh-990mdb"))  # type: ignore[arg-type]
    assert gm is not None and sz is not None
    changes = [c["by_category"]["tool_change"]["time_ns"] for c in doc["columns"]]
    assert changes == [2 * round(gm.tool_change_s * 1e9), 2 * round(sz.tool_change_s * 1e9)]


@pytest.mark.parametrize("bad", ["O7", "O1@O2@x@y", ","])
def test_bad_compare_is_a_diagnostic(bad: str) -> None:
    r = compile_text(PROGRAM, emit="timing", compare=bad)
    assert not r.ok
    assert [d.code for d in r.sink] == ["E0904"]


def test_text_report_has_totals_and_slowest_blocks() -> None:
    r = compile_text(PROGRAM, emit="timing", opt_level=0)
    assert r.ok
    assert "the 10 slowest blocks" in r.output
    assert "tool change" in r.output and "N130" in r.output
    assert "operator-dependent" in r.output


def test_annotated_program_compiles_to_the_same_motion() -> None:
    r = compile_text(PROGRAM, emit="timing", annotate_time=True, opt_level=0)
    assert r.ok
    out = r.output.splitlines()
    src = PROGRAM.splitlines()
    assert len(out) == len(src)
    notes = [re.search(r"\(t ([\d.]+) s \+([\d.]+) s\)", ln) for ln in out]
    for before, after, note in zip(src, out, notes, strict=True):
        if note is None:
            assert after == before
    timed = [n for n in notes if n is not None]
    assert len(timed) >= 14  # every block from N20 on
    elapsed = [float(n.group(1)) for n in timed]
    assert elapsed == sorted(elapsed)
    total = json.loads(compile_text(PROGRAM, emit="timing", report_format="json", opt_level=0).output)["total_s"]
    assert elapsed[-1] == pytest.approx(total, abs=1e-3)
    assert sum(float(n.group(2)) for n in timed) == pytest.approx(total, abs=1e-3 * len(timed))
    def motion(text: str) -> list[str]:
        return [ln for ln in compile_text(text, emit="canon").output.splitlines() if "COMMENT(" not in ln]

    assert motion(r.output) == motion(PROGRAM)


@pytest.mark.parametrize(("comments", "block_end", "line", "expected"), [
    (("paren", "slash"), ";", "G01 X1. // go", "G01 X1. (t=1 s) // go"),
    (("paren", "slash"), ";", "G01 X1.;", "G01 X1. (t=1 s) ;"),
    (("paren",), "", "G01 X1. (a) Y2.", "G01 X1. (a) Y2. (t=1 s)"),
    (("semicolon", "paren"), "", "G01 X1. ; go", "G01 X1. ; go t=1 s"),
    (("semicolon", "paren"), "", "G01 X1.", "G01 X1. ; t=1 s"),
    (("slash",), ";", "G01 X1.;", "G01 X1.; // t=1 s"),
])
def test_annotation_uses_the_dialect_comment_syntax(comments: tuple[str, ...], block_end: str, line: str,
                                                    expected: str) -> None:
    from types import SimpleNamespace

    from cncc.backends.timing.annotate import annotate_line

    dialect = SimpleNamespace(comments=comments, block_end=block_end)
    assert annotate_line(line, "t=1 s", dialect) == expected  # type: ignore[arg-type]


def test_progress_bar_only_on_a_terminal() -> None:
    import io

    from cncc.backends.timing import progress

    class Tty(io.StringIO):
        def isatty(self) -> bool:
            return True

    items = list(range(progress.MIN_ITEMS))
    pipe, tty = io.StringIO(), Tty()
    assert list(progress.track(items, len(items), "x", pipe)) == items
    assert pipe.getvalue() == ""
    assert list(progress.track(items, len(items), "x", tty)) == items
    assert progress.wanted(len(items), tty) and not progress.wanted(10, tty)
    cmds, _ = compile_commands(PROGRAM)
    assert list(progress.track_source(iter(cmds), 10**8, 0, pipe)) == cmds
    assert list(progress.track_source(iter(cmds), 10**8, 0, tty)) == cmds
    with progress.stage("planning", 10**6, pipe):
        pass
    assert pipe.getvalue() == ""
    assert "reading the program" in tty.getvalue()


LOOP = """O0002
G90 G71 G94
T2 M06
#1=0
WHILE [#1 LT 3] DO1
G91 G01 X10. F600
G04 X0.5
#1=#1+1
END1
G90 G00 Z5.
M30
"""


def test_expanded_program_gets_a_time_after_every_executed_block() -> None:
    r = compile_text(LOOP, emit="gcode", expand=True, annotate_time=True, opt_level=1)
    assert r.ok, [d.message for d in r.sink]
    notes = re.findall(r"\(t ([\d.]+) s \+([\d.]+) s\)", r.output)
    assert len(notes) == 1 + 3 * 2 + 2  # T2 M06, three passes of (G01, G04), G00, M30
    elapsed = [float(e) for e, _ in notes]
    assert elapsed == sorted(elapsed)
    assert [float(d) for _, d in notes][2:7:2] == [0.5, 0.5, 0.5]  # each pass's dwell
    total = json.loads(compile_text(LOOP, emit="timing", report_format="json", opt_level=1).output)["total_s"]
    assert elapsed[-1] == pytest.approx(total, abs=1e-3)
    plain = compile_text(LOOP, emit="gcode", expand=True, opt_level=1).output

    def motion(text: str) -> list[str]:
        return [ln for ln in text.splitlines() if not ln.startswith("(")]

    assert motion(r.output) == motion(plain)


@pytest.mark.parametrize("program", ["", "(only a comment)\n", "G04 X1.\nM00\n", "G01 X0 F100\n", "G00 X10.\n",
                                     "N10 G01 X10. F600\nN10 X20.\nN20 X30.\n"])
def test_odd_programs_give_valid_reports(program: str) -> None:
    validator = jsonschema.Draft202012Validator(schema())
    doc = json.loads(compile_text(program, emit="timing", report_format="json", opt_level=0).output)
    validator.validate(doc)
    assert doc["total_ns"] == sum(line["times_ns"][0] for line in doc["lines"])
    assert sum(b["times_ns"][0] for b in doc["blocks"]) == doc["total_ns"]
    page = compile_text(program, emit="timing", report_format="html", opt_level=0).output
    assert page.count("<canvas") == 5 and 'id="cncc-data"' in page
    assert compile_text(program, emit="timing", opt_level=0).output.startswith("cycle time")


# (12 integer digits: the most cncc reads, E0161 refuses more; still far beyond MAX_S)
@pytest.mark.parametrize("program", ["G04 X999999999999.\n", "G01 X1. F0.000000000000000000001\n",
                                     "G01 X999999999999. F1.\nG04 X999999999999.\n"])
def test_absurd_times_are_clamped_with_a_warning(program: str) -> None:
    from cncc.backends.timing.model import MAX_S

    r = compile_text(program, emit="timing", report_format="json", opt_level=0)
    assert r.ok
    assert "W0690" in [d.code for d in r.sink]
    doc = json.loads(r.output)
    jsonschema.Draft202012Validator(schema()).validate(doc)
    assert 0 < doc["total_s"] <= 2 * MAX_S
    assert doc["total_ns"] == sum(line["times_ns"][0] for line in doc["lines"])
