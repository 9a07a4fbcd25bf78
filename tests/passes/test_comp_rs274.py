"""LinuxCNC cutter compensation (cncc/passes/comp_rs274.py) against traces printed by rs274 2.9.

Each expected list below is the motion of ``rs274 -g`` (LinuxCNC 2.9.x, Debian linuxcnc-uspace)
for the same program, copied from its output; the oracle suite (tests/oracle) checks generated
programs the same way when rs274 is installed.  These run without it.
"""

from __future__ import annotations

import re
import tempfile
from pathlib import Path

import pytest

from tests.helpers import calls, canon, compile_text

MOTION = ("STRAIGHT_FEED", "ARC_FEED")


def _motion(text: str) -> list[tuple[str, list[float]]]:
    lines, r = canon(text, dialect="linuxcnc")
    assert r.ok, [(d.code, d.message) for d in r.sink]
    return [(n, a[:6] if n == "ARC_FEED" else a[:3]) for n, a in calls(lines, *MOTION)]


def _same(got: list[tuple[str, list[float]]], want: list[tuple[str, list[float]]]) -> None:
    assert [n for n, _ in got] == [n for n, _ in want]
    for (_, g), (_, w) in zip(got, want, strict=True):
        assert g == pytest.approx(w, abs=1e-4)


SQUARE = "G21 F100\nG0 X0 Y-10\n{on} G1 X20 Y0\nG1 X20 Y10\nG40 G1 X0 Y20\nM2\n"
# rs274 2.9: the entry ends r square to itself, an arc about the outside corner, G40 to the point
RIGHT_D4 = [("STRAIGHT_FEED", [20.8944, -1.7889, 0]), ("ARC_FEED", [22, 0, 20, 0, 1, 0]),
            ("STRAIGHT_FEED", [22, 10, 0]), ("STRAIGHT_FEED", [0, 20, 0])]


@pytest.mark.parametrize("on", ["G42.1 D4", "G41.1 D-4"])
def test_negative_dynamic_diameter_swaps_the_side(on: str) -> None:
    _same(_motion(SQUARE.format(on=on)), RIGHT_D4)


def test_z_move_at_an_outside_corner_goes_first_then_the_corner_arc() -> None:
    text = ("G21 F100\nG0 X-10 Y-10\nG42.1 D4 G1 X0 Y0\nG1 X20 Y0\nG1 Z-1\nG1 X20 Y20\nG1 X10 Y10\n"
            "G40 G1 X30 Y30\nM2\n")
    _same(_motion(text), [
        ("STRAIGHT_FEED", [0.8284, -2, 0]), ("STRAIGHT_FEED", [20, -2, 0]), ("STRAIGHT_FEED", [20, -2, -1]),
        ("ARC_FEED", [22, 0, 20, 0, 1, -1]), ("STRAIGHT_FEED", [22, 20, -1]),
        ("ARC_FEED", [18.5858, 21.4142, 20, 20, 1, -1]), ("STRAIGHT_FEED", [8.5858, 11.4142, -1]),
        ("STRAIGHT_FEED", [30, 30, -1])])


def test_inside_corners_back_the_path_up() -> None:
    text = ("G21 F100\nG0 X-10 Y-10\nG41.1 D4 G1 X0 Y0\nG1 X20 Y0\nG1 Z-1\nG1 X20 Y20\nG1 X10 Y10\n"
            "G40 G1 X30 Y30\nM2\n")
    _same(_motion(text), [
        ("STRAIGHT_FEED", [-1.4142, 1.4142, 0]), ("ARC_FEED", [0, 2, 0, 0, -1, 0]), ("STRAIGHT_FEED", [18, 2, 0]),
        ("STRAIGHT_FEED", [18, 2, -1]), ("STRAIGHT_FEED", [18, 15.1716, -1]),
        ("STRAIGHT_FEED", [11.4142, 8.5858, -1]), ("STRAIGHT_FEED", [30, 30, -1])])


@pytest.mark.parametrize("on", ["G41 G2 X20 Y0 R15", "G41\nG2 X20 Y0 R15"])
def test_compensation_may_start_on_an_arc(on: str) -> None:
    # T1 has diameter 0.25 in (r = 3.175 mm): the entry arc keeps its start, its end moves by r.
    tools = "T1 P1 Z12.7 D6.35 ;\n"
    with tempfile.TemporaryDirectory() as tmp:
        tbl = Path(tmp) / "t.tbl"
        tbl.write_text(tools)
        lines, r = canon(f"G21 F100\nT1 M6\nG0 X0 Y-10\n{on}\nM2\n", dialect="linuxcnc", tools_file=str(tbl))
    assert r.ok, [(d.code, d.message) for d in r.sink]
    arcs = [a[:5] for _, a in calls(lines, "ARC_FEED")]
    assert arcs == [pytest.approx([21.1701, 2.9515, 15.4503, -11.4768, -1], abs=1e-4)]


def test_an_arc_just_after_g40_is_an_error() -> None:
    r = compile_text("G21 F100\nG0 X0 Y-10\nG41.1 D4 G1 X20 Y0\nG1 X20 Y10\nG40\nG2 X30 Y20 R20\nM2\n",
                     dialect="linuxcnc")
    assert not r.ok and any("must be straight, not an arc" in d.message for d in r.sink)


def test_an_entry_no_longer_than_the_radius_is_an_error() -> None:
    r = compile_text("G21 F100\nG0 X0 Y0\nG41.1 D10 G1 X3 Y0\nG1 X20\nG40 G1 X30\nM2\n", dialect="linuxcnc")
    assert not r.ok and any("entry move is not greater than the tool radius" in d.message for d in r.sink)


@pytest.mark.parametrize("target", ["fanuc", "grbl"])
def test_translations_keep_a_z_move_a_z_move(target: str) -> None:
    text = ("G21 F100\nG0 X-10 Y-10\nG42.1 D4 G1 X0 Y0\nG1 X20 Y0\nG1 Z-1\nG1 X20 Y20\nG40 G1 X30 Y30\nM2\n")
    r = compile_text(text, dialect="linuxcnc", emit="gcode", target=target)
    assert r.ok
    z_lines = [ln for ln in r.output.splitlines() if re.search(r"\bZ-1", ln)]
    assert len(z_lines) == 1 and not re.search(r"[XY]-?\d", z_lines[0])
