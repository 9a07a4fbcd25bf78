"""SERIES 8: the manual's examples E001-01 ... E001-19 with the results the spec derives.

Expected values are the spec's (shared/spec/series8.md section 5), in inches as the
examples are; canon traces print program coordinates in program units.  Where the
spec shows the source inconsistent (E001-04's printed block, E001-08's stated move
2 and 3, E001-16's arithmetic), the test checks the spec's derived value and the
diagnostic cncc gives for the printed form.
"""

from __future__ import annotations

import math

import pytest

from tests.helpers import canon, codes, compile_commands, moves, nominal

S8 = "series8"
IN = 25.4


def _xyz(got: list[tuple[str, tuple[float, ...]]]) -> list[tuple[str, tuple[float, ...]]]:
    return [(k, tuple(round(v, 4) for v in p[:3])) for k, p in got]


def test_e001_01_rapid_is_modal_and_z_stays() -> None:
    prog = "G00X1.5Z2. ; move at maximum speed to position X1.5, Z2.\nX5.6 ; move at maximum speed to position X5.6\n"
    assert _xyz(moves(prog, S8)) == [("STRAIGHT_TRAVERSE", (1.5, 0.0, 2.0)), ("STRAIGHT_TRAVERSE", (5.6, 0.0, 2.0))]


E001_02 = """G00XZ ; position to X0 Z0 at max speed
F50 ; set feedrate to 50 IPM
G01X2.5 ; feed to X2.5, Z makes no move;stays at Z0
X1.Z4.6 ; feed to X1., Z4.6
"""


def test_e001_02_bare_letters_are_zero_and_feed_times() -> None:
    assert _xyz(moves("G00X3.Z3.\n" + E001_02, S8))[1:] == [
        ("STRAIGHT_TRAVERSE", (0.0, 0.0, 0.0)), ("STRAIGHT_FEED", (2.5, 0.0, 0.0)), ("STRAIGHT_FEED", (1.0, 0.0, 4.6))]
    t = nominal(E001_02, S8)
    assert t.total_s == pytest.approx(3.0 + math.hypot(1.5, 4.6) / 50 * 60, abs=1e-3)  # 3.000 s + 5.806 s


E001_03 = "\n".join([  # the manual's lines L91-L98, byte for byte
    "G00X0Y0 ; position to location X0 Y0 at max speed",
    "F10 ; set feedrate of 10 IPM",
    "G02X2.Y0R1. ; move in CW direction to X2. Y0 at a radius of 1.this would result in a 180° move",
    "G03X1.Y1. ; move in CCW direction to X1. Y1. at a radius of 1. (last programmed R-code); this would result"
    " in a 90° move.",
    "X0Y0; move in CCW direction to X0 Y0 at a radius of 1. the G03 and the last programmed R-code are modal."
    " The move : made would be 90°.",
    "X1.Y1.R-1.; move in CCW direction to X1 Y1 at a radius of 1.; this",
    "; would result in a 270° move.",
    "G01X1.Y1. ; move in linear mode to X1. Y1.",
    ""])


def test_e001_03_modal_radius_four_arcs_on_one_circle() -> None:
    got = moves(E001_03, S8)
    arcs = [(round(a[0], 4), round(a[1], 4), round(a[2], 4), round(a[3], 4), int(a[4])) for k, a in got
            if k == "ARC_FEED"]
    # end X, end Y, centre X, centre Y, direction (-1 CW, +1 CCW): centre (1, 0) every time
    assert arcs == [(2.0, 0.0, 1.0, 0.0, -1), (1.0, 1.0, 1.0, 0.0, 1), (0.0, 0.0, 1.0, 0.0, 1),
                    (1.0, 1.0, 1.0, 0.0, 1)]
    assert got[-1] == ("STRAIGHT_FEED", (1.0, 1.0, 0.0))  # zero length, no error
    sweeps_deg = [180, 90, 90, 270]
    t = nominal(E001_03, S8)
    assert t.total_s == pytest.approx(sum(math.radians(s) for s in sweeps_deg) / 10 * 60, abs=1e-3)  # 65.973 s


def test_e001_03_first_arc_goes_over_the_top() -> None:
    cmds, _ = compile_commands(E001_03, dialect=S8)
    arc = next(c for c in cmds if type(c).__name__ == "Arc")
    assert arc.turns == -1 and arc.center[:2] == pytest.approx((IN, 0.0))  # CW about (1, 0): through (1, 1)


def test_e001_04_unsigned_j_corrected_block() -> None:
    got = moves("G00X20.Y30.\nF10\nG02 X30. Y20. I0 J10.\n", S8)
    end_x, end_y, cx, cy, turn = got[-1][1][:5]
    assert (end_x, end_y, cx, cy, turn) == pytest.approx((30.0, 20.0, 20.0, 20.0, -1))  # radius 10, CW 90


def test_e001_04_printed_block_is_invalid_arc() -> None:
    # the printed block ends where it starts; under the quadrant rule it is INVALID ARC.
    got, r = canon("G00X20.Y30.\nF10\nG02 X20. Y30. I0 J10.\n", S8)
    assert "E0253" in codes(r)
    assert not [ln for ln in got if "ARC_FEED" in ln]


def test_e001_05_dwell_x_is_seconds_not_a_move() -> None:
    got, r = canon("G00X1.\nG04X5.\n", S8)
    assert [ln.split("N..... ")[1] for ln in got] == ["STRAIGHT_TRAVERSE(1.0000, 0.0000, 0.0000, 0.0000, 0.0000, "
                                                      "0.0000)", "DWELL(5.0000)"]
    assert r.ok


E001_06 = """G00X0Y0 ;Rapid move to 0,0
G01F50G10Y5R.5;Move 1 - inserted .5" arc
G10X10Y0L.25;Move 2 - inserted .25" chamfer
G10Y5R.5;Move 3 - inserted .5" arc
X5 ;Move 4
M30
"""


def test_e001_06_inserted_radius_and_chamfer() -> None:
    got = moves(E001_06, S8)
    rows = [(k, tuple(round(v, 4) for v in (p[:2] if k != "ARC_FEED" else p[:5]))) for k, p in got]
    assert rows == [
        ("STRAIGHT_TRAVERSE", (0.0, 0.0)),
        ("STRAIGHT_FEED", (0.0, 4.191)),  # stated X0Y4.1909 (4.19098 rounds to 4.1910)
        ("ARC_FEED", (0.7236, 4.6382, 0.5, 4.191, -1.0)),  # clockwise, R .5
        ("STRAIGHT_FEED", (9.7764, 0.1118)),
        ("STRAIGHT_FEED", (10.0, 0.25)),  # the chamfer
        ("STRAIGHT_FEED", (10.0, 4.5)),
        ("ARC_FEED", (9.5, 5.0, 9.5, 4.5, 1.0)),  # counter-clockwise, R .5
        ("STRAIGHT_FEED", (5.0, 5.0)),
    ]
    t = nominal(E001_06, S8)
    assert t.total_s == pytest.approx(25.1278 / 50 * 60, abs=2e-3)  # 30.15 s


E001_07 = "\n".join([  # L210-L218
    "T01D01; select tool number 1, offset number 1",
    "G00XY ; position to X0 Y0",
    "G41; activate cutter compensation left",
    "G01X1.; first a move is made to compensate for the cutter radius,then the head is lowered, and finally a"
    " move is made along the X-axis. The final endpoint is determined by the cutter radius.",
    "Y1.; continue milling a square pattern", "X0", "Y0", "G40; cancel cutter compensation", "M30; end program", ""])


def _tools(tmp_path: object, radius_in: float) -> str:
    from pathlib import Path

    path = Path(str(tmp_path)) / "tools.toml"
    path.write_text(f'units = "inch"\n[tools.1]\nradius = {radius_in}\n', encoding="utf-8")
    return str(path)


def test_e001_07_cutter_comp_left_inside_the_square(tmp_path: object) -> None:
    r = 0.1
    got, res = canon("F10\n" + E001_07, S8, tools_file=_tools(tmp_path, r))  # the fragment has no F
    assert "W0252" in codes(res)  # the index and the text disagree on the side
    feeds = [tuple(round(float(v), 4) for v in ln.split("(")[1].split(",")[:2]) for ln in got if "STRAIGHT_FEED" in ln]
    assert feeds == [(0.0, r), (1 - r, r), (1 - r, 1 - r), (r, 1 - r), (r, 0.0)]


def test_e001_07_index_reading_puts_the_tool_outside(tmp_path: object) -> None:
    r = 0.1
    got, _ = canon("F10\n" + E001_07, S8, tools_file=_tools(tmp_path, r),
                   dialect_options={"crc_sides_swapped": True})
    feeds = [tuple(round(float(v), 4) for v in ln.split("(")[1].split(",")[:2]) for ln in got if "STRAIGHT_FEED" in ln]
    assert feeds[:4] == [(0.0, -r), (1 + r, -r), (1 + r, 1 + r), (-r, 1 + r)]


E001_08 = """G00X5Y5 ;move 1
G55R45;turn on rotation with an angle of 45 deg
G01F50X10 ;move 2
Y10 ;move 3
G56 ;turn off rotation
M30
"""


def test_e001_08_rotation_semantics_a() -> None:
    got = _xyz(moves(E001_08, S8))
    c, s = math.cos(math.radians(45)), math.sin(math.radians(45))
    assert got == [("STRAIGHT_TRAVERSE", (5.0, 5.0, 0.0)),
                   ("STRAIGHT_FEED", (round(10 * c - 5 * s, 4), round(10 * s + 5 * c, 4), 0.0)),  # (3.5355, 10.6066)
                   ("STRAIGHT_FEED", (0.0, 14.1421, 0.0))]  # the source's X5 is a doc error


def test_e001_08_rotation_semantics_b_gives_the_stated_move_2() -> None:
    got = _xyz(moves(E001_08, S8, dialect_options={"rotation_unprogrammed_axes": "current_position"}))
    assert got[1:] == [("STRAIGHT_FEED", (7.0711, 7.0711, 0.0)), ("STRAIGHT_FEED", (0.0, 14.1421, 0.0))]


E001_09 = """G00X5Y5 ;move 1
G57R.5;turn on scaling with a factor of .5
G01X6 ;move 2
Y10 ;move 3
X8Y12 ;move 4
G58 ;turn off scaling
"""


def test_e001_09_scaling_about_program_zero() -> None:
    got = _xyz(moves("F10\n" + E001_09, S8))  # no F in the fragment: the feed is inherited
    assert got == [("STRAIGHT_TRAVERSE", (5.0, 5.0, 0.0)), ("STRAIGHT_FEED", (3.0, 2.5, 0.0)),
                   ("STRAIGHT_FEED", (3.0, 5.0, 0.0)), ("STRAIGHT_FEED", (4.0, 6.0, 0.0))]
    t = nominal("F10\n" + E001_09, S8)
    assert t.by_category_s["feed"] == pytest.approx((math.hypot(2, 2.5) + 2.5 + math.sqrt(2)) / 10 * 60, abs=1e-3)


E001_10 = (  # L436-L437 (the first line ends with a blank in the manual)
    'G87 X5. Y6. R3.5 Z3.0 F20. ; drill first hole at X5 Y6, to depth of 3.0" (no retract) \n'
    "R2.0 Z1.0; drill second hole by moving at rapid to Z2.0, then feeding to position of Z1.0\n")


def test_e001_10_case_boring_stays_at_depth() -> None:
    prog = "G00X0Y0Z4.\n" + E001_10
    assert _xyz(moves(prog, S8))[1:] == [
        ("STRAIGHT_TRAVERSE", (5.0, 6.0, 4.0)), ("STRAIGHT_TRAVERSE", (5.0, 6.0, 3.5)),
        ("STRAIGHT_FEED", (5.0, 6.0, 3.0)),  # no retract
        ("STRAIGHT_TRAVERSE", (5.0, 6.0, 2.0)),  # a downward rapid across the gap between walls
        ("STRAIGHT_FEED", (5.0, 6.0, 1.0))]
    t = nominal(prog, S8)
    assert t.by_category_s["feed"] == pytest.approx(1.5 + 3.0, abs=1e-3)


def test_e001_11_and_12_absolute_then_incremental() -> None:
    assert _xyz(moves("G90\nX1.5Z1.5\n", S8)) == [("STRAIGHT_TRAVERSE", (1.5, 0.0, 1.5))]
    got = _xyz(moves("G90\nX1.5Z1.5\nG91\nX.5\nX-.75\n", S8))
    assert [p for _, p in got] == [(1.5, 0.0, 1.5), (2.0, 0.0, 1.5), (1.25, 0.0, 1.5)]


E001_13 = """G00 X5.; position the X-axis to 5.000"
G92 X3.5 ; define this position to now be 3.500"
G00 X5; move to X position 5.000"(the X-axis moves 1.5", from 3.5" ; to 5.0")
"""


@pytest.mark.parametrize("code", ["G92", "G98"])  # E001-13, and E001-19 (the G98 section: the same)
def test_e001_13_and_19_program_zero_preset(code: str) -> None:
    prog = E001_13.replace("G92", code)
    got = _xyz(moves(prog, S8))
    assert [p[0] for _, p in got] == [5.0, 5.0]  # program X
    cmds, r = compile_commands(prog, dialect=S8, emit="timing")  # machine coordinates
    assert r.ok
    xs = [c.end[0] / IN for c in cmds if type(c).__name__ == "Rapid"]
    assert xs == pytest.approx([5.0, 6.5])  # the second rapid moves 1.5 in, from 3.5 to 5.0


def test_e001_14_inverse_time() -> None:
    prog = "G00 X0; position X to 0.0\nG93 F2; set inverse time feedrate of ½ minute (30 seconds)\n" \
           "G01 X10.; move X to a position of 10.\n"
    t = nominal(prog, S8)
    assert t.total_s == pytest.approx(30.0, abs=1e-6)  # 10 in at 20 in/min
    _, r = canon(prog, S8, dialect_options={"g93_f_every_block": True})
    assert "E0211" in codes(r)  # A-29's stricter reading needs F in the G01 block


def test_e001_15_feed_per_minute() -> None:
    t = nominal("G00 X0\nG01 X10. F20.\n", S8)
    assert t.total_s == pytest.approx(30.0, abs=1e-6)


def test_e001_16_feed_per_revolution_is_10_ipm() -> None:
    t = nominal("G00 X0\nM03 S500 ; turn spindle on at 500 RPM\nG95 ; set IPR programming mode\nG01 X10. F.02\n", S8)
    assert t.by_category_s["feed"] == pytest.approx(60.0, abs=1e-6)  # 500 x 0.020 = 10 in/min, not 100


def test_e001_17_g97_is_the_default() -> None:
    got, r = canon("G97\n", S8)
    assert r.ok and got == []


E001_18 = """G00X8.Z0 ; move to diameter of 8 inches
G95F.005 ; sets feedrate of 0.01 IPM
G92R4.S600 ; sets radius as 4 inches and limits RPM to 600
G96S300; sets CSS mode at 300 SFM (initial RPM is 143 RPM)
G01X-.01 ; moves X axis 0.01 inches past center
G01Z.1 ; move Z away from part
G97; return to RPM spindle speed programming mode
"""


def test_e001_18_css_facing_moves_and_records() -> None:
    cmds, r = compile_commands("M03\n" + E001_18, dialect=S8)
    assert r.ok, [d.message for d in r.sink]
    kinds = [(type(c).__name__, tuple(round(v / IN, 4) for v in c.end[:3])) for c in cmds
             if type(c).__name__ in ("Rapid", "Linear")]
    # a lathe program (G92 R S, G96): X is a diameter, the IR holds the radius
    assert kinds == [("Rapid", (4.0, 0.0, 0.0)), ("Linear", (-0.005, 0.0, 0.0)), ("Linear", (-0.005, 0.0, 0.1))]
    ref = next(c for c in cmds if type(c).__name__ == "SetCssReference")
    # R4 at the current X (the G92 R S form, not a preset)
    assert (ref.radius_mm, ref.x_mm) == pytest.approx((4 * IN, 4 * IN))
    speeds = [c.rpm for c in cmds if type(c).__name__ == "SpindleSpeed"]
    assert speeds == [300.0]  # S600 is the clamp of G92 R S, not a spindle speed
    assert not any(type(c).__name__ == "SetG92Offset" for c in cmds)
    # The initial and top speeds the spec derives: 300 ft/min on a 4 in radius, 600 rpm below r*.
    assert 300 * 12 / (2 * math.pi * 4) == pytest.approx(143.24, abs=0.01)
    assert 3600 / (2 * math.pi * 600) == pytest.approx(0.954930, abs=1e-6)


def _facing_min(r0_in: float, r1_in: float, sfm: float, clamp_rpm: float, ipr: float) -> float:
    """Minutes of a radial move r0 -> r1 (0 <= r1 < r0 or through the centre) at F ipr under CSS:
    integral of dr / (F rpm(r)), rpm = min(clamp, 12 sfm / (2 pi r)), in closed form per piece."""
    r_star = 12 * sfm / (2 * math.pi * clamp_rpm)
    outside = math.pi * (r0_in**2 - r_star**2) / (12 * sfm * ipr)  # r0 down to r*, below the clamp
    inside = (r_star + abs(r1_in)) / (clamp_rpm * ipr)  # r* to r1 at the clamp (|r1| < r*)
    return outside + inside


def test_e001_18_nominal_time_integrates_the_css_speed() -> None:
    t = nominal("M03\n" + E001_18, S8)
    feeds = [s for c, s, cat in t.by_command if cat == "feed"]
    facing_s = 60 * _facing_min(4.0, -0.005, 300, 600, 0.005)  # X is a diameter: r = X / 2
    assert facing_s == pytest.approx(177.20, abs=0.01)  # the spec's derived value
    assert feeds == [pytest.approx(facing_s, abs=1e-6), pytest.approx(60 * 0.1 / (600 * 0.005), abs=1e-6)]
    assert feeds[1] == pytest.approx(2.0, abs=1e-6)  # G01 Z.1 at 600 rpm x 0.005 = 3 in/min


def test_e001_18_x_as_radius_option() -> None:
    # With X a radius (A-25's alternative) the tool ends 0.01 in past centre; the
    # manual's "diameter of 8 inches" is then X4. (the same start radius as G92 R4.).
    t = nominal("M03\n" + E001_18.replace("G00X8.", "G00X4.", 1), S8, dialect_options={"lathe_diameter_x": False})
    feeds = [s for c, s, cat in t.by_command if cat == "feed"]
    facing_s = 60 * _facing_min(4.0, -0.01, 300, 600, 0.005)
    assert facing_s == pytest.approx(177.30, abs=0.01)  # the spec's A-25 figure
    assert feeds == [pytest.approx(facing_s, abs=1e-6), pytest.approx(2.0, abs=1e-6)]


def test_diameter_x_only_in_lathe_programs() -> None:
    # no G96 / G92 R S: a mill program, X stays a position; G04 X in a lathe program is a time
    assert _xyz(moves("G00X8.Z1.\n", S8)) == [("STRAIGHT_TRAVERSE", (8.0, 0.0, 1.0))]
    t = nominal("G00X8.\nG04X2.\nG96S100\n", S8)
    assert t.by_category_s["dwell"] == pytest.approx(2.0)
    assert [round(c.end[0] / IN, 4) for c, _, cat in t.by_command if cat == "rapid"] == [4.0]


def test_e001_18_g92_with_both_forms_is_an_error() -> None:
    _, r = canon("G92 X1. R4. S600\n", S8)
    assert codes(r) == ["E0501"]
