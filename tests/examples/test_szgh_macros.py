"""SZGH macro and subprogram examples E002-40 ... E002-51 and E002-60 ... E002-62
(shared/spec/szgh-990mdb.md section 4), asserted through the canon trace with the
positions the spec derives."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from tests.helpers import calls, canon, codes, compile_text, moves

SZ = "szgh"


def xyz(text: str, **opts: object) -> list[tuple[float, ...]]:
    return [m[1][:3] for m in moves(text, SZ, **opts)]


E002_40_MACRO = """N1 #2=#0+#1
N2 IF (#2 EQ 10) GOTO 4
N3 G00 X#2
N4 G00 Z#1
N5 M99 ;Return
"""


def test_e002_40_g65_call_from_an_include_folder(tmp_path: Path) -> None:
    (tmp_path / "8000").write_text(E002_40_MACRO)
    main = "G00 X0 Z0\nG65 P8000 L1 A5 B6\nG0 X0 Z0\nM30\n"
    r = compile_text(main, dialect=SZ, include_dirs=[str(tmp_path)])
    assert r.ok, [d.message for d in r.sink]
    pts = xyz(main, include_dirs=[str(tmp_path)])
    # A5 -> #0 = 5, B6 -> #1 = 6; #2 = 11 is not 10: X11, then Z6, back to the main program
    assert pts == [(0, 0, 0), (11, 0, 0), (11, 0, 6), (0, 0, 0)]


def test_e002_40_branch_taken_when_sum_is_ten(tmp_path: Path) -> None:
    (tmp_path / "8000.nc").write_text(E002_40_MACRO)
    pts = xyz("G65 P8000 A4 B6\nM30\n", include_dirs=[str(tmp_path)])
    assert pts == [(0, 0, 6)]  # #2 = 10: GOTO 4 skips the X move


E002_41 = """G00 X0 Z0
G66 P6000 L2 A5 B6
A8 B1
A9 B10
G67
A3 B3
M30
O6000
N1 #2=#0+#1
N2 IF (#2 EQ 10) GOTO 4
N3 G00 X#2
N4 G00 Z#1
N5 M99          ; Return
"""


def test_e002_41_g66_argument_blocks_call_twice() -> None:
    pts = xyz(E002_41)
    # the G66 block only arms the call; (A8 B1) -> X9 Z1 twice; (A9 B10) -> X19 Z10 twice;
    # after G67 "A3 B3" is a plain move of the A and B axes
    assert pts[0] == (0, 0, 0)
    assert pts[1:5] == [(9, 0, 0), (9, 0, 1), (9, 0, 1), (9, 0, 1)]
    assert pts[5:9] == [(19, 0, 1), (19, 0, 10), (19, 0, 10), (19, 0, 10)]
    lines, _ = canon(E002_41, SZ)
    assert calls(lines, "STRAIGHT_TRAVERSE")[-1][1][3:5] == [3.0, 3.0]


def test_e002_42_assignment() -> None:
    text = "#123=7\n#470=2.5\n#234=1\n#251=890.34 #450=#123\n#440=#234+#470\nG00 X#251 Y#450 Z#440\nM30\n"
    assert xyz(text) == [(890.34, 7, 3.5)]


def test_e002_43_goto_number_and_variable() -> None:
    text = "#100=7\nGOTO 5\nG00 X1\nN5 G00 Y5\nGOTO #100\nG00 X2\nN7 G00 Z7\nM30\n"
    assert xyz(text) == [(0, 5, 0), (0, 5, 7)]


def test_e002_43_goto_out_of_range_is_an_error() -> None:
    r = compile_text("GOTO 100000\nM30\n", dialect=SZ)
    assert "E0306" in codes(r)


E002_44 = "#200={v}\nN1 IF(#200 EQ 1) GOTO 20\nN10 G00 X0\nN20 G00 Z0\nM30\n"


@pytest.mark.parametrize(("v", "n_moves"), [(1, 1), (2, 2)])
def test_e002_44_if_goto(v: int, n_moves: int) -> None:
    lines, _ = canon("G00 X5 Z5\n" + E002_44.format(v=v), SZ)
    traverses = calls(lines, "STRAIGHT_TRAVERSE")
    assert len(traverses) == 1 + n_moves
    assert traverses[-1][1][:3] == [0.0 if n_moves == 2 else 5.0, 0.0, 0.0]


E002_45 = "#100={v}\n#101=0\nN1 IF(#100 EQ 1) THEN #101=1\nN2 IF(#101 EQ 1) GOTO 4\nN3 G00 X100\nN4 G00 Z100\nM30\n"


def test_e002_45_if_then() -> None:
    assert xyz(E002_45.format(v=1)) == [(0, 0, 100)]
    assert xyz(E002_45.format(v=0)) == [(100, 0, 0), (100, 0, 100)]


E002_46 = """#1={a}
IF(#1 EQ 1)
G00 X10
ELIF(#1 EQ 2)
G00 X20
ELSE
G00 X30
ENDIF
IF(#1 GT 1)
G00 Y1
ELSE
G00 Y2
ENDIF
M30
"""


@pytest.mark.parametrize(("a", "x", "y"), [(1, 10, 2), (2, 20, 1), (3, 30, 1)])
def test_e002_46_block_if_else_elif(a: int, x: float, y: float) -> None:
    assert xyz(E002_46.format(a=a)) == [(x, 0, 0), (x, y, 0)]


def test_e002_46_bare_elif_is_else_with_a_warning() -> None:
    text = "#1=0\nIF(#1 EQ 1)\nG00 X10\nELIF\nG00 X20\nENDIF\nM30\n"
    lines, r = canon(text, SZ)
    assert calls(lines, "STRAIGHT_TRAVERSE")[-1][1][0] == 20.0
    assert "W0321" in codes(r)


E002_47 = """#100=2 #150=5 #200=25
WHILE (#100 LT 3) DO 1
G00 X100
WHILE (#150 EQ 5) DO 2
G00 Y100
WHILE (#200 GE 20) DO 3
G00 Z100
#200=#200-2
END 3
#150=#150-1
END 2
#100=#100-1
END 1
M30
"""


def test_e002_47_nested_while_runs_forever_and_hits_the_budget() -> None:
    lines, r = canon(E002_47, SZ, max_steps=2000)
    assert "E0301" in codes(r)
    names = [c[0] for c in calls(lines, "STRAIGHT_TRAVERSE")]
    pts = [tuple(a[:3]) for _, a in calls(lines, "STRAIGHT_TRAVERSE")]
    # pass 1: X100, Y100, Z100 three times (#200 = 25, 23, 21); later passes only X100
    assert pts[:5] == [(100, 0, 0), (100, 100, 0), (100, 100, 100), (100, 100, 100), (100, 100, 100)]
    assert len(names) > 100 and set(pts[5:]) == {(100, 100, 100)}


def test_e002_48_program_generation(tmp_path: Path) -> None:
    text = ("G0X0Z0\nFILEON[AABBCC]\nFILEWD [G54G0X0Z0]\nG1X45Z89 F100\nFILEWC\nG1X99Z76\nFILEWC\nFILECE\nM30\n")
    r = compile_text(text, dialect=SZ, write_dir=str(tmp_path))
    assert r.ok, [d.message for d in r.sink]
    # FILEWC writes X Y Z of the milling controller (the lathe manual shows X and Z)
    assert (tmp_path / "AABBCC").read_text().splitlines() == ["G54G0X0Z0", "X45Y0Z89", "X99Y0Z76"]


def test_e002_48_without_write_dir_nothing_is_written(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    r = compile_text("FILEON(AABBCC)\nFILEWD(G0X1)\nFILECE\nM30\n", dialect=SZ)
    assert "W0314" in codes(r) and r.ok
    assert list(tmp_path.iterdir()) == []


def test_e002_49_filems_saves_globals_as_a_program(tmp_path: Path) -> None:
    r = compile_text("#21=1.5\n#500=-2\nFILEMS(ABC)\nM30\n", dialect=SZ, write_dir=str(tmp_path))
    assert r.ok
    saved = (tmp_path / "ABC").read_text()
    assert saved.splitlines() == ["#21=1.5", "#500=-2", "M99"]
    # running the saved program as a subprogram restores the values
    pts = xyz("M98 PABC\nG00 X#21 Y#500\nM30\n", include_dirs=[str(tmp_path)])
    assert pts == [(1.5, -2, 0)]


def test_e002_50_scanner_loop_writes_ten_lines(tmp_path: Path) -> None:
    text = "G0 X100 Z2\nFILEON(SCANNER01)\nG22 L10\nG1 Z-10 F100\nFILEWC\nG0 Z2\nG91 X-1\nG90\nG800\nM30\n"
    r = compile_text(text, dialect=SZ, write_dir=str(tmp_path))
    assert r.ok, [d.message for d in r.sink]
    lines = (tmp_path / "SCANNER01").read_text().splitlines()
    assert lines == [f"X{100 - k}Y0Z-10" for k in range(10)]


PROGRAM_G152 = """#80=#0
#81=#1
#82=#2
#85=#5
#86=#6
#87=#7
#92=#12
#98=#18

#99=#19
#100=#20
#30=#4003
#31=#4014
G90
IF[#30 EQ 90] GOTO 1
G53
#98=#5001+#98
#99=#5002+#99
N1 WHILE[#86 GT 0] DO 1
#35=#98+#87*COS[#80]
#36=#99+#87*SIN[#80]
G81X#35Y#36Z#100R#92F#85
#80=#80+#81
#86=#86-1
END 1
G#30 G#31 G80
M99
"""


def test_e002_51_g152_bolt_hole_circle(tmp_path: Path) -> None:
    (tmp_path / "ProgramG152").write_text(PROGRAM_G152)
    main = "G90 G92 X0 Y0 Z4\nG152 X100 Y50 R10 Z-20.0 F20 I40.0 A0 B45.0 H5\nM30\n"
    r = compile_text(main, dialect=SZ, include_dirs=[str(tmp_path)])
    assert r.ok, [d.message for d in r.sink]
    pts = xyz(main, include_dirs=[str(tmp_path)])
    holes = [p[:2] for p in pts if p[2] == -20.0]
    expect = [(100 + 40 * math.cos(math.radians(a)), 50 + 40 * math.sin(math.radians(a)))
              for a in (0, 45, 90, 135, 180)]
    assert len(holes) == 5
    for (x, y), (ex, ey) in zip(holes, expect, strict=True):
        assert x == pytest.approx(ex, abs=1e-4) and y == pytest.approx(ey, abs=1e-4)


def test_user_macro_missing_program_is_reported() -> None:
    r = compile_text("G120 T3\nM30\n", dialect=SZ)
    assert "E0310" in codes(r)
    assert "ProgramG120" in next(d.message for d in r.sink if d.code == "E0310")


def test_e002_60_m97_jump() -> None:
    assert xyz("M97 P0120\nG00 X1\nN0120 G00 Y2\nM30\n") == [(0, 2, 0)]


def test_e002_61_m98_call_forms(tmp_path: Path) -> None:
    (tmp_path / "HIDEFILE01").write_text("G91 G00 X1\nM99\n")
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "1390").write_text("G91 G00 Y1\nM99\n")
    (tmp_path / "FFDE").write_text("G91 G00 Z1\nM99\n")
    (tmp_path / "A1234").write_text("G91 G00 X10\nM99\n")
    text = "M98 PHIDEFILE01\nM98 P*01 L2\nM98 Psub/1390\nPP[FFDE\nM98 P[A1234\nG90\nM30\n"
    r = compile_text(text, dialect=SZ, include_dirs=[str(tmp_path)])
    assert r.ok, [d.message for d in r.sink]
    assert xyz(text, include_dirs=[str(tmp_path)])[-1] == (13, 1, 1)


def test_e002_61_nesting_limit_is_four() -> None:
    subs = "".join(f"O{k}\nM98 P{k + 1}\nM99\n" for k in range(1, 7))
    r = compile_text("M98 P1\nM30\n" + subs, dialect=SZ)
    assert "E0309" in codes(r)
    d = next(d for d in r.sink if d.code == "E0309")
    assert len(d.related) == 4  # the call chain


E002_62 = "M12\nM14 P0120\nG00 X1\nN0120 G00 Y2\nM30\n"


def test_e002_62_input_wait_and_jump(tmp_path: Path) -> None:
    io = tmp_path / "io.txt"
    io.write_text("M12 = on\nM14 = on\n")
    assert xyz(E002_62, io_file=str(io)) == [(0, 2, 0)]  # M14 valid: jump to N0120
    io.write_text("M12 = on\nM14 = off\n")
    assert xyz(E002_62, io_file=str(io)) == [(1, 0, 0), (1, 2, 0)]


def test_e002_62_wait_for_an_input_that_never_comes(tmp_path: Path) -> None:
    io = tmp_path / "io.txt"
    io.write_text("M12 = 0\nX05 = 0\n")
    assert "E0323" in codes(compile_text("M12\nM30\n", dialect=SZ, io_file=str(io)))
    assert "E0323" in codes(compile_text("WAT+X05\nM30\n", dialect=SZ, io_file=str(io)))
