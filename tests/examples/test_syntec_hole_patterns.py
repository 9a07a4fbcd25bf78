"""SYNTEC hole patterns E000-58 ... E000-61 (= 900M E004-54 ... E004-57) and the
drilling part of E000-41.  Hole positions are the spec's tables (3 decimals)."""

from __future__ import annotations

import pytest

from tests.helpers import calls, canon, codes


def run(text: str, **options: object) -> tuple[list[tuple[str, list[float]]], list[str]]:
    lines, r = canon(text, dialect_options=options) if options else canon(text)
    assert r.ok, [d.message for d in r.sink]
    return calls(lines, "STRAIGHT_TRAVERSE", "STRAIGHT_FEED"), codes(r)


def feeds(moves: list[tuple[str, list[float]]]) -> list[tuple[float, float, float]]:
    return [(a[0], a[1], a[2]) for name, a in moves if name == "STRAIGHT_FEED"]


def close(got: list[tuple[float, float]], want: list[tuple[float, float]]) -> None:
    assert len(got) == len(want)
    for g, w in zip(got, want, strict=True):
        assert g == pytest.approx(w, abs=1e-3)


E58 = ("G92 X500.0 Y100.0 ;\nG91 G81 Z-10.0 R5.0 K0 F200 ;\nG134 X200.0 Y100.0 I100.0 J20.0 K6 ;\n"
       "G80 ;\nG90 G0 X0.0 Y0.0 ;\n")
E58_HOLES = [(793.969, 234.202), (717.365, 298.481), (623.396, 264.279), (606.031, 165.798),
             (682.635, 101.519), (776.604, 135.721)]


def test_e000_58_g134_bolt_circle_holes() -> None:
    moves, diags = run(E58)
    close([(x, y) for x, y, _ in feeds(moves)], E58_HOLES)
    # G91: R = initial (0) + 5, bottom = R - 10; the R level is above the initial level
    assert {z for _, _, z in feeds(moves)} == {-5.0}
    assert "W0410" in diags
    # K0 moved nothing: the first move is the positioning over hole 1 at the initial level
    assert moves[0][1][:3] == pytest.approx([793.969, 234.202, 0.0], abs=1e-3)
    assert moves[-1][1][:3] == pytest.approx([0.0, 0.0, 5.0])  # G90 G0 X0 Y0 at the return level


def test_e000_58_return_level_options() -> None:
    """Default: with R above the initial level, G98 returns to R (900M A-27); literal: to I."""
    moves, _ = run(E58)
    assert [a[2] for n, a in moves if n == "STRAIGHT_TRAVERSE"][1:4] == [5.0, 5.0, 5.0]
    moves, _ = run(E58, cycle_return_higher=False)
    zs = [a[2] for n, a in moves if n == "STRAIGHT_TRAVERSE"]
    assert zs[:4] == [0.0, 5.0, 0.0, 0.0]  # over hole 1, up to R, (feed), back to I, over hole 2


def test_e000_59_g135_line_holes() -> None:
    text = "G91 ;\nG81 Z-10.0 R5.0 K0 F100 ;\nG135 X200.0 Y100.0 I100.0 J30.0 K5 ;\nG80 ;\n"
    moves, _ = run(text)
    close([(x, y) for x, y, _ in feeds(moves)],
          [(200.0, 100.0), (286.603, 150.0), (373.205, 200.0), (459.808, 250.0), (546.410, 300.0)])


def test_g135_negative_pitch_runs_the_other_way() -> None:
    moves, _ = run("G91 ;\nG81 Z-10.0 R5.0 K0 F100 ;\nG135 X200.0 Y100.0 I-100.0 J30.0 K2 ;\nG80 ;\n")
    close([(x, y) for x, y, _ in feeds(moves)], [(200.0, 100.0), (113.397, 50.0)])


def test_e000_60_g136_arc_holes_p_in_thousandths_of_a_degree() -> None:
    text = "G91 ;\nG81 Z-10.0 R5.0 K0 F100 ;\nG136 X300.0 Y100.0 I300.0 J10.0 P15000 K6 ;\nG80 ;\n"
    moves, _ = run(text)
    close([(x, y) for x, y, _ in feeds(moves)],
          [(595.442, 152.094), (571.892, 226.785), (529.813, 292.836), (472.073, 345.746),
           (402.606, 381.908), (326.147, 398.858)])


def test_e000_61_g137_1_grid_80_holes_serpentine() -> None:
    text = "G91 ;\nG81 Z-10.0 R5.0 K0 F20 ;\nG137.1 X300.0 Y-100.0 I50.0 P10 J100.0 K8 ;\nG80 ;\n"
    moves, _ = run(text)
    holes = [(x, y) for x, y, _ in feeds(moves)]
    assert len(holes) == 80
    assert set(holes) == {(300.0 + 50 * i, -100.0 + 100 * j) for i in range(10) for j in range(8)}
    assert holes[9] == (750.0, -100.0) and holes[10] == (750.0, 0.0)  # row 2 runs back
    moves, _ = run(text, g137_order="raster")
    assert [(x, y) for x, y, _ in feeds(moves)][10] == (300.0, 0.0)


def test_e000_41_drilling_part_g134_and_g137_1() -> None:
    """Absolute patterns after a K0 block; the tool ends at (100, -100, 2) as on the screenshot."""
    text = ("G00 X-80. Y0.;\nG90 G81 Z-20. R2. F1000. K0;\nG134 X0 Y0 I75. J30. K6;\n"
            "G137.1 X60. Y-60. I20. J-20. P3 K3;\nG80;\nM02;\n")
    moves, _ = run(text)
    holes = [(x, y) for x, y, _ in feeds(moves)]
    close(holes[:6], [(64.952, 37.5), (0.0, 75.0), (-64.952, 37.5), (-64.952, -37.5), (0.0, -75.0),
                      (64.952, -37.5)])
    assert set(holes[6:]) == {(x, y) for x in (60.0, 80.0, 100.0) for y in (-60.0, -80.0, -100.0)}
    assert {z for _, _, z in feeds(moves)} == {-20.0}
    assert moves[-1][1][:3] == pytest.approx([100.0, -100.0, 2.0])


def test_g134_negative_k_runs_clockwise() -> None:
    moves, _ = run("G90 G81 Z-20. R2. F1000. K0;\nG134 X0 Y0 I10. J0. K-4;\nG80;\n")
    close([(x, y) for x, y, _ in feeds(moves)], [(10.0, 0.0), (0.0, -10.0), (-10.0, 0.0), (0.0, 10.0)])
