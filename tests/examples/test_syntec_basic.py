"""SYNTEC worked examples (shared/spec/syntec-mill-v8.20.md section 6) in the
foundation's scope, asserted through the canon trace.  Expected values are the
spec's derived coordinates; timing values are recomputed here from geometry."""

from __future__ import annotations

import math

import pytest

from tests.helpers import calls, canon, codes, moves, nominal


def nominal_total(text: str, **opts: object) -> float:
    return float(nominal(text, **opts).total_s)


START_20_20 = "G90 G00 X20.0 Y20.0 ;\n"


def test_e000_01_g00_absolute() -> None:
    m = moves(START_20_20 + "G90 G00 X90.0 Y40.0 ;\n")
    assert m[-1] == ("STRAIGHT_TRAVERSE", (90.0, 40.0, 0.0))


def test_e000_02_and_54_g00_incremental_same_end() -> None:
    assert moves(START_20_20 + "G91 G00 X70.0 Y20.0 ;\n")[-1] == ("STRAIGHT_TRAVERSE", (90.0, 40.0, 0.0))


def test_e000_03_g01_absolute_default_feed() -> None:
    lines, r = canon(START_20_20 + "G90 G01 X90.0 Y40.0 ;\n")
    assert calls(lines, "STRAIGHT_FEED")[-1][1][:2] == [90.0, 40.0]
    assert "N0212" in codes(r)  # default F1000 used, and said
    length = math.hypot(70.0, 20.0)
    t = nominal_total(START_20_20 + "G90 G01 X90.0 Y40.0 ;\n")
    rapid = nominal_total(START_20_20)
    assert t - rapid == pytest.approx(length / (1000.0 / 60.0), abs=1e-9)
    assert t - rapid == pytest.approx(4.368, abs=5e-4)


def test_e000_04_g01_incremental() -> None:
    m = moves(START_20_20 + "G91 G01 X70.0 Y20.0 ;\n")
    assert m[-1] == ("STRAIGHT_FEED", (90.0, 40.0, 0.0))


E000_05 = """N001 G00 X0.0 Y0.0 Z10.0 ; //positioning to above of P0
N002 G90 G01 Z-10.0 F1000 ; //straight interpolation to bottom of workpiece, speed 1000mm/min
N003 Y38.0 ; //P0 → P1
N004 X20.0 Y45.0 ; //P1 → P2
N005 X55.0 ; //P2 → P3
N006 Y10.0 ; //P3 → P4
N007 X45.0 Y0.0 ; //P4 → P5
N008 X0.0 ; //P5 → P0
N009 G00 Z10.0 ; //positioning back to above of P0
N010 M30 ; //program end
"""

E000_06 = """N001 G00 X0.0 Y0.0 Z10.0 ; //positioning to above of P₀
N002 G91 G01 Z-20.0 F1000 ; //straight interpolation to bottom of workpiece, speed 1000mm/min
N003 Y38.0 ; //P₀ → P₁
N004 X20.0 Y7.0 ; //P₁ → P₂
N005 X35.0 ; //P₂ → P₃
N006 Y-35.0 ; //P₃ → P₄
N007 X-10.0 Y-10.0 ; //P₄ → P₅
N008 X-45.0 ; //P₅ → P₀
N009 G00 Z20.0 ; //positioning back to above of P₀
N011 M30 ; //program end
"""

E000_05_POINTS = [
    ("STRAIGHT_TRAVERSE", (0.0, 0.0, 10.0)),
    ("STRAIGHT_FEED", (0.0, 0.0, -10.0)),
    ("STRAIGHT_FEED", (0.0, 38.0, -10.0)),
    ("STRAIGHT_FEED", (20.0, 45.0, -10.0)),
    ("STRAIGHT_FEED", (55.0, 45.0, -10.0)),
    ("STRAIGHT_FEED", (55.0, 10.0, -10.0)),
    ("STRAIGHT_FEED", (45.0, 0.0, -10.0)),
    ("STRAIGHT_FEED", (0.0, 0.0, -10.0)),
    ("STRAIGHT_TRAVERSE", (0.0, 0.0, 10.0)),
]


def test_e000_05_contour_absolute() -> None:
    assert moves(E000_05) == E000_05_POINTS
    lines, _ = canon(E000_05)
    assert lines[-1].endswith("PROGRAM_END()")


def test_e000_06_incremental_equals_absolute() -> None:
    assert moves(E000_06) == E000_05_POINTS


def test_e000_05_feed_length_time() -> None:
    xy = 38 + math.hypot(20, 7) + 35 + 35 + math.hypot(10, 10) + 45
    assert xy == pytest.approx(188.332, abs=5e-4)
    feed_time = (xy + 20.0) / (1000.0 / 60.0)
    assert feed_time == pytest.approx(12.500, abs=5e-4)
    assert nominal(E000_05).by_category_s["feed"] == pytest.approx(feed_time, rel=1e-12)


E000_07 = """G90 G00 X5500 Y4000;//positioning to start point of arc
G17 G90 G03 X1500 Y4000 I-3000 J-1000 F200;
//absolute command
(G17 G91 G03 X-4000 Y2000 I-3000 J-1000 F200;
//increment command)
"""


def test_e000_07_radius_mismatch_is_an_error() -> None:
    lines, r = canon(E000_07)
    assert "E0208" in codes(r)
    assert not calls(lines, "ARC_FEED")
    err = next(d for d in r.sink if d.code == "E0208")
    src = r.sources.get(err.span.source_id)
    assert src is not None and src.position(err.span.start).line == 2
    # the '(' comment spanning two lines is reported, not a syntax error
    assert "W0103" in codes(r)
    assert "E0101" not in codes(r)


def test_e000_07_lenient_repair_keeps_end_and_moves_centre() -> None:
    lines, r = canon(E000_07, repair_arcs=True)
    assert r.ok
    (_, args), = calls(lines, "ARC_FEED")
    e1, e2, c1, c2 = args[:4]
    assert (e1, e2) == (1.5, 4.0)
    assert math.hypot(5.5 - c1, 4.0 - c2) == pytest.approx(math.hypot(1.5 - c1, 4.0 - c2), abs=1e-4)
    assert "W0511" in codes(r)


def test_e000_08_incremental_arc() -> None:
    prog = "G90 G00 X5500 Y4000;\nG17 G91 G03 X-4000 Y2000 I-3000 J-1000 F200;\n"
    lines, r = canon(prog)
    assert r.ok
    (_, args), = calls(lines, "ARC_FEED")
    assert args == [1.5, 6.0, 2.5, 3.0, 1.0, 0.0, 0.0, 0.0, 0.0]
    radius = math.hypot(3.0, 1.0)
    assert radius == pytest.approx(3.162278, abs=1e-6)
    length = radius * math.pi / 2
    assert length == pytest.approx(4.96729, abs=1e-5)
    t = nominal_total(prog) - nominal_total("G90 G00 X5500 Y4000;\n")
    assert t == pytest.approx(length / (200 / 60), rel=1e-9)
    assert t == pytest.approx(1.490, abs=5e-4)


def test_e000_09_full_circle() -> None:
    prog = "G90 G00 X0 Y0;\nG02 I1000 F100; //interpolate a full circle\n"
    lines, r = canon(prog)
    assert r.ok
    (_, args), = calls(lines, "ARC_FEED")
    assert args[:5] == [0.0, 0.0, 1.0, 0.0, -1.0]
    assert nominal_total(prog) == pytest.approx(2 * math.pi / (100 / 60), rel=1e-9)  # 3.770 s
    assert nominal_total(prog) == pytest.approx(3.770, abs=5e-4)


E000_10 = ("G00 X1000.0 Y0 Z0;\nG17 G03 X0.0 Y1000.0 R1000.0 Z900.0 F600 ;\n"
           "// synchronously with arc of X-Y plane (CCW), do helical interpolation with feedrate 600mm/min\n")


def test_e000_10_helix_projection_feed() -> None:
    lines, r = canon(E000_10)
    assert r.ok
    (_, args), = calls(lines, "ARC_FEED")
    assert args[:6] == [0.0, 1000.0, 0.0, 0.0, 1.0, 900.0]
    t = nominal_total(E000_10) - nominal_total("G00 X1000.0 Y0 Z0;\n")
    assert t == pytest.approx(1000 * math.pi / 2 / 10.0, rel=1e-9)  # 157.08 s: F on the projection
    t3d = nominal_total(E000_10, dialect_options={"helix_feed": "path"}) - nominal_total("G00 X1000.0 Y0 Z0;\n")
    assert t3d == pytest.approx(math.hypot(1000 * math.pi / 2, 900) / 10.0, rel=1e-9)  # 181.04 s


def test_e000_11_dwell_units() -> None:
    prog = "G04 X2500;//delay 2.5 sec\nG04 X2.5;//delay 2.5 sec\nG04 P2500;//delay 2.5 sec\n"
    lines, r = canon(prog)
    assert r.ok
    assert [a for _, a in calls(lines, "DWELL")] == [[2.5], [2.5], [2.5]]


def test_e000_11_decimal_p_policy() -> None:
    lines, r = canon("G04 P2.5;//delay 2 sec (decimal point not permitted)\n")
    assert [a for _, a in calls(lines, "DWELL")] == [[0.002]]
    assert "W0218" in codes(r)
    lines, r = canon("G04 P2.5;\n", dialect_options={"g04_p_decimal": "error"})
    assert not calls(lines, "DWELL") and "E0109" in codes(r)
