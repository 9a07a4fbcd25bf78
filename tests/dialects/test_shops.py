"""Real programs from real shops (issue 23; detection parts of issues 19 and 25).

Each test names the controller rule it checks.  Where the rule comes from general
knowledge of a controller's manual (Fanuc Custom Macro B, the Haas NGC mill manual),
the docstring says which rule; the expected values are computed in the test.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from cncc.api import compile_commands, compile_text
from cncc.cli import main
from cncc.diagnostics import Severity
from cncc.dialects import DialectError, load_dialect, merge_base, parse_dialect
from cncc.frontend.detect import detect, guess_dialect, views
from cncc.frontend.parser import abbreviations
from cncc.ir import Aux
from tests.helpers import calls, canon, codes, moves

TOOLS = str(Path(__file__).resolve().parents[1] / "translate" / "tools.toml")


def errors(r: object) -> list[str]:
    return [d.code for d in r.sink if d.severity is Severity.ERROR]  # type: ignore[attr-defined]


# ---- macro-word abbreviations ----------------------------------------------------------------
def test_two_letter_abbreviations_run_like_the_words() -> None:
    """Fanuc Custom Macro B: the first two characters of a macro word may stand for it
    (WH = WHILE, GO = GOTO, EN = END, AT = ATAN, SQ = SQRT, RO = ROUND).  ROUND is assigned to a
    variable: inside an address it rounds to the address's increment instead (issue 17)."""
    spelled = ("G21 G90\n#1=0\nWHILE[#1LT3]DO1\nG01 X[#1*10.] F100.\n#1=#1+1\nEND1\n"
               "IF[#1EQ3]GOTO20\nG01 Y50.\nN20 #3=ROUND[2.6]\nG01 Y[ATAN[1]/[1]] Z-[SQRT[16.]] X[#3]\nM30\n")
    short = ("G21 G90\n#1=0\nWH[#1LT3]DO1\nG01 X[#1*10.] F100.\n#1=#1+1\nEN1\n"
             "IF[#1EQ3]GO20\nG01 Y50.\nN20 #3=RO[2.6]\nG01 Y[AT[1]/[1]] Z-[SQ[16.]] X[#3]\nM30\n")
    want = moves(spelled, "fanuc")
    assert moves(short, "fanuc") == want
    assert [m[1] for m in want] == [(0.0, 0.0, 0.0), (10.0, 0.0, 0.0), (20.0, 0.0, 0.0), (3.0, 45.0, -4.0)]


def test_abbreviations_come_from_the_dialect_data() -> None:
    """The abbreviated words are the dialect's [macro_words]; a prefix two words share is not used."""
    fanuc = dict(abbreviations(load_dialect("fanuc")))
    assert fanuc["WHILE"] == "WH" and fanuc["GOTO"] == "GO" and fanuc["ATAN"] == "AT"
    raw = {"name": "x", "macro_words": {"abbreviation_letters": 2, "words": ["SIN", "SIGN", "GOTO"]}}
    assert abbreviations(parse_dialect(raw)) == (("GOTO", "GO"),)  # SI is ambiguous
    assert abbreviations(load_dialect("haas")) == ()  # Haas spells the words out


def test_abbreviation_is_not_read_where_the_dialect_has_none() -> None:
    """Without abbreviations (SYNTEC), WH[ is the address W with no value, as before."""
    r = compile_text("#1=0\nWH[#1LT3]DO1\nEND1\nM30\n", dialect="syntec", emit="none")
    assert "E0108" in codes(r)


# ---- M codes the machine handles --------------------------------------------------------------
def test_unknown_m_code_goes_to_the_machine_on_fanuc() -> None:
    """Fanuc: an M code the CNC does not use itself is sent to the PMC (ladder): no alarm."""
    cmds, r = compile_commands("G21\nM262\nM10\nG0 X1.\nM10\nM30\n", dialect="fanuc")
    assert errors(r) == [] and codes(r).count("W0270") == 2  # once per code and program
    assert [c.code for c in cmds if isinstance(c, Aux)] == [2620, 100, 100]


def test_m_code_policy_is_a_dialect_option() -> None:
    """SZGH and grbl reject M codes they do not define; -funknown_m_code=error makes Fanuc strict."""
    assert "E0202" in errors(compile_text("M277\nM30\n", dialect="szgh", emit="none"))
    assert errors(compile_text("M262\nM30\n", dialect="grbl", emit="none"))
    strict = compile_text("M262\nM30\n", dialect="fanuc", emit="none",
                          dialect_options={"unknown_m_code": "error"})
    assert "E0202" in errors(strict)


def test_machine_model_lists_its_m_codes_with_times(tmp_path: Path) -> None:
    """A machine file's [[m_codes]] say what the builder's M codes do and how long they take;
    the timing report counts the time, and no warning is given for a listed code."""
    machine = tmp_path / "vmc.toml"
    machine.write_text('base = "generic-mill"\nname = "vmc"\n[[m_codes]]\ncode = "M10"\n'
                       'meaning = "vise clamp"\nseconds = 0.8\n')
    text = "G21 G90\nM10\nG4 X1.\nM30\n"
    r = compile_text(text, dialect="fanuc", emit="none", machine=str(machine))
    assert "W0270" not in codes(r) and errors(r) == []
    from tests.helpers import nominal

    with_clamp = nominal(text, "fanuc", machine=str(machine)).total_s
    without = nominal(text, "fanuc").total_s
    assert math.isclose(with_clamp - without, 0.8, abs_tol=1e-9)
    assert math.isclose(without, 1.0, abs_tol=1e-9)  # the dwell only


def test_machine_m_code_table_is_checked(tmp_path: Path) -> None:
    machine = tmp_path / "bad.toml"
    machine.write_text('base = "generic-mill"\n[[m_codes]]\ncode = "X10"\n')
    assert main(["-x", "fanuc", "-m", str(machine), "--emit=none", "-"]) != 0


# ---- system variables -------------------------------------------------------------------------
def tool_length(text: str, dialect: str) -> float:
    lines, r = canon(text, dialect)
    assert errors(r) == [], [(d.code, d.message) for d in r.sink]
    offsets = [a for name, a in calls(lines, "USE_TOOL_LENGTH_OFFSET")]
    return offsets[-1][2]


def test_fanuc_memory_c_offsets_are_writable_and_add_up() -> None:
    """Fanuc tool compensation memory C: #11001.. H geometry and #10001.. H wear are
    writable; the H offset G43 applies is geometry + wear."""
    assert math.isclose(tool_length("G21\n#11001=100.\n#10001=-0.25\nG43 H1 Z0\nM30\n", "fanuc"), 99.75)


def test_haas_tool_offset_variables() -> None:
    """Haas: #2001-#2200 length geometry, #2201-#2400 length wear (H = geometry + wear)."""
    assert math.isclose(tool_length("G21\n#2001=50.\n#2201=0.5\nG43 H1 Z0\nM30\n", "haas"), 50.5)


def test_extended_work_offsets_are_writable() -> None:
    """Fanuc #7001 (G54.1 P1 X) and Haas #14001 (G154 P1 X) set the additional work systems."""
    for text, dialect in (("G21\n#7001=12.5\nG54.1 P1\nG0 X0\nM30\n", "fanuc"),
                          ("G21\n#14001=12.5\nG154 P1\nG0 X0\nM30\n", "haas")):
        lines, r = canon(text, dialect)
        assert errors(r) == []
        assert [a[:2] for _, a in calls(lines, "SET_G5X_OFFSET")][-1] == [7.0, 12.5]


def test_unknown_system_variable_is_a_warning_and_read_only_stays_an_error() -> None:
    """An unknown number may be an option cncc does not know: warn (read vacant, write
    ignored).  Writing a listed read-only variable (#5001 position) is still an alarm."""
    r = compile_text("#9999=1\n#101=#9998\nM30\n", dialect="fanuc", emit="none")
    assert errors(r) == [] and codes(r).count("W0370") == 2
    assert "E0303" in errors(compile_text("#5001=3\nM30\n", dialect="fanuc", emit="none"))


def test_system_variable_table_is_validated() -> None:
    raw = {"name": "x", "macro_flavour": "fanuc", "system_variables": [{"first": 1, "last": 2, "kind": "nope"}]}
    from cncc.frontend.macro.systable import table_for

    with pytest.raises(DialectError):
        table_for(parse_dialect(raw))


# ---- program numbers --------------------------------------------------------------------------
def test_iso_colon_program_number() -> None:
    """ISO tape code: ':' is the program-number address (EIA 'O'); ':1000' is O1000."""
    text = "%\n:0001 (MAIN)\nG21 G90\nM98 P1000\nM30\n:1000 (SUB)\nG01 X5. F100.\nM99\n%\n"
    got = moves(text, "fanuc")
    assert got == [("STRAIGHT_FEED", (5.0, 0.0, 0.0))]


# ---- libraries without a caller, modal state from the caller ----------------------------------
LIB = ("%\nO9010 (BOLT CIRCLE: X Y CENTRE, R RADIUS, Z DEPTH, K HOLES)\n"
       "IF[#18EQ#0]GOTO90\n#30=0\nWH[#30LT#6]DO1\n#31=#30*360/#6\n"
       "G81 X[#24+#18*COS[#31]] Y[#25+#18*SIN[#31]] Z#26 R2. F#9\n#30=#30+1\nEN1\nG80\nGOTO99\n"
       "N90 #3000=1(R MISSING)\nN99 M99\n%\n")


def test_library_alone_reports_argument_checks_as_notes(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """Without a caller, arguments are unknown: the #3000 argument check is a note, not an error."""
    lib = tmp_path / "O9010.nc"
    lib.write_text(LIB)
    assert main(["-x", "fanuc", "--emit=none", str(lib)]) == 0
    err = capsys.readouterr().err
    assert "N0371" in err and "E0311" in err and "error" not in err.split("[E0311]")[0].rsplit("\n", 1)[-1]


def test_library_defect_whatever_the_arguments_stays_an_error(tmp_path: Path) -> None:
    """A problem every call would hit (a jump to a missing sequence number) keeps its severity."""
    lib = tmp_path / "lib.nc"
    lib.write_text("O9011\nGOTO77\nM99\n")
    r = compile_text(lib.read_text(), dialect="fanuc", emit="none")
    assert "E0313" in errors(r) or errors(r), [(d.code, d.message) for d in r.sink]


def test_library_is_checked_with_the_callers_arguments(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """With the main program in the same run, the library runs with the caller's arguments:
    a call without R raises the library's own alarm as an error."""
    lib = tmp_path / "lib.nc"
    lib.write_text(LIB)
    good = tmp_path / "main.nc"
    good.write_text("O0001\nG21 G90 G17\nG65 P9010 X0 Y0 R30. Z-5. K4. F100.\nM30\n")
    assert main(["-x", "fanuc", "--emit=none", str(good), str(lib)]) == 0
    bad = tmp_path / "bad.nc"
    bad.write_text("O0002\nG21 G90 G17\nG65 P9010 X0 Y0 Z-5. K4. F100.\nM30\n")
    assert main(["-x", "fanuc", "--emit=none", str(bad), str(lib)]) == 1
    assert "E0311" in capsys.readouterr().err


def test_holes_of_the_called_library_are_where_the_arguments_put_them(tmp_path: Path) -> None:
    """Independent expectation: K=4 holes on R30 about (0, 0) at 0, 90, 180, 270 degrees."""
    lib = tmp_path / "O9010.nc"
    lib.write_text(LIB)
    got = moves("O0001\nG21 G90 G17\nG65 P9010 X0 Y0 R30. Z-5. K4. F100.\nM30\n", "fanuc",
                include_dirs=[str(tmp_path)])
    holes = [(round(p[0], 6), round(p[1], 6)) for kind, p in got if kind == "STRAIGHT_FEED" and p[2] == -5.0]
    want = [(round(30 * math.cos(math.radians(a)), 6), round(30 * math.sin(math.radians(a)), 6))
            for a in (0, 90, 180, 270)]
    assert holes == want


def test_subprogram_file_relies_on_the_callers_feed(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """A subprogram file takes the caller's modal F: standalone, the missing F is a note;
    called from a main without any F, it is an error."""
    sub = tmp_path / "O1000.nc"
    sub.write_text("O1000\nG91 G01 X10.\nY10.\nG90\nM99\n")
    assert main(["-x", "fanuc", "--emit=none", str(sub)]) == 0
    assert "N0371" in capsys.readouterr().err
    main_ok = tmp_path / "a.nc"
    main_ok.write_text("O1\nG21 G90 G01 F200.\nM98 P1000\nM30\n")
    assert main(["-x", "fanuc", "--emit=none", str(main_ok), str(sub)]) == 0
    main_bad = tmp_path / "b.nc"
    main_bad.write_text("O2\nG21 G90\nM98 P1000\nM30\n")
    assert main(["-x", "fanuc", "--emit=none", str(main_bad), str(sub)]) == 1


# ---- the haas dialect -------------------------------------------------------------------------
def test_haas_reads_integers_as_whole_units() -> None:
    """Haas reads X10 as X10. (a whole number of units), not Fanuc's least input units."""
    assert moves("G21 G90\nG01 X10 F100\nM30\n", "haas") == [("STRAIGHT_FEED", (10.0, 0.0, 0.0))]
    assert moves("G21 G90\nG01 X10 F100\nM30\n", "fanuc") == [("STRAIGHT_FEED", (0.01, 0.0, 0.0))]


def test_haas_m97_local_subprogram() -> None:
    """Haas M97 P_ L_: run from N(P) of this program to M99, L times."""
    text = "G21 G90\nG00 X0 Y0\nM97 P100 L2\nM30\nN100 G91 G01 X5. F100.\nG90\nM99\n"
    assert [m[1] for m in moves(text, "haas")] == [(0.0, 0.0, 0.0), (5.0, 0.0, 0.0), (10.0, 0.0, 0.0)]


def test_haas_codes_and_fanuc_options_it_lacks() -> None:
    """Haas has G187 smoothness, G103 look-ahead, G154 P work systems, M16 tool change;
    the Fanuc options G45-G48 are not Haas codes."""
    r = compile_text("G21\nG187 P2 E0.01\nG103 P1\nG154 P5\nT2 M16\nM30\n", dialect="haas", emit="none")
    assert errors(r) == [], [(d.code, d.message) for d in r.sink]
    assert "E0201" in errors(compile_text("G21\nG45 X1. D1\nM30\n", dialect="haas", emit="none"))
    assert load_dialect("haas").code("G", 450) is None and load_dialect("fanuc").code("G", 450) is not None


def test_dialect_base_merges_by_code() -> None:
    """A dialect written as changes to its base: codes replaced or added by code, removed by list."""
    base = {"name": "a", "g": [{"code": "G01", "op": "linear"}, {"code": "G45", "op": "x"}],
            "options": {"p": 1, "q": 2}, "detect": {"rule": []}}
    top = {"name": "b", "base": "a", "remove": ["G45"], "g": [{"code": "G01", "op": "other"}], "options": {"q": 3}}
    merged = merge_base(base, top)
    assert merged["g"] == [{"code": "G01", "op": "other"}]
    assert merged["options"] == {"p": 1, "q": 3} and "detect" not in merged and merged["name"] == "b"


# ---- detection --------------------------------------------------------------------------------
@pytest.mark.parametrize("name, text, want", [
    # issue 19: G21 alone does not outvote SYNTEC evidence
    ("a.nc", "G21 G90\nG01 X10. F300. // face\nG134 X0 Y0 I20. J0 K6\nM30\n", "syntec"),
    ("a.nc", "G21 G90 // metric\nG01 X10. F300.\nM30\n", "syntec"),
    # issue 25: http:// inside a CamBam comment is no // comment; G90G20 without spaces
    ("a.nc", "( Made using CamBam - http://www.cambam.co.uk )\nG21 G90 G91.1 G64 G40\nG0 Z3.\nM30\n", "linuxcnc"),
    ("a.nc", "G90G20\nG0 X1. Y1.\nG1 X2. F10.\nM2\n", "linuxcnc"),
    # issue 23: FreeCAD grbl output, Haas programs, ISO program numbers, abbreviations
    ("a.nc", "(Exported by FreeCAD)\n(Post Processor: grbl_post)\nG17 G90\nG21\nG0 X1. Y1.\nM2\n", "grbl"),
    ("a.nc", "%\nO01001 (PART)\n(MACHINE)\n(  VENDOR HAAS AUTOMATION)\nG20 G90\nG187 P3\nM30\n%\n", "haas"),
    ("a.nc", "%\n:1000\nG21 G90\nG01 X1. F100.\nM30\n%\n", "fanuc"),
    ("a.nc", "O9000\n#1=0\nWH[#1LT5]DO1\n#1=#1+1\nEN1\nM99\n", "fanuc"),
    # SZGH accepts round brackets in conditions (spec 3.8); SERIES 8's compact blocks with ';' text
    ("a.nc", "#5=0\nN2 IF (#5 GE 3) GOTO 9\nG00 X[#5*10.]\n#5=#5+1\nGOTO 2\nN9 M30\n", "szgh"),
    ("a.nc", "G00X0Y0 ; to the corner\nF12 ; slow\nG01X3.Y0 ; along X\nM30\n", "series8"),
])
def test_detection_scores_evidence(name: str, text: str, want: str) -> None:
    assert guess_dialect(name, text)[0] == want, detect(name, text).explain()


def test_code_view_blanks_paren_comments() -> None:
    seen = views("a.nc", "G0 X1. (see http://example.com)\n")
    assert "//" not in seen["code"] and "http://example.com" in seen["comments"]


def test_g90g20_without_spaces_is_units_evidence() -> None:
    found = detect("a.nc", "G90G20\n")
    assert any(e.why == "G20/G21 units codes" and e.dialect == "linuxcnc" for e in found.evidence)


def test_verbose_shows_the_evidence(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    p = tmp_path / "part.nc"
    p.write_text("G21 G90 // metric\nG01 X10. F300.\nM30\n")
    main(["-v", "--emit=none", str(p)])
    err = capsys.readouterr().err
    assert "N0251" in err and "dialect syntec" in err and "// comments +4" in err


def test_weak_guess_that_changes_numbers_warns(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """Issue 25: a plain .nc with integer coordinates guessed as a least-input-unit dialect
    warns without -v (X10 is 0.010 mm there, 10 mm under LinuxCNC); -x silences it."""
    p = tmp_path / "plain.nc"
    p.write_text("G0 X10 Y20\nG1 X30 F100\nM30\n")
    main(["--emit=none", str(p)])
    err = capsys.readouterr().err
    assert "W0271" in err and "0.010 mm" in err
    main(["-x", "syntec", "--emit=none", str(p)])
    assert "W0271" not in capsys.readouterr().err
    z = tmp_path / "zeros.nc"  # X0 is 0 under every rule: nothing to warn about
    z.write_text("G91 G28 Z0\nG90 G0 X0 Y0\nG1 X12.5 F100\nM30\n")
    main(["--emit=none", str(z)])
    assert "W0271" not in capsys.readouterr().err
    q = tmp_path / "sure.nc"  # strong SYNTEC evidence: no warning
    q.write_text("G71 G90 // metric\nG134 X0 Y0 I20. J0 K6 // holes\nG0 X10 Y20\nM30\n")
    main(["--emit=none", str(q)])
    assert "W0271" not in capsys.readouterr().err


# ---- W0513 once per program -------------------------------------------------------------------
def test_missing_offsets_without_a_tool_table_are_one_warning() -> None:
    r = compile_text("G21 G90\nG43 H1 Z10.\nG43 H2 Z10.\nG43 H1 Z5.\nG41 D3 G01 X10. F100.\nG40 X20.\nM30\n",
                     dialect="fanuc", emit="none")
    found = [d for d in r.sink if d.code == "W0513"]
    assert len(found) == 1 and "H1, H2, D3" in found[0].message


def test_missing_offset_with_a_tool_table_is_reported_per_word() -> None:
    r = compile_text("G21 G90\nG43 H1 Z10.\nG43 H7 Z10.\nG43 H8 Z5.\nM30\n", dialect="fanuc", emit="none",
                     tools_file=TOOLS)
    assert [d.message.split()[0] for d in r.sink if d.code == "W0513"] == ["H7", "H8"]


def test_text_after_the_closing_percent_is_not_read() -> None:
    """ISO/EIA tape format: the '%' after the program ends the tape; a DNC trailer after it
    is not part of the program."""
    text = "%\nO1000\nG21 G90\nG01 X1. F100.\nM30\n%\nTRAILER TEXT 123\n"
    for dialect in ("fanuc", "haas"):
        lines, r = canon(text, dialect)
        assert errors(r) == [] and any("STRAIGHT_FEED(1.0000" in ln for ln in lines), dialect
    assert "E0108" in errors(compile_text(text, dialect="syntec", emit="none"))  # no such rule there


def test_concatenated_tapes_are_kept_and_called_files_end_at_their_percent(tmp_path: Path) -> None:
    """Two tapes in one file (% ... % % ... %) are both read; a called program file with a
    DNC trailer after its closing '%' is read up to the '%'."""
    both = "%\nO1\nG21 G90\nM98 P2\nM30\n%\n%\nO2\nG01 X4. F100.\nM99\n%\n"
    assert moves(both, "fanuc") == [("STRAIGHT_FEED", (4.0, 0.0, 0.0))]
    (tmp_path / "O0003.nc").write_text("%\nO0003\nG01 X7. F100.\nM99\n%\nSENT BY DNC 2024-05-01\n")
    got = moves("O1\nG21 G90\nM98 P3\nM30\n", "fanuc", include_dirs=[str(tmp_path)])
    assert got == [("STRAIGHT_FEED", (7.0, 0.0, 0.0))]
