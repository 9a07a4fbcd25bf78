"""SYNTEC examples for reference returns, G52, G53 and G92 (E000-20 ... E000-24,
E000-36, E000-37, E000-55).  The reference positions are the machine model's
(``generic-mill``: all zero unless a user's model says otherwise); a test machine
file with distinct positions checks that G28/G30 use the right one."""

from __future__ import annotations

from pathlib import Path

from tests.helpers import calls, canon, codes, moves

MACHINE = """name = "test-refs"
base = "generic-mill"
reference_positions_mm = [[500.0, 400.0, 300.0, 0, 0, 0], [10.0, 20.0, 30.0, 0, 0, 0],
                          [11.0, 21.0, 31.0, 0, 0, 0], [12.0, 22.0, 32.0, 0, 0, 0]]
"""


def machine_file(tmp_path: Path) -> str:
    p = tmp_path / "refs.toml"
    p.write_text(MACHINE)
    return str(p)


def test_e000_20_g28_via_intermediate(tmp_path: Path) -> None:
    m = moves("G00 X5. Y5. Z7.;\nG90 G28 X50.0 Y30.0; //A→B→C, mid-point(50,30)\n", machine=machine_file(tmp_path))
    assert m[1:] == [("STRAIGHT_TRAVERSE", (50.0, 30.0, 7.0)),   # B, Z does not move
                     ("STRAIGHT_TRAVERSE", (500.0, 400.0, 7.0))]  # C = reference, X and Y only


def test_e000_21_g28_single_axes(tmp_path: Path) -> None:
    prog = "G00 X5. Y6. Z7.;\nG28 X0; //only X\nG28 Y0; //only Y\nG28 Z0; //only Z\n"
    m = moves(prog, machine=machine_file(tmp_path))
    assert m[1:] == [
        ("STRAIGHT_TRAVERSE", (0.0, 6.0, 7.0)), ("STRAIGHT_TRAVERSE", (500.0, 6.0, 7.0)),
        ("STRAIGHT_TRAVERSE", (500.0, 0.0, 7.0)), ("STRAIGHT_TRAVERSE", (500.0, 400.0, 7.0)),
        ("STRAIGHT_TRAVERSE", (500.0, 400.0, 0.0)), ("STRAIGHT_TRAVERSE", (500.0, 400.0, 300.0)),
    ]


def test_e000_22_g28_g29_absolute(tmp_path: Path) -> None:
    prog = ("N001 G90 G28 X20.0 Y30.0;\n//A→B→C, mid-point(20,40), in absolute command mode\n"
            "N002 M06;//change the tool\nN003 G29 X40.0 Y0.0;\n// C→B→D, the specified point is absolute coordinate\n")
    lines, r = canon(prog, machine=machine_file(tmp_path))
    assert r.ok
    m = [(n, tuple(a[:2])) for n, a in calls(lines, "STRAIGHT_TRAVERSE")]
    assert m == [("STRAIGHT_TRAVERSE", (20.0, 30.0)), ("STRAIGHT_TRAVERSE", (500.0, 400.0)),
                 ("STRAIGHT_TRAVERSE", (20.0, 30.0)), ("STRAIGHT_TRAVERSE", (40.0, 0.0))]
    assert [n for n, _ in calls(lines, "CHANGE_TOOL")] == ["CHANGE_TOOL"]


def test_e000_23_g28_g29_incremental(tmp_path: Path) -> None:
    prog = ("N001 G91 G28 X20.0 Y40.0;\nN002 M06;//change the tool\nN003 G29 X40.0 Y-40.0;\n")
    m = [(n, a[:2]) for n, a in moves(prog, machine=machine_file(tmp_path))]
    # B = A + (20, 40) with A = (0, 0); D = B + (40, -40) = (60, 0)
    assert m == [("STRAIGHT_TRAVERSE", (20.0, 40.0)), ("STRAIGHT_TRAVERSE", (500.0, 400.0)),
                 ("STRAIGHT_TRAVERSE", (20.0, 40.0)), ("STRAIGHT_TRAVERSE", (60.0, 0.0))]


def test_e000_24_g30_second_and_third_reference(tmp_path: Path) -> None:
    mf = machine_file(tmp_path)
    start = "G00 X60.0 Y10.0;\n"
    m2 = moves(start + "G30 P2 X75.0 Y25.0 ; //A→B→ 2nd reference point\n", machine=mf)
    assert m2[1:] == [("STRAIGHT_TRAVERSE", (75.0, 25.0, 0.0)), ("STRAIGHT_TRAVERSE", (10.0, 20.0, 0.0))]
    m3 = moves(start + "G30 P3 X15.0 Y10.0 ; //A→C→ 3rd reference point\n", machine=mf)
    assert m3[1:] == [("STRAIGHT_TRAVERSE", (15.0, 10.0, 0.0)), ("STRAIGHT_TRAVERSE", (11.0, 21.0, 0.0))]
    _, r = canon(start + "G30 P5 X1.0;\n", machine=mf)
    assert "E0215" in codes(r)


def test_e000_55_g92_sets_current_position() -> None:
    lines, r = canon("G92 X20.0 Y15.0 Z20.0 ;\nG01 X21.0 F100;\n")
    assert r.ok
    assert calls(lines, "SET_G92_OFFSET") == [("SET_G92_OFFSET", [-20.0, -15.0, -20.0, 0.0, 0.0, 0.0])]
    assert not calls(lines[:-2], "STRAIGHT_FEED", "STRAIGHT_TRAVERSE")  # no motion from G92
    assert calls(lines, "STRAIGHT_FEED")[0][1][:3] == [21.0, 15.0, 20.0]


E000_37 = """N001 G92 X-200.0 Y-100.0 ; //specify to basic coordinate system
N002 G54 G90 X100.0 Y200.0 ; //to specified position on workpiece coordinate system
N003 G53 X300.0 Y100.0 ; //to specified position on machine coordinate system
N004 X300.0 Y0 ;
//because of G53 only effective in one block, this block continue G54 to the specified position on workpiece coordinate system
N005 G52 X300.0 Y200.0 ; //set local coordinate to specified position on workpiece coordinate system
N006 X0.0 Y0.0 ;
"""


def test_e000_37_g53_machine_coordinates(tmp_path: Path) -> None:
    offsets = tmp_path / "off.toml"
    offsets.write_text("[work.G54]\nX = 10.0\nY = 20.0\n")
    lines, r = canon(E000_37, offsets_file=str(offsets))
    assert r.ok, [d.message for d in r.sink]
    trav = [tuple(a[:2]) for _, a in calls(lines, "STRAIGHT_TRAVERSE")]
    # program = machine - (G54 + G92): G54 (10, 20), G92 shift (200, 100) from N001 at (0,0)
    assert trav[0] == (100.0, 200.0)                 # N002 in work coordinates
    assert trav[1] == (300.0 - 210.0, 100.0 - 120.0)  # N003: machine (300, 100)
    assert trav[2] == (300.0, 0.0)                   # N004 back in work coordinates
    assert trav[3] == (0.0, 0.0)                     # N006: local origin = work (300, 200)
    g92 = calls(lines, "SET_G92_OFFSET")
    assert g92[0][1][:2] == [200.0, 100.0]
    assert g92[-1][1][:2] == [500.0, 300.0]          # G52 (300, 200) reported with the G92 shift


E000_36_PART = """N001 T1 S1000 M03 ; //tool No.1(diameter 10mm), spindle 1000rpm (CW)
N002 G54 X0.0 Y0.0 Z0.0 ; //specify work coordinate (G54)
N003 G00 X90.0 Y15.0 Z10.0 ; //positioning to above of specified position
N009 M05 ; //spindle stops
N010 G28 X0.0 Y0.0 Z10.0 ; //reference point return, X0.0,Y0.0,Z10.0 to be center point
N011 T2 M06 S1000 M03 ; //execute tool exchange
N012 G52 X30.0 Y30.0 Z0.0 ; //specify local coordinate zero point
N013 G00 X0.0 Y0.0 Z10.0; //positioning to local coordinate X0.0,Y0.0,Z10.0(above the hole)
N014 G01 Z-12.0; //linear interpolation to bottom of the hole
N030 G90 G00 Z10.0 ; //specify to use absolute positioning
N031 G52 X0.0 Y0.0 Z0.0 ; //cancel local coordinate
N033 M30 ; //program ends
"""


def test_e000_36_local_coordinates() -> None:
    """The G52 part of E000-36 (its drilling and cutter-compensation blocks are
    covered by the cycle and compensation suites)."""
    lines, r = canon(E000_36_PART)
    assert r.ok, [d.message for d in r.sink]
    trav = [tuple(a[:3]) for _, a in calls(lines, "STRAIGHT_TRAVERSE")]
    assert trav[0] == (0.0, 0.0, 0.0) and trav[1] == (90.0, 15.0, 10.0)
    assert trav[2] == (0.0, 0.0, 10.0) and trav[3] == (0.0, 0.0, 0.0)  # G28 via (0,0,10) to the reference
    assert trav[4] == (0.0, 0.0, 10.0)  # N013: local (0,0,10) ...
    g92 = [a[:3] for _, a in calls(lines, "SET_G92_OFFSET")]
    assert g92[0] == [30.0, 30.0, 0.0]  # ... which is G54 (30, 30, 10)
    assert g92[-1] == [0.0, 0.0, 0.0]   # N031 cancels
    assert calls(lines, "STRAIGHT_FEED")[0][1][:3] == [0.0, 0.0, -12.0]
    assert calls(lines, "SELECT_TOOL") == [("SELECT_TOOL", [1.0]), ("SELECT_TOOL", [2.0])]
