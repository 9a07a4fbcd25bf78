"""SZGH worked examples for frames and offsets (szgh-990mdb.md E002-16 ... E002-26)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from tests.passes._frames import close, ends, path, tools_file

SZ = "szgh"
HOLES = [(86.6025, 50.0), (-86.6025, 50.0), (0.0, -100.0)]


def _holes(moves: list[object]) -> list[tuple[float, ...]]:
    return [p for p, m in zip(ends(moves), moves, strict=True) if m.end[2] == -20.0]  # type: ignore[attr-defined]


def test_e002_16_polar_absolute_angles() -> None:
    text = ("N1 G17 G90 G16 X0 Y0;\nN2 G81 X100.0 Y30.0 Z-20.0 R-5.0 F200.0;\nN3 Y150.0;\nN4 Y270.0;\n"
            "N5 G15 G80;\n")
    moves, _codes = path(text, SZ)
    assert _holes(moves) == HOLES


def test_e002_17_polar_incremental_angles() -> None:
    text = "N1 G17 G90 G16;\nN2 G81 X100.0 Y30.0 Z-20.0 R-5.0 F200.0\nN3 G91 Y120.0;\nN4 Y120.0;\nN5 G15 G80;\n"
    moves, _ = path(text, SZ)
    assert [p[:2] for p in _holes(moves)] == HOLES


def test_polar_origin_is_the_current_point_when_g16_is_incremental() -> None:
    moves, _ = path("G00 X10 Y10\nG91 G16\nG90 G00 X5 Y90\nG15\n", SZ)
    assert ends(moves)[-1] == (10.0, 15.0)


KG11 = "N10 G00 G90 X60.0 Y60.0 ;\nN20 G01 X100.0 F100 ;\nN30 G01 Y100.0 ;\nN40 G01 X60.0 Y60.0 ;\nN50 M99 ;\n"
E002_18 = ("N10 G00 G90;\nN20 M98 PKG11;\nN30 G11 X50.0\nN40 M98 PKG11;\nN50 G11 X50.0 Y50.0\nN60 M98 PKG11;\n"
           "N70 G11 Y50.0\nN80 M98 P%9000;\nN90 G12;\nN100 M12;\n")


def test_e002_18_mirror(tmp_path: Path) -> None:
    (tmp_path / "KG11").write_text(KG11)
    fixed = E002_18.replace("P%9000", "PKG11").replace("N100 M12;", "N100 M30;")
    moves, _codes = path(fixed, SZ, include_dirs=[str(tmp_path)])
    assert ends(moves) == [(60.0, 60.0), (100.0, 60.0), (100.0, 100.0), (60.0, 60.0),
                           (40.0, 60.0), (0.0, 60.0), (0.0, 100.0), (40.0, 60.0),
                           (40.0, 40.0), (0.0, 40.0), (0.0, 0.0), (40.0, 40.0),
                           (60.0, 40.0), (100.0, 40.0), (100.0, 0.0), (60.0, 40.0)]


def test_e002_18_as_printed_reports_the_bad_call(tmp_path: Path) -> None:
    (tmp_path / "KG11").write_text(KG11)
    _, codes = path(E002_18, SZ, include_dirs=[str(tmp_path)])
    assert any(c.startswith("E") for c in codes)  # "M98 P%9000" names no program


E002_19 = ("N1 G01 X-500 Y-500 F2000 G17;\nN2 G68 X700 Y300 R60;\nN3 G90 G01 X0 Y0 F2000;\nN4 G91 X1000\n"
           "N5 G02 Y1000 R1000\nN6 G03 X-1000 I-500 J-500;\nN7 G01 Y-1000\nN8 G69\nN9 G90 X-500 Y-500\nN10 M02;\n")


def test_e002_19_rotation_absolute_start() -> None:
    moves, _codes = path(E002_19, SZ)
    xy = ends(moves)
    assert xy == [(-500.0, -500.0), (609.8076, -456.2178), (1109.8076, 409.8076), (243.7822, 909.8076),
                  (-256.2178, 43.7822), (609.8076, -456.2178), (-500.0, -500.0)]
    assert [getattr(m, "turns", 0) for m in moves] == [0, 0, 0, -1, 1, 0, 0]


def test_e002_19_rotation_incremental_start_turns_about_the_tool() -> None:
    moves, _ = path(E002_19.replace("N3 G90 G01 X0 Y0 F2000;", "N3 G91 X500.0 Y500.0"), SZ)
    xy = ends(moves)
    assert xy[1] == (-683.0127, 183.0127)
    # "the rest is the same shape shifted": every later vertex moves by the same vector
    absolute = ends(path(E002_19, SZ)[0])
    shift = (xy[1][0] - absolute[1][0], xy[1][1] - absolute[1][1])
    for a, b in zip(absolute[2:6], xy[2:6], strict=True):
        assert close((a[0] + shift[0], a[1] + shift[1]), b)


def test_e002_20_tool_length_a(tmp_path: Path) -> None:
    tools = tools_file(tmp_path, {1: (20.0, 0.0), 2: (30.0, 0.0)})
    moves, _ = path("G90 G43 Z100.0 H1;\nG90 G43 Z100.0 H2;\n", SZ, tools_file=tools, emit="timing")
    assert [m.end[2] for m in moves] == [120.0, 130.0]  # a new H replaces the old value


def test_e002_21_tool_length_b_acts_on_the_plane_normal(tmp_path: Path) -> None:
    tools = tools_file(tmp_path, {1: (7.0, 0.0)})
    opts = {"tool_length_type": "B"}
    moves, _ = path("G19 G43 H1\nG00 X10. Y0 Z0\nG18 G43 H1\nG00 X0 Y10. Z0\n", SZ, tools_file=tools,
                    emit="timing", dialect_options=opts)
    assert [m.end[:3] for m in moves] == [(17.0, 0.0, 0.0), (0.0, 17.0, 0.0)]


E002_22 = ("N1 G91 G00 X120.0 Y80.0;\nN2 G43 Z-32.0 H1;\nN3 G01 Z-21.0 F1000 ;\nN4 G04 P2000 ;\nN5 G0 Z21.0 ;\n"
           "N6 X30.0 Y-50.0 ;\nN7 G01 Z-41.0 ;\nN8 G00 Z41.0 ;\nN9 X50.0 Y30.0 ;\nN10 G01 Z-25.0 ;\n"
           "N11 G04 P2000 ;\nN12 G00 Z57.0 H0 ;\nN13 X-200.0 Y-60.0 ;\nN14 M2 ;\n")


def test_e002_22_tool_length_program(tmp_path: Path) -> None:
    moves, _codes = path(E002_22, SZ, tools_file=tools_file(tmp_path, {1: (-4.0, 0.0)}), emit="timing")
    assert [round(m.end[2], 4) for m in moves] == [0.0, -36.0, -57.0, -36.0, -36.0, -77.0, -36.0, -36.0, -61.0,
                                                   0.0, 0.0]
    assert ends(moves)[-1] == (0.0, 0.0)


E002_24 = ("N1 G91 G46 G00 X80.0 Y50.0 D01\nN2 G47 G01 X50.0 F120.0\nN3 Y40.0\nN4 G48 X40.0\nN5 Y-40.0;\n"
           "N6 G45 X30.0\nN7 G45 G03 X30.0 Y30.0 J30.0\nN8 G45 G01 Y20.0\nN9 G46 X0\n"
           "N10 G46 G02 X-30.0 Y30.0 J30.0\nN11 G45 G01 Y0 ;\nN12 G47 X-120.0\nN13 G47 Y-80.0\n"
           "N14 G46 G00 X-80.0 Y-50.0\n")


@pytest.mark.parametrize("r", [5.0, 2.5])
def test_e002_24_tool_offsets(tmp_path: Path, r: float) -> None:
    moves, codes = path(E002_24, SZ, tools_file=tools_file(tmp_path, {1: (0.0, r)}))
    assert not [c for c in codes if c.startswith("E")], codes
    expected = [(80 - r, 50 - r), (130 + r, 50 - r), (130 + r, 90 - r), (170 - r, 90 - r), (170 - r, 50 - r),
                (200, 50 - r), (230 + r, 80), (230 + r, 100 + r), (230, 100 + r), (200 + r, 130),
                (200 + r, 130 + r), (80 - r, 130 + r), (80 - r, 50 - r), (0, 0)]
    assert all(close(a, b) for a, b in zip(ends(moves), expected, strict=True))
    arcs = [m for m in moves if hasattr(m, "center")]
    assert [round(math.hypot(a.end[0] - a.center[0], a.end[1] - a.center[1]), 6) for a in arcs] == [30 + r, 30 - r]


def _offset_polygon(pts: list[tuple[float, float]], r: float) -> list[tuple[float, float]]:
    """Inner corners of a polygon offset by r to the left (independent line-line intersections)."""
    n = len(pts)
    out = []
    for k in range(n):
        a, b, c = pts[k - 1], pts[k], pts[(k + 1) % n]
        d1 = ((b[0] - a[0]) / math.dist(a, b), (b[1] - a[1]) / math.dist(a, b))
        d2 = ((c[0] - b[0]) / math.dist(b, c), (c[1] - b[1]) / math.dist(b, c))
        p1 = (a[0] - r * d1[1], a[1] + r * d1[0])
        p2 = (b[0] - r * d2[1], b[1] + r * d2[0])
        den = d1[0] * d2[1] - d1[1] * d2[0]
        t = ((p2[0] - p1[0]) * d2[1] - (p2[1] - p1[1]) * d2[0]) / den
        out.append((p1[0] + t * d1[0], p1[1] + t * d1[1]))
    return out


E002_25 = ("G54 X0 Y0 Z0 ;\nN1 G90 G17 G00 G41 D03 X250.0 Y550.0;\nN2 G01 Y900.0 F150 ;\nN3 X450.0 ;\n"
           "N4 G03 X500.0 Y1150.0 R650.0 ;\nN5 G02 X900.0 R-250.0 ;\nN6 G03 X950.0 Y900.0 R650.0 ;\n"
           "N7 G01 X1150.0 ;\nN8 Y550.0 ;\nN9 X700.0 Y650.0\nN10 X250.0 Y550.0\nN11 G00 G40 X0 Y0\n")


def test_e002_25_cutter_compensation_c(tmp_path: Path) -> None:
    moves, codes = path(E002_25, SZ, tools_file=tools_file(tmp_path, {3: (0.0, 15.0)}))
    assert not [c for c in codes if c.startswith("E")], codes
    xy = ends(moves)
    assert xy[1] == (235.0, 550.0)  # start-up: square to P1 -> P2
    # straight-edged corners (computed independently on the polygon P6..P1): P7 (a 90 degree outside
    # corner) and P9 (inside) at the intersection of the offset lines ...
    poly = [(950.0, 900.0), (1150.0, 900.0), (1150.0, 550.0), (700.0, 650.0), (250.0, 550.0)]
    inner = _offset_polygon(poly, 15.0)
    for p in (inner[1], inner[3]):
        assert any(close(q, p) for q in xy), p
    # ... and P8, an acute outside corner (77.5 degrees), by two extensions of r joined by a line
    t2 = ((700.0 - 1150.0) / math.dist(poly[2], poly[3]), (650.0 - 550.0) / math.dist(poly[2], poly[3]))
    b_start = (1150.0 - 15.0 * t2[1], 550.0 + 15.0 * t2[0])
    k = xy.index((1165.0, 550.0))
    assert xy[k + 1] == (1165.0, 535.0)
    assert close(xy[k + 2], (b_start[0] - 15.0 * t2[0], b_start[1] - 15.0 * t2[1]))
    assert close(xy[k + 3], b_start)
    # arcs keep their centres; radii 650 - 15 (CCW, tool inside) and 250 + 15 (CW, tool outside)
    arcs = [m for m in moves if hasattr(m, "center")]
    radii = [round(math.hypot(a.start[0] - a.center[0], a.start[1] - a.center[1]), 4) for a in arcs]
    assert radii == [635.0, 265.0, 635.0]
    # the last element ends square to P9 -> P1, and G40 returns to (0, 0)
    d = (250.0 - 700.0, 550.0 - 650.0)
    n = math.hypot(*d)
    assert close(xy[-2], (250.0 - 15.0 * d[1] / n, 550.0 + 15.0 * d[0] / n))
    assert xy[-1] == (0.0, 0.0)


def test_e002_26_cancel_without_motion_keeps_the_vector(tmp_path: Path) -> None:
    text = "G41 D1 G01 X0 Y50 F100\nN6 G91 X100.0 Y100.0\nN7 G40;\nN8 X100.0 Z0 ;\n"
    moves, _ = path(text, SZ, tools_file=tools_file(tmp_path, {1: (0.0, 5.0)}))
    s = 5.0 / math.sqrt(2.0)
    assert close(ends(moves)[1], (100.0 - s, 150.0 + s))  # square to N6
    assert moves[2].start[:2] == moves[1].end[:2] and ends(moves)[2] == (200.0, 150.0)  # removed during N8


def test_szgh_offsets_in_micrometres(tmp_path: Path) -> None:
    """The controller keeps tool data in um: a table in "um" units reads as mm."""
    tools = tools_file(tmp_path, {1: (0.0, 5000.0)}, units="um")
    moves, _ = path("N1 G91 G46 G00 X80.0 Y50.0 D01\n", SZ, tools_file=tools)
    assert ends(moves) == [(75.0, 45.0)]
