"""LinuxCNC codes of issue 24: G38.x probing, @/^ polar words, the $ spindle word, M61, M70-M73
and --ini.  Expected values come from LinuxCNC's G-code documentation and the behaviour of its
stand-alone interpreter rs274 2.9 (measured; tests/oracle compares whole programs with it),
recomputed here independently (the probe back-off, polar end points)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from cncc.api import compile_text
from cncc.ir import Linear, OriginKind, Probe, SetToolNumber
from tests.helpers import calls, canon, codes, compile_commands

LINUXCNC = "linuxcnc"


def _calls(text: str, *names: str, **opts: object) -> list[tuple[str, list[float]]]:
    lines, r = canon(text, LINUXCNC, **opts)
    assert not r.sink.has_errors, [f"{d.code} {d.message}" for d in r.sink]
    return calls(lines, *names)


# ---- probing ----------------------------------------------------------------------------------
def test_probe_prints_straight_probe_and_backs_off_toward_the_start() -> None:
    got = _calls("G21 F100\nG0 X1 Y2 Z3\nG38.2 Z-5\nG1 X7\nM2\n", "STRAIGHT_PROBE", "STRAIGHT_FEED", "TURN_PROBE_ON")
    assert got[0] == ("TURN_PROBE_ON", [])
    assert got[1] == ("STRAIGHT_PROBE", [1, 2, -5, 0, 0, 0])
    # the tool ends 0.254 mm (the stand-alone canon's back-off) from the end point toward the start
    assert got[2] == ("STRAIGHT_FEED", [7, 2, pytest.approx(-5 + 0.254), 0, 0, 0])


def test_probe_is_a_typed_marker_then_the_probe_move_and_its_back_off() -> None:
    cmds, r = compile_commands("G21 F100\nG0 X1 Y2 Z3\nG38.2 Z-5\nM2\n", dialect=LINUXCNC)
    assert not r.sink.has_errors
    k = next(i for i, c in enumerate(cmds) if isinstance(c, Probe))
    marker, move, back = cmds[k], cmds[k + 1], cmds[k + 2]
    assert isinstance(marker, Probe) and marker.op == "probe_toward" and marker.folded == 2
    assert marker.end == (1.0, 2.0, -5.0, 0.0, 0.0, 0.0)
    assert isinstance(move, Linear) and move.origin.kind is OriginKind.PROBE and move.origin.code == "G38.2"
    assert isinstance(back, Linear) and back.origin.kind is OriginKind.PROBE_BACKOFF
    assert back.end[2] == pytest.approx(-5 + 0.254)  # the stand-alone canon's back-off toward the start


def test_probe_result_parameters() -> None:
    # #5061-#5063: the end point in program units (inches here); #5070: 0, the probe did not trip
    got = _calls("G20 F10\nG38.3 X1 Y2 Z-1\nG1 X#5061 Y#5063 Z[#5070 + 4]\nM2\n", "STRAIGHT_FEED")
    assert got == [("STRAIGHT_FEED", [1, -1, 4, 0, 0, 0])]


def test_probe_back_off_is_along_the_probe_line() -> None:
    got = _calls("G21 F100\nG38.4 X3 Y4\nG1 Z1\nM2\n", "STRAIGHT_FEED")
    d = 0.254 / 5.0  # the move is (3, 4): unit vector back (-0.6, -0.8)
    x, y = got[0][1][:2]
    assert (x, y) == (pytest.approx(3 - 3 * d, abs=1e-4), pytest.approx(4 - 4 * d, abs=1e-4))


@pytest.mark.parametrize(("text", "message"), [
    ("G21\nG38.2 Z-5\nM2\n", "Cannot probe with zero feed rate"),
    ("G21 F100\nG41.1 D2 G1 X5\nG38.2 Z-5\nM2\n", "Cannot probe with cutter radius comp on"),
    ("G21 F100 S100 M3\nG95 F1\nG38.2 Z-5\nM2\n", "Cannot probe with feed per rev mode"),
    ("G21 F100\nG38.2 Z0\nM2\n", "Start point too close to probe point"),
    ("G21\nG93 G38.2 Z-5 F10\nM2\n", "Cannot probe with zero feed rate"),  # F in G93 is not a feed rate
])
def test_probe_errors(text: str, message: str) -> None:
    _, r = canon(text, LINUXCNC)
    assert "E0250" in codes(r)
    assert any(d.message == message for d in r.sink)


def test_probe_translation_keeps_the_code_or_refuses() -> None:
    text = "G21 F100\nG38.2 Z-5\nG0 Z5\nM2\n"
    grbl = compile_text(text, dialect=LINUXCNC, emit="gcode", target="grbl")
    assert grbl.ok and "G38.2 Z-5." in grbl.output
    fanuc = compile_text(text, dialect=LINUXCNC, emit="gcode", target="fanuc")
    assert "E0883" in codes(fanuc)
    assert "Z-5." not in fanuc.output  # no silent move to the probe point (a comment says what is missing)


# ---- polar words ------------------------------------------------------------------------------
def test_polar_words_absolute_and_incremental() -> None:
    text = "G21\nG0 @5 ^30\nG91 G0 @1 ^90\nG90 G0 ^45\nM2\n"
    got = [a[:2] for _, a in _calls(text, "STRAIGHT_TRAVERSE")]
    r1, a1 = 5.0, math.radians(30)
    r2, a2 = 6.0, math.radians(120)  # G91: both add to the current radius and angle
    r3, a3 = 6.0, math.radians(45)  # only ^: the radius stays
    want = [(r * math.cos(a), r * math.sin(a)) for r, a in ((r1, a1), (r2, a2), (r3, a3))]
    assert got == [[pytest.approx(x, abs=1e-4), pytest.approx(y, abs=1e-4)] for x, y in want]


@pytest.mark.parametrize("text", ["G21\nG0 X1 @5 ^30\nM2\n", "G21\nG0 @5\nM2\n", "G21\nG91 G0 @5 ^30\nM2\n",
                                  "G21\nG53 G0 @5 ^30\nM2\n"])
def test_polar_word_errors(text: str) -> None:
    _, r = canon(text, LINUXCNC)
    assert "E0250" in codes(r)


# ---- $ ------------------------------------------------------------------------------------------
def test_spindle_word() -> None:
    assert _calls("G21\nS100 $0 M3\nS200 $-1\nM2\n", "SET_SPINDLE_SPEED") == [
        ("SET_SPINDLE_SPEED", [0, 100]), ("SET_SPINDLE_SPEED", [0, 200])]
    for bad in ("G21\nS100 $1 M3\nM2\n", "G21\n$0\nM2\n", "G21\nM3 $2\nM2\n"):
        _, r = canon(bad, LINUXCNC)
        assert "E0250" in codes(r), bad


def test_m61_is_a_typed_tool_number_command() -> None:
    cmds, r = compile_commands("G21\nM61 Q3\nM2\n", dialect=LINUXCNC)
    assert not r.sink.has_errors
    assert [c.tool for c in cmds if isinstance(c, SetToolNumber)] == [3]


# ---- M61 ----------------------------------------------------------------------------------------
def test_m61_sets_the_loaded_tool(tmp_path: Path) -> None:
    tbl = tmp_path / "t.tbl"
    tbl.write_text("T1 P1 Z10 D2\nT2 P2 Z-3 D4\n")
    lines, r = canon("G21\nM61 Q2\nG43\nG0 Z1\nM61 Q1.4\nM2\n", LINUXCNC, tools_file=str(tbl))
    assert not r.sink.has_errors
    assert calls(lines, "CHANGE_TOOL_NUMBER") == [("CHANGE_TOOL_NUMBER", [2]), ("CHANGE_TOOL_NUMBER", [1])]
    assert any("USE_TOOL_LENGTH_OFFSET(0.0000 0.0000 -3.0000," in ln for ln in lines)  # tool 2's length
    for bad in ("G21\nM61\nM2\n", "G21\nM61 Q-1\nM2\n", "G21\nM61 Q7\nM2\n"):
        _, r = canon(bad, LINUXCNC, tools_file=str(tbl))
        assert "E0250" in codes(r), bad


# ---- M70-M73 ------------------------------------------------------------------------------------
def test_m72_restores_what_changed() -> None:
    got = _calls("G21 F10\nM70\nG20 F5 G18\nM72\nG0 X1\nM2\n", "USE_LENGTH_UNITS", "SET_FEED_RATE", "SELECT_PLANE",
                 "STRAIGHT_TRAVERSE")
    got = got[:[n for n, _ in got].index("STRAIGHT_TRAVERSE") + 1]  # not the program end's resets
    # after the changes: units first, then F (10), then the plane, then the move in mm
    assert [n for n, _ in got[-4:]] == ["USE_LENGTH_UNITS", "SET_FEED_RATE", "SELECT_PLANE", "STRAIGHT_TRAVERSE"]
    assert got[-3][1] == [10] and got[-1][1][0] == 1


def test_m73_restores_at_the_return_and_m72_needs_a_save() -> None:
    text = "G21\no100 sub\nM73\nG91\no100 endsub\no100 call\nG0 X1\nG0 X1\nM2\n"
    assert [a[0] for _, a in _calls(text, "STRAIGHT_TRAVERSE")] == [1, 1]  # back in G90 after the call
    for bad in ("G21\nM72\nM2\n", "G21\nM70\nM71\nM72\nM2\n"):
        _, r = canon(bad, LINUXCNC)
        assert "E0250" in codes(r), bad


# ---- --ini ----------------------------------------------------------------------------------------
def test_ini_subroutine_path_and_parameters(tmp_path: Path) -> None:
    (tmp_path / "subs").mkdir()
    (tmp_path / "subs" / "side.ngc").write_text("o<side> sub\nG0 X[#1 * 2]\no<side> endsub\nM2\n")
    ini = tmp_path / "m.ini"
    ini.write_text("[RS274NGC]\nSUBROUTINE_PATH = subs\n# a comment\n[MY]\nDEPTH = -2.5\nNAME = text\n")
    got = _calls("G21\no<side> call [3]\nG0 Z#<_ini[my]depth>\nM2\n", "STRAIGHT_TRAVERSE", ini_file=str(ini))
    assert [a[:3] for _, a in got] == [[6, 0, 0], [6, 0, -2.5]]
    for bad in ("G21\nG0 X#<_ini[my]name>\nM2\n", "G21\n#<_ini[my]depth> = 1\nM2\n"):
        _, r = canon(bad, LINUXCNC, ini_file=str(ini))
        assert r.sink.has_errors, bad


def test_ini_disables_fanuc_subs(tmp_path: Path) -> None:
    ini = tmp_path / "m.ini"
    ini.write_text("[RS274NGC]\nDISABLE_FANUC_STYLE_SUB = 1\n")
    _, r = canon("G21\nM98 P100\nM2\n", LINUXCNC, ini_file=str(ini))
    assert any(d.message == "DISABLE_FANUC_STYLE_SUB set in INI file, but found m98" for d in r.sink)


def test_ini_file_problems(tmp_path: Path) -> None:
    _, r = canon("G21\nM2\n", LINUXCNC, ini_file=str(tmp_path / "missing.ini"))
    assert "E0983" in codes(r)
    bad = tmp_path / "bad.ini"
    bad.write_text("[A]\nX = 1\njunk\nY = 2\n")
    _, r = canon("G21\nM2\n", LINUXCNC, ini_file=str(bad))
    found = [d for d in r.sink if d.code == "E0984"]
    assert len(found) == 1
    src = r.sources.get(found[0].span.source_id)
    assert src is not None and src.text[found[0].span.start:found[0].span.end] == "junk"


def test_ini_from_cncc_toml(tmp_path: Path) -> None:
    from cncc.api import compile as compile_program

    (tmp_path / "m.ini").write_text("[MY]\nX = 4\n")
    (tmp_path / "cncc.toml").write_text('dialect = "linuxcnc"\nini = "m.ini"\n')
    prog = tmp_path / "p.ngc"
    prog.write_text("G21\nG0 X#<_ini[my]x>\nM2\n")
    r = compile_program(prog)
    assert r.ok and "STRAIGHT_TRAVERSE(4.0000," in r.output
