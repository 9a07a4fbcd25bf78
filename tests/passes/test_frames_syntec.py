"""SYNTEC worked examples for frames and compensation (syntec-mill-v8.20.md E000-31 ...
E000-41 and the same programs in syntec-900m.md, E004-27 ... E004-37).

Expected coordinates are the ones the specs derive; the 900M manual prints the same
programs with full-width semicolons, which the tests write as ';'.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from tests.passes._frames import close, ends, has_point, path, tools_file

E000_31 = """N001 T1 S1000 M03 ; //tool NO.1(diameter 10mm), spindle 1000rpm (CW)
N002 G00 X0.0 Y0.0 Z10.0 ; //positioning above programmed zero point
N003 M08 ; //open cutting liquid
N004 G90 G01 Z-10.0 F600 ; //linear interpolation to bottom of workpiece, feedrate 600mm/min
N005 G42 Y24.0 D01 ; //cutter compensation left, program zero point->A
N006 G03 X9.0 Y30.0 R10.0 ;
N007 G02 X30.0 Y9.0 R15.0 ;
N008 G03 X30.0 Y-9.0 R10.0 ;
N009 G02 X9.0 Y-30.0 R15.0 ;
N010 G03 X-9.0 Y-30.0 R10.0 ;
N011 G02 X-30.0 Y-9.0 R15.0 ;
N012 G03 X-30.0 Y9.0 R10.0 ;
N013 G02 X-9.0 Y30.0 R15.0 ;
N014 G03 X0.0 Y24.0 R10.0 ;
N015 G00 Z10.0 ; //Z axis rise, return to start point
N016 G40 X0.0 Y0.0 ; //cutter interpolation cancel, return to start point
N017 M09 ;
N018 M05 ;
N019 M30 ;
"""

E000_31_PATH = [  # spec E000-31 "compensated path" (and E004-27)
    (0.0829, 19.0007), (12.8752, 26.5870), (26.5436, 12.8032), (26.5436, -12.8032), (12.8032, -26.5436),
    (-12.8032, -26.5436), (-26.5436, -12.8032), (-26.5436, 12.8032), (-12.8752, 26.5870), (-0.0829, 19.0007),
]


@pytest.mark.parametrize("example", ["E000-31", "E004-27"])
def test_e000_31_four_lobe_pocket(tmp_path: Path, example: str) -> None:
    text = E000_31 if example == "E000-31" else E000_31.replace(" ;", "；").replace("；", ";")
    moves, codes = path(text, tools_file=tools_file(tmp_path, {1: (0.0, 5.0)}))
    assert not [c for c in codes if c.startswith("E")], codes
    xy = ends(moves)
    start = xy.index((0.0, 0.0), 1)  # after the rapid to (0, 0, 10) and the plunge
    contour = xy[start + 1:start + 11]
    assert all(close(a, b) for a, b in zip(contour, E000_31_PATH, strict=True)), contour
    # offset radii: notch arcs R10 -> 15, lobe arcs R15 -> 10 (tool inside, G42 on a CW contour)
    arcs = [m for m in moves if hasattr(m, "center")]
    radii = sorted({round(math.hypot(a.end[0] - a.center[0], a.end[1] - a.center[1]), 4) for a in arcs})
    assert radii == [10.0, 15.0]
    # G00 Z10 at the last offset point, then the G40 move back to the start point
    assert ends(moves, plane=False)[-2:] == [(-0.0829, 19.0007, 10.0), (0.0, 0.0, 10.0)]


E000_32 = """T1 S1000 M03 ;
G42 D01 ; //tool radius compensation right(D01=10)
G00 X10.0 Y5.0 Z15.0 ; //positioning above A point
G43 H01 ; //tool length compensation positive(H01=-10)
G01 Z-10.0 ;
X110.0 ;
Y85.0 ;
X90.0 Y105.0 ;
X50.0 ;
G02 X10.0 Y65.0 R40.0 ;
G01 Y5.0 ;
G00 Z15.0 ;
G40 G49 ;
M05 ;
M30 ;
"""


@pytest.mark.parametrize("example", ["E000-32", "E004-28"])
def test_e000_32_length_and_radius_compensation(tmp_path: Path, example: str) -> None:
    tools = tools_file(tmp_path, {1: (-10.0, 10.0)})
    moves, _codes = path(E000_32, tools_file=tools)
    assert ends(moves) == [(10.0, -5.0), (10.0, -5.0), (120.0, -5.0), (120.0, 89.1421), (94.1421, 115.0),
                           (38.2843, 115.0), (0.0, 76.7157), (0.0, 5.0), (0.0, 5.0)]
    arc = next(m for m in moves if hasattr(m, "center"))
    assert (arc.center[0], arc.center[1], arc.turns) == (pytest.approx(10.0), pytest.approx(105.0), -1)
    assert math.hypot(arc.end[0] - 10.0, arc.end[1] - 105.0) == pytest.approx(30.0)
    # machine coordinates: H01 = -10 lowers every Z after G43 (Z-10 -> -20, Z15 -> 5)
    machine, _ = path(E000_32, tools_file=tools, emit="timing")
    zs = [round(m.end[2], 4) for m in machine]
    assert zs == [15.0, -20.0, -20.0, -20.0, -20.0, -20.0, -20.0, -20.0, 5.0]


E000_33 = """N001 G00 X50.0 Y50.0 ;
N002 G51 X125.0 Y90.0 P0.5 ;
N003 G01 Y70.0 F1000 ;
N004 X100.0 Y150.0 ;
N005 G03 X150.0 I25.0 ;
N006 G01 X200.0 Y70.0 ;
N007 Y50.0 ;
N008 X50.0 ;
N009 G00 X0.0 Y0.0 ;
N010 G50 ;
N011 M30 ;
"""


@pytest.mark.parametrize("example", ["E000-33", "E004-29"])
def test_e000_33_scaling(example: str) -> None:
    moves, _codes = path(E000_33)
    assert ends(moves) == [(50.0, 50.0), (87.5, 80.0), (112.5, 120.0), (137.5, 120.0), (162.5, 80.0),
                           (162.5, 70.0), (87.5, 70.0), (62.5, 45.0)]
    assert moves[1].start[:2] == (50.0, 50.0)  # the first scaled move starts unscaled
    arc = moves[3]
    assert (arc.center[0], arc.center[1], arc.turns) == (125.0, 120.0, 1)  # R 12.5, still CCW
    feed = sum(math.hypot(m.end[0] - m.start[0], m.end[1] - m.start[1]) for m in moves[1:7]
               if not hasattr(m, "center")) + math.pi * 12.5
    assert feed == pytest.approx(266.633, abs=1e-3)


def test_scaling_cancel_keeps_the_machine_where_it_is() -> None:
    """After G50 the commanded X goes to its unscaled target; the uncommanded Y stays at the scaled 45
    (the spec's "machine stays where it is"; issue 17: an uncommanded axis never moves)."""
    moves, _ = path(E000_33.replace("N011 M30 ;", "G01 X10.0 F100\nM30\n"))
    assert moves[-1].start[:2] == (62.5, 45.0) and ends(moves)[-1] == (10.0, 45.0)
    moves, _ = path(E000_33.replace("N011 M30 ;", "G01 X10.0 Y0 F100\nM30\n"))
    assert ends(moves)[-1] == (10.0, 0.0)  # named absolutely: the program position


def test_g50_is_cancel_option_reads_the_code_list() -> None:
    """A-01: with g50_is_cancel = false, G50 scales and G51 cancels (the manual's list)."""
    text = E000_33.replace("G51 X125.0", "G50 X125.0").replace("N010 G50", "N010 G51")
    moves, _ = path(text, dialect_options={"g50_is_cancel": False})
    assert ends(moves)[1] == (87.5, 80.0)


E000_34 = """N001 T1 S1000 M03 ;
N002 M98 H100 ;
N003 G51.1 X60.0 ;
N004 M98 H100 ;
N005 G50.1 ;
N006 G51.1 Y55.0 ;
N007 M98 H100 ;
N008 G50.1 ;
N009 M05 ;
N010 M30 ;
N100 ; //sub-program list
G00 X60.0 Y55.0 ;
G01 Y75.0 ;
X80.0 ;
X120.0 ;
Y105.0 ;
X80.0 Y95.0 ;
Y75.0 ;
M99 ;
"""


@pytest.mark.parametrize("example", ["E000-34", "E004-30"])
def test_e000_34_mirror(example: str) -> None:
    moves, _codes = path(E000_34)
    xy = ends(moves)
    assert xy == [(60.0, 55.0), (60.0, 75.0), (80.0, 75.0), (120.0, 75.0), (120.0, 105.0), (80.0, 95.0),
                  (80.0, 75.0),
                  (60.0, 55.0), (60.0, 75.0), (40.0, 75.0), (0.0, 75.0), (0.0, 105.0), (40.0, 95.0), (40.0, 75.0),
                  (60.0, 55.0), (60.0, 35.0), (80.0, 35.0), (120.0, 35.0), (120.0, 5.0), (80.0, 15.0), (80.0, 35.0)]
    feed = sum(math.hypot(m.end[0] - m.start[0], m.end[1] - m.start[1]) for m in moves if m.motion and
               type(m).__name__ == "Linear")
    assert feed == pytest.approx(513.693, abs=1e-3)


E000_35 = """N001 T1 S1000 M03 ;
N002 G41 D01 ;
N003 M98 H100 ;
N004 G51.1 X0.0 ;
N005 M98 H100 ;
N006 G50.1 ;
N007 G51.1 X0.0 Y0.0 ;
N008 M98 H100 ;
N009 G50.1 ;
N010 G51.1 Y0.0 ;
N011 M98 H100 ;
N012 G50.1 ;
N013 G40 ;
N014 M05 ;
N015 M30 ;
N100 ; sub-program list
G00 X58.0 Y0.0 Z10.0 ;
G01 Z-10.0 ;
G03 X49.36 Y7.9744 R8.0 ;
G03 X40.5415 Y29.2641 R50.0 ;
G03 X29.2641 Y40.5415 R8.0 ;
G03 X7.9744 Y49.36 R50.0 ;
G03 X0.0 Y58.0 R8.0 ;
G00 Z10.0 ;
M99 ;
"""


@pytest.mark.parametrize("example", ["E000-35", "E004-31"])
def test_e000_35_mirror_with_compensation(tmp_path: Path, example: str) -> None:
    moves, codes = path(E000_35, tools_file=tools_file(tmp_path, {1: (0.0, 5.0)}))
    arcs = [m for m in moves if hasattr(m, "center")]
    programmed = [a for a in arcs if abs(math.hypot(a.end[0] - a.center[0], a.end[1] - a.center[1]) - 5.0) > 1e-6]
    # offset radii R8 -> 3 and R50 -> 45: the tool is inside the trough in every call
    radii = {round(math.hypot(a.end[0] - a.center[0], a.end[1] - a.center[1]), 4) for a in programmed}
    assert radii == {3.0, 45.0}
    # arc directions per call: CCW, CW (X mirror), CCW (point mirror), CW (Y mirror)
    turns = [a.turns for a in programmed]
    assert [turns[0], turns[5], turns[10], turns[15]] == [1, -1, 1, -1]
    # first call: square offset points at the first junction (spec E004-31)
    pts = ends(moves)
    assert has_point(pts, (49.7600, 2.9904)) and has_point(pts, (44.4240, 7.1770))
    # X-mirrored call: the same points mirrored; the effective side is G42 and the tool is still inside
    assert has_point(pts, (-49.7600, 2.9904)) and has_point(pts, (-44.4240, 7.1770))
    assert has_point(pts, (-49.7600, -2.9904)) and has_point(pts, (49.7600, -2.9904))
    # petal/circle junctions are outside corners whose offset circles do not meet: arcs, with a warning
    assert codes.count("W0507") == 16
    # G41 stays on across the G00 repositioning between calls; entering the X- and the Y-mirrored
    # calls is an inside corner the tool cannot make: the user sees it at the first arc of the call
    assert codes.count("E0506") == 2


E000_36 = """N001 T1 S1000 M03 ;
N002 G54 X0.0 Y0.0 Z0.0 ;
N003 G00 X90.0 Y15.0 Z10.0 ;
N004 G43 H01 ;
N005 G99 G81 Z-15.0 R2.0 F1000 ;
N006 X110.0 ;
N007 X100.0 Y65.0 ;
N008 G80 ;
N009 M05 ;
N010 G28 X0.0 Y0.0 Z10.0 ;
N011 T2 M06 S1000 M03 ;
N012 G52 X30.0 Y30.0 Z0.0 ;
N013 G00 X0.0 Y0.0 Z10.0;
N014 G01 Z-12.0;
N015 G17 G41 D02 ;
N016 G91 X20.0 ;
N017 Y10.0 ;
N018 X-10.0 ;
N019 Y10.0 ;
N020 X-20.0 ;
N021 Y-10.0 ;
N022 X-10.0 ;
N023 Y-20.0 ;
N024 X10.0 ;
N025 Y-10.0 ;
N026 X20.0 ;
N027 Y10.0 ;
N028 X10.0 ;
N029 Y10.0 ;
N030 G90 G00 Z10.0 ;
N031 G52 X0.0 Y0.0 Z0.0 ;
N032 G40 M05 ;
N033 M30 ;
"""


@pytest.mark.parametrize("example", ["E000-36", "E004-32"])
def test_e000_36_local_system_and_cross_pocket(tmp_path: Path, example: str) -> None:
    tools = tools_file(tmp_path, {1: (0.0, 5.0), 2: (0.0, 5.0)})
    moves, codes = path(E000_36, tools_file=tools)
    assert not [c for c in codes if c.startswith("E")], codes
    xy = ends(moves)
    local = [(15.0, 0.0), (15.0, 5.0), (5.0, 5.0), (5.0, 15.0), (-5.0, 15.0), (-5.0, 5.0), (-15.0, 5.0),
             (-15.0, -5.0), (-5.0, -5.0), (-5.0, -15.0), (5.0, -15.0), (5.0, -5.0), (15.0, -5.0), (15.0, 0.0)]
    k = xy.index((15.0, 0.0))
    assert xy[k:k + 14] == local
    holes = [p for p, m in zip(xy, moves, strict=True) if m.end[2] == -15.0]
    assert holes == [(90.0, 15.0), (110.0, 15.0), (100.0, 65.0)]
    # in machine coordinates the pocket sits at G54 + (30, 30)
    machine, _ = path(E000_36, tools_file=tools, emit="timing")
    mxy = ends(machine)
    k = mxy.index((45.0, 30.0))
    assert mxy[k:k + 14] == [(x + 30.0, y + 30.0) for x, y in local]


def test_e000_37_g92_g53_g52_machine_positions() -> None:
    text = """N001 G92 X-200.0 Y-100.0 ;
N002 G54 G90 X100.0 Y200.0 ;
N003 G53 X300.0 Y100.0 ;
N004 X300.0 Y0 ;
N005 G52 X300.0 Y200.0 ;
N006 X0.0 Y0.0 ;
"""
    machine, _codes = path(text, emit="timing")
    # zero G54: the G92 shift (200, 100) is the program origin in machine coordinates
    assert ends(machine) == [(300.0, 300.0), (300.0, 100.0), (500.0, 100.0), (500.0, 300.0)]


def test_g53_is_not_transformed() -> None:
    text = "G51 X0 Y0 P2.\nG68 X0 Y0 R90.\nG00 G53 X10. Y0\nG00 X10. Y0\n"
    moves, _ = path(text)
    assert ends(moves) == [(10.0, 0.0), (0.0, 20.0)]


POLAR_ROTATION = """G54 X0 Y0 F3000.;
G16;
G90 G00 X50. Y9.207;
M98 H100;
G68 X0 Y0 R90.;
M98 H100;
G68 X0 Y0 R180.;
M98 H100;
G68 X0 Y0 R270.;
M98 H100;
G69;
G15;
M02;
N100
G90 G01 X50. Y9.207;
G03 X50. Y80.793 R50.;
G03 X50. Y99.207 R8.;
M99;
"""


@pytest.mark.parametrize("example", ["E000-40", "E004-36"])
def test_e000_40_polar_and_rotation_close_the_contour(example: str) -> None:
    moves, codes = path(POLAR_ROTATION)
    assert not [c for c in codes if c.startswith("E")], codes
    xy = ends(moves)
    table = [  # spec E000-40: end of the R50 arc and end of the bump for 0, 90, 180, 270 degrees
        ((8.0001, 49.3558), (-8.0001, 49.3558)), ((-49.3558, 8.0001), (-49.3558, -8.0001)),
        ((-8.0001, -49.3558), (8.0001, -49.3558)), ((49.3558, -8.0001), (49.3558, 8.0001)),
    ]
    for arc_end, bump_end in table:
        assert has_point(xy, arc_end) and has_point(xy, bump_end)
    assert close(xy[-1], (49.3558, 8.0001))  # closed: ends at the start point
    bumps = [m for m in moves if hasattr(m, "center") and abs(m.center[0]) + abs(m.center[1]) > 1.0]
    assert [tuple(round(v, 4) + 0.0 for v in b.center[:2]) for b in bumps] == [
        (0.0, 49.3558), (-49.3558, 0.0), (0.0, -49.3558), (49.3558, 0.0)]


def test_e000_40_as_printed_reports_the_defects() -> None:
    """A-49: R8. on a G00/G01 block and the double decimal point are what the manual printed."""
    text = POLAR_ROTATION.replace("G90 G00 X50. Y9.207;", "G90 G00 X50. Y9.207 R8.;").replace(
        "Y80.793 R50.", "Y80.793. R50.")
    moves, codes = path(text)
    assert "W0102" in codes  # 80.793. read leniently, with a warning
    assert close(ends(moves)[-1], (49.3558, 8.0001))


def test_e000_41_eight_copies_and_the_mirrored_flower() -> None:
    rot = "".join(f"G68 X0 Y0 R{a}.;\nM98 H100;\n" for a in range(45, 360, 45))
    text = ("G54 X0 Y0 F3000.;\nG16;\nG90 G00 X50. Y9.207;\nM98 H100;\n" + rot +
            "G69;\nG15;\nG00 X-80. Y0.\nM98 H200;\nG51.1 Y-40.;\nM98 H200;\nG50;\nG90 G00 X0 Y75.\nM02;\n"
            "N100\nG90 G01 X50. Y9.207;\nG03 X50. Y35.793 R50.;\nG03 X50. Y54.207 R8.;\nM99;\n"
            "N200\nG90 G00 X-70. Y10.;\nG91 G03 X-20. R10.;\nG03 Y-20. R10.;\nG03 X20. R10.;\nG03 Y20. R10.;\n"
            "M99;\n")
    moves, _codes = path(text)
    xy = ends(moves)
    for p in [(40.5568, 29.2429), (29.2429, 40.5568), (-8.0001, 49.3558), (-40.5568, 29.2429),
              (-49.3558, -8.0001), (8.0001, -49.3558), (40.5568, -29.2429), (49.3558, 8.0001)]:
        assert has_point(xy, p), p
    # flower 1 (CCW) and flower 2 mirrored about y = -40 even though G91 is modal: CW
    assert has_point(xy, (-90.0, 10.0)) and has_point(xy, (-90.0, -90.0)) and has_point(xy, (-70.0, -70.0))
    flower2 = [m for m in moves if hasattr(m, "center") and m.center[1] < -50.0]
    assert len(flower2) == 4 and all(m.turns == -1 for m in flower2)
    # G50 also cancels the mirror: the G134 hole at (0, 75) is not mirrored
    assert xy[-1] == (0.0, 75.0)


def test_g50_cancels_mirror_only_with_the_option() -> None:
    text = "G51.1 Y-40.\nG50\nG90 G00 X0 Y75.\n"
    assert ends(path(text)[0]) == [(0.0, 75.0)]
    assert ends(path(text, dialect_options={"g50_cancels_mirror": False})[0]) == [(0.0, -155.0)]
