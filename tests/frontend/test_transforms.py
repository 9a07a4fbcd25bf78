"""Front-end handling of the frame codes: G10, lone H/D words, G68/G51 words, polar words."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from tests.helpers import compile_text
from tests.passes._frames import close, ends, path, tools_file


def test_g10_sets_radius_and_length_then_g91_adds_wear() -> None:
    text = ("G10 L12 P1 R4.\nG10 L10 P1 R20.\nG91 G10 L13 P1 R1.\nG10 L11 P1 R-0.5\nG90\n"
            "G43 H1 G00 Z0\nG41 D1 G01 X10. Y0 F100\nX20.\nG40 X20. Y-20.\n")
    moves, codes = path(text, emit="timing")
    assert not [c for c in codes if c.startswith(("E", "W"))], codes
    assert moves[0].end[2] == pytest.approx(19.5)  # length 20 + wear -0.5
    assert ends(moves)[2] == (20.0, 5.0)  # radius 4 + wear 1


def test_g10_r_without_a_point_is_in_micrometres() -> None:
    moves, _ = path("G10 L10 P2 R2500\nG43 H2 G00 Z0\n", emit="timing")
    assert moves[0].end[2] == pytest.approx(2.5)


def test_g10_l2_changes_the_active_work_offset() -> None:
    moves, _ = path("G54 G00 X0 Y0\nG10 L2 P1 X100. Y50.\nG00 X0 Y0\n", emit="timing")
    assert ends(moves) == [(0.0, 0.0), (100.0, 50.0)]


@pytest.mark.parametrize("text, code", [("G10 L99 P1 R1.\n", "E0512"), ("G10 L12 R1.\n", "E0501"),
                                        ("G10 L12 P1\n", "E0501"), ("G51 X0 Y0\n", "E0501"),
                                        ("G51.1\n", "E0501"), ("G68 X0 Y0\n", "W0514"),
                                        ("G41 D7 G01 X1. F100\n", "W0513")])
def test_frame_code_diagnostics(text: str, code: str) -> None:
    assert code in [d.code for d in compile_text(text).sink]


def test_lone_h_changes_the_length_offset_and_h0_cancels(tmp_path: Path) -> None:
    tools = tools_file(tmp_path, {1: (10.0, 0.0), 2: (20.0, 0.0)})
    moves, _ = path("G43 H1 G00 Z0\nZ1. H2\nZ2. H0\n", tools_file=tools, emit="timing")
    assert [m.end[2] for m in moves] == [10.0, 21.0, 2.0]


def test_lone_d_changes_the_radius_in_compensation(tmp_path: Path) -> None:
    tools = tools_file(tmp_path, {1: (0.0, 5.0), 2: (0.0, 2.0)})
    moves, _ = path("G41 D1 G01 X10. Y0 F100\nX20.\nD2 X30.\nG40 X30. Y-20.\n", tools_file=tools)
    assert ends(moves)[1] == (20.0, 5.0) and ends(moves)[3] == (30.0, 2.0)


def test_g68_incremental_angle_adds_to_the_rotation() -> None:
    moves, _ = path("G68 X0 Y0 R30.\nG91 G68 R60.\nG90 G00 X10. Y0\n")
    assert close(ends(moves)[0], (0.0, 10.0))


def test_g68_integer_angle_follows_the_liu_rule() -> None:
    moves, _ = path("G68 X0 Y0 R90000\nG00 X10. Y0\n")  # 90000 x 0.001 deg
    assert close(ends(moves)[0], (0.0, 10.0))


def test_g51_factor_without_a_point_is_in_thousandths() -> None:
    moves, _ = path("G51 X0 Y0 P500\nG01 X10. Y10. F100\n")
    assert ends(moves) == [(5.0, 5.0)]


def test_g51_per_axis_factors_and_ellipse_arc_error() -> None:
    moves, codes = path("G51 X0 Y0 I2. J1.\nG01 X10. Y10. F100\nG02 X20. Y0 R10.\n")
    assert ends(moves)[0] == (20.0, 10.0)
    assert "E0502" in codes


def test_negative_scale_factor_mirrors_arcs_and_the_side() -> None:
    moves, _ = path("G51 X0 Y0 I-1. J1.\nG01 X10. Y0 F100\nG02 X20. Y0 R5.\n")
    assert moves[-1].turns == 1 and ends(moves) == [(-10.0, 0.0), (-20.0, 0.0)]


def test_szgh_g36_scales_only_the_named_axes() -> None:
    moves, _ = path("G36 X0 R2.\nG01 X10. Y10. F100\n", "szgh")
    assert ends(moves) == [(20.0, 10.0)]
    moves, _ = path("G36 X0 R2.\nG01 X10. Y10. F100\n", "szgh", dialect_options={"scale_r_semantics": "divide"})
    assert ends(moves) == [(5.0, 10.0)]


def test_polar_arc_between_polar_points() -> None:
    moves, _ = path("G16\nG00 X10. Y0\nG03 X10. Y90. R10.\nG15\n")
    arc = moves[-1]
    assert close(ends(moves)[-1], (0.0, 10.0)) and arc.turns == 1
    assert math.hypot(arc.center[0], arc.center[1]) == pytest.approx(0.0, abs=1e-9)


def test_polar_incremental_radius_and_angle() -> None:
    moves, _ = path("G16\nG00 X10. Y0\nG91 X5. Y90.\nG90 G15\n")
    assert close(ends(moves)[-1], (0.0, 15.0))


def test_g45_is_refused_in_compensation(tmp_path: Path) -> None:
    tools = tools_file(tmp_path, {1: (0.0, 5.0)})
    _, codes = path("G41 D1 G01 X10. F100\nG45 X20.\n", "szgh", tools_file=tools)
    assert "E0510" in codes


def test_g41_in_an_arc_block_is_refused(tmp_path: Path) -> None:
    _, codes = path("G41 G02 X10. R5. F100\n", tools_file=tools_file(tmp_path, {1: (0.0, 5.0)}))
    assert "E0503" in codes
