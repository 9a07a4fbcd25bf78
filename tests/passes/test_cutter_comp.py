"""Cutter compensation: interference cases, corner rules, restrictions, look-ahead."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from tests.helpers import compile_text
from tests.passes._frames import close, ends, path, tools_file


@pytest.fixture
def r5(tmp_path: Path) -> str:
    return tools_file(tmp_path, {1: (0.0, 5.0)})


def _diag(text: str, code: str, tools: str) -> tuple[int, list[int]]:
    """(line of the diagnostic, lines of its related locations)."""
    r = compile_text(text, tools_file=tools)
    d = next(d for d in r.sink if d.code == code)
    line = text.count("\n", 0, d.span.start) + 1
    return line, [text.count("\n", 0, rel.span.start) + 1 for rel in d.related]


def test_notch_narrower_than_the_tool_is_a_gouge(r5: str) -> None:
    text = ("G00 X-10. Y10.\nG41 D1 G01 X0 Y0 F100\nX20.\nY-10.\nX24.\n"  # the notch is 4 wide: tool is 10
            "Y0\nX44.\nG40 G00 X44. Y20.\n")
    _, codes = path(text, tools_file=r5)
    assert "E0504" in codes
    line, related = _diag(text, "E0504", r5)
    assert line == 5 and related == [4, 6]  # the notch bottom, with the two walls


def test_chamfer_shorter_than_the_corner_trims_is_a_gouge(r5: str) -> None:
    # a 2 x 2 chamfer in a pocket corner: each 45 degree inside corner trims r tan(22.5) = 2.07
    # off the chamfer's 2.83 mm offset, so the offset chamfer would run backwards
    text = ("G00 X10. Y10.\nG41 D1 G01 X0 Y0 F100\nX38.\nX40. Y2.\nY40.\nX0\nY0\nG40 G00 X10. Y10.\n")
    _, codes = path(text, tools_file=r5)
    assert "E0504" in codes
    assert _diag(text, "E0504", r5) == (4, [3, 5])


def test_chamfer_longer_than_the_corner_trims_is_fine(r5: str) -> None:
    text = ("G00 X10. Y10.\nG41 D1 G01 X0 Y0 F100\nX35.\nX40. Y5.\nY40.\nX0\nY0\nG40 G00 X10. Y10.\n")
    moves, codes = path(text, tools_file=r5)
    assert not [c for c in codes if c.startswith("E")], codes
    c = 35.0 - 5.0 * math.sqrt(2.0)  # the offset chamfer is the line x - y = c
    assert close(ends(moves)[2], (c + 5.0, 5.0)) and close(ends(moves)[3], (35.0, 35.0 - c))


def test_inside_arc_smaller_than_the_tool(r5: str) -> None:
    # a pocket corner rounded with R3 and a tool of radius 5: G41 on a CCW contour is inside
    text = ("G00 X10. Y10.\nG41 D1 G01 X0 Y0 F100\nX37.\nG03 X40. Y3. R3.\nG01 Y40.\nX0\nY0\n"
            "G40 G00 X10. Y10.\n")
    _, codes = path(text, tools_file=r5)
    assert "E0505" in codes
    assert _diag(text, "E0505", r5)[0] == 4


def test_inside_arc_equal_to_the_tool_radius_leaves_the_tool_standing(r5: str) -> None:
    text = "G00 X10. Y10.\nG41 D1 G01 X0 Y0 F100\nX35.\nG03 X40. Y5. R5.\nG01 Y40.\nG40 G00 X10. Y10.\n"
    moves, codes = path(text, tools_file=r5)
    assert not [c for c in codes if c.startswith("E")], codes
    assert ends(moves)[2:4] == [(35.0, 5.0), (35.0, 40.0)]  # through the arc centre, no arc
    assert not [m for m in moves if hasattr(m, "center")]


def test_outside_acute_corner_uses_extensions(r5: str) -> None:
    # G42 on a CCW triangle: the tool is outside; the 45 degree tip gets two extensions of r
    text = "G00 X0 Y-20.\nG42 D1 G01 X0 Y0 F100\nX40.\nX0 Y40.\nY0\nG40 G00 X0 Y-20.\n"
    moves, _ = path(text, tools_file=r5)
    xy = ends(moves)
    k = xy.index((40.0, -5.0))  # end of the bottom edge offset, square to it
    t2 = (-1 / math.sqrt(2), 1 / math.sqrt(2))
    b_start = (40.0 + 5.0 * t2[1], 0.0 - 5.0 * t2[0])
    assert xy[k + 1] == (45.0, -5.0)
    assert close(xy[k + 2], (b_start[0] - 5.0 * t2[0], b_start[1] - 5.0 * t2[1]))
    assert close(xy[k + 3], b_start)


def test_outside_corner_arc_option(r5: str) -> None:
    text = "G00 X0 Y-20.\nG42 D1 G01 X0 Y0 F100\nX40.\nX0 Y40.\nY0\nG40 G00 X0 Y-20.\n"
    moves, _ = path(text, tools_file=r5, dialect_options={"comp_outer_corner": "arc"})
    arcs = [m for m in moves if hasattr(m, "center")]
    assert len(arcs) == 2  # the two corners met in offset mode
    for a in arcs:
        assert a.turns == 1  # G42: round an outside corner counter-clockwise
        assert math.hypot(a.start[0] - a.center[0], a.start[1] - a.center[1]) == pytest.approx(5.0)
        assert math.hypot(a.end[0] - a.center[0], a.end[1] - a.center[1]) == pytest.approx(5.0)


def test_start_up_on_an_arc_is_an_error(r5: str) -> None:
    _, codes = path("G41 D1 G02 X10. Y0 R5. F100\n", tools_file=r5)
    assert "E0503" in codes


def test_cancel_on_an_arc_is_an_error(r5: str) -> None:
    _, codes = path("G41 D1 G01 X10. F100\nX20.\nG40\nG02 X30. R5.\n", tools_file=r5)
    assert "E0503" in codes


def test_plane_change_during_compensation_is_an_error(r5: str) -> None:
    _, codes = path("G41 D1 G01 X10. F100\nX20.\nG18 X30. Z5.\n", tools_file=r5)
    assert "E0509" in codes


def test_lookahead_through_non_motion_blocks(r5: str) -> None:
    base = "G41 D1 G01 X10. Y0 F100\n{}X10. Y20.\nG40 X0 Y20.\n"
    ref, _ = path(base.format(""), tools_file=r5)
    held, codes = path(base.format("M08\nG01 Z-1.\nZ-2.\n"), tools_file=r5)
    assert "W0508" not in codes
    assert ends(ref)[0] == (5.0, 0.0)  # start-up: square to the next element (type A)
    assert ends(held)[:3] == [(5.0, 0.0)] * 3  # the Z moves happen at the settled point


def test_lookahead_exhausted_warns_and_sets_the_vector_square(r5: str) -> None:
    text = "G41 D1 G01 X10. Y0 F100\nX20.\nZ-1.\nZ-2.\nZ-3.\nX20. Y20.\nG40 X0 Y20.\n"
    moves, codes = path(text, tools_file=r5)
    assert "W0508" in codes
    assert ends(moves)[1] == (20.0, 5.0)  # square to X10 -> X20


def test_negative_d_swaps_the_side(tmp_path: Path) -> None:
    tools = tools_file(tmp_path, {1: (0.0, -5.0)})
    moves, _ = path("G41 D1 G01 X10. Y0 F100\nX20.\nG40 X20. Y-20.\n", tools_file=tools)
    assert ends(moves)[1] == (20.0, -5.0)  # right of the path


def test_g91_moves_in_compensation_match_g90(r5: str) -> None:
    a, _ = path("G41 D1 G01 X10. Y0 F100\nX20.\nY10.\nG40 X0 Y10.\n", tools_file=r5)
    b, _ = path("G41 D1 G01 X10. Y0 F100\nG91 X10.\nY10.\nG90 G40 X0 Y10.\n", tools_file=r5)
    assert ends(a) == ends(b)


def test_frames_are_identity_after_the_machine_passes(r5: str) -> None:
    text = ("G54 G52 X5. Y5.\nG43 H1 G51 X0 Y0 P2.\nG68 X0 Y0 R30.\nG51.1 X1.\nG41 D1 G01 X10. Y0 F100\n"
            "X20.\nG40 G50 G69 G50.1 G49 X0 Y0\n")
    moves, _ = path(text, tools_file=r5, emit="timing")
    assert all(m.frame.is_identity for m in moves)
