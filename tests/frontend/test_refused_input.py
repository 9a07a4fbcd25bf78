"""Input a controller refuses is refused, with a positioned diagnostic, never silently read
(issue 17) — and a G4 dwell never drops the move of its block (issue 24).

* exponent notation (``X1e400`` was read as ``X1`` plus a word ``E400``), a value that
  overflows (a 400-digit ``X`` was infinity), NaN: errors, block skipped;
* F0 on a feed move: error (Fanuc PS0011, LinuxCNC "zero feed rate", grbl error 22);
* G41/G42 without an offset number: a warning (the Fanuc-family controllers run it with
  radius 0);
* ``G04 P0.5 G01 Z-1.``: LinuxCNC and grbl dwell, then move (their order of execution
  puts the dwell before the motion); the Fanuc family, whose G04 reads the block's axis
  words (``G04 X2.5`` is a time), rejects the block rather than drop the move.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from tests.helpers import calls, canon, codes

ROOT = Path(__file__).resolve().parents[2]
ALL = ["syntec", "fanuc", "szgh", "series8", "linuxcnc", "grbl"]
MM = {"series8": "G71 ", "syntec": "G71 "}  # metric in the dialects that power up in inch / use G70/G71
END = {"linuxcnc": "M2\n", "grbl": "M2\n"}


def prog(dialect: str, *lines: str) -> str:
    return MM.get(dialect, "G21 ") + "G90\n" + "\n".join(lines) + "\n" + END.get(dialect, "M30\n")


@pytest.mark.parametrize("dialect", ALL)
@pytest.mark.parametrize(("word", "code"), [("X1e400", "E0160"), ("X1e3", "E0160"), ("X2.5E-4", "E0160"),
                                            ("X1e+5", "E0160"), ("X" + "9" * 400 + ".", "E0161"),
                                            ("X" + "1" * 13, "E0161"), ("XNaN", "E0108")])
def test_refused_number_forms(dialect: str, word: str, code: str) -> None:
    if dialect == "grbl" and code != "E0108":
        if word == "X" + "1" * 13:
            return  # grbl's read_float accepts it (its checker's call: own_number_checks)
        code = "E0250"  # grbl's own checker: error:11 (line too long) / error:20 (no E word)
    lines, r = canon(prog(dialect, f"G01 {word} F100.", "G01 Y1. F100."), dialect)
    assert code in codes(r), (dialect, word, codes(r))
    d = next(d for d in r.sink if d.code == code)
    text = prog(dialect, f"G01 {word} F100.", "G01 Y1. F100.")
    line_start = text.index("G01 ")
    assert line_start <= d.span.start < text.index("\n", line_start)  # positioned in the offending block
    ends = [args[:2] for _, args in calls(lines, "STRAIGHT_FEED")]
    assert all(abs(x) < 1e6 for x, _ in ends)  # the refused block did not move anything
    assert [y for _, y in ends][-1:] == [1.0]  # the next block runs


def test_exponent_inside_expressions_and_assignments() -> None:
    _, r = canon("#1=1e400\nG01 X#1 F100.\nM30\n", "fanuc")
    assert "E0160" in codes(r)
    _, r = canon("G01 X[1e3] F100.\nM30\n", "fanuc")
    assert "E0160" in codes(r)


def test_exponent_text_in_comments_is_text() -> None:
    _, r = canon("(1e5 parts, 2E+3 more)\nG01 X1. F100.\nM30\n", "fanuc")
    assert not [c for c in codes(r) if c.startswith("E")]


def test_upper_case_e_after_a_number_is_the_e_word_where_the_dialect_has_one() -> None:
    _, r = canon("G01X1.E5F100.\nM30\n", "fanuc")  # compact CAM output: X1. and E5
    assert "E0160" not in codes(r)
    _, r = canon("G71 G01X1.E5F100.\nM30\n", "series8")  # SERIES 8 has no E address
    assert "E0160" in codes(r)


def test_no_runtime_warning_on_stderr_for_refused_numbers(tmp_path: Path) -> None:
    src = tmp_path / "big.nc"
    src.write_text("G21 G90\nG01 X" + "9" * 400 + ". F100.\nG01 X1e400\nG00 Y" + "9" * 12 + ".\nM30\n")
    for emit in ("timing", "canon"):
        p = subprocess.run([sys.executable, "-W", "error::RuntimeWarning", "-m", "cncc", "-x", "fanuc", str(src),
                            f"--emit={emit}"], capture_output=True, text=True, cwd=ROOT, timeout=120,
                           env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"})
        assert "RuntimeWarning" not in p.stderr and "Traceback" not in p.stderr, p.stderr
        assert "E0161" in p.stderr and "E0160" in p.stderr


@pytest.mark.parametrize("dialect", ["syntec", "fanuc", "szgh", "series8", "linuxcnc"])
def test_f0_on_a_feed_move_is_an_error(dialect: str) -> None:
    lines, r = canon(prog(dialect, "G01 X1. F100.", "G01 X2. F0", "G00 X3.", "G01 X4."), dialect)
    assert [a[0] for _, a in calls(lines, "STRAIGHT_FEED")] == [1.0]
    if dialect == "linuxcnc":  # rs274 stops at the first error
        assert codes(r).count("E0260") == 1, codes(r)
        return
    assert codes(r).count("E0260") == 2, codes(r)  # the F0 block and the later G01 that inherits F0
    assert [a[0] for _, a in calls(lines, "STRAIGHT_TRAVERSE")][-1:] == [3.0]  # a rapid needs no F


def test_f0_in_grbl_is_its_error_22() -> None:
    _, r = canon("G21 G90\nG01 X1. F0\nM2\n", "grbl")
    assert "E0250" in codes(r)


@pytest.mark.parametrize("dialect", ["syntec", "fanuc", "szgh", "series8"])
def test_g41_without_d_warns(dialect: str) -> None:
    _, r = canon(prog(dialect, "G00 X0 Y0", "G41 G01 X10. F100.", "G40 G00 X0"), dialect)
    assert "W0560" in codes(r)
    _, r = canon(prog(dialect, "G00 X0 Y0", "G42 D0 G01 X10. F100.", "G40 G00 X0"), dialect)
    assert "W0560" not in codes(r)  # D0 is an explicit "no offset"
    _, r = canon(prog(dialect, "G00 X0 Y0", "D1", "G42 G01 X10. F100.", "G40 G00 X0"), dialect)
    assert "W0560" not in codes(r)  # the D in force


def test_linuxcnc_g41_without_d_is_left_to_its_front_end() -> None:
    _, r = canon("G21 G90\nG0 X0 Y0\nG41 G1 X10. F100.\nG40 G0 X0\nM2\n", "linuxcnc")
    assert "W0560" not in codes(r)  # LinuxCNC uses the loaded tool's radius


# ---- G4 and a move in one block, in every dialect ---------------------------------------------------
DWELL = {"syntec": "G04 P500", "fanuc": "G04 P500", "szgh": "G04 P500", "series8": "G04 X0.5",
         "linuxcnc": "G04 P0.5", "grbl": "G4 P0.5"}


@pytest.mark.parametrize("dialect", ["linuxcnc", "grbl"])
def test_dwell_then_move_where_only_p_is_a_time(dialect: str) -> None:
    lines, r = canon(prog(dialect, "G01 X1. F100.", f"{DWELL[dialect]} G01 Z-1."), dialect)
    assert not [c for c in codes(r) if c.startswith("E")], codes(r)
    seq = [(n, a[:3]) for n, a in calls(lines, "DWELL", "STRAIGHT_FEED")]
    assert seq[-2:] == [("DWELL", [0.5]), ("STRAIGHT_FEED", [1.0, 0.0, -1.0])]  # rs274ngc: dwell, then motion


@pytest.mark.parametrize("dialect", ["syntec", "fanuc", "szgh", "series8"])
def test_dwell_with_a_move_is_rejected_in_the_fanuc_family(dialect: str) -> None:
    lines, r = canon(prog(dialect, "G01 X1. F100.", f"{DWELL[dialect]} G01 Z-1.", "G01 Y2."), dialect)
    assert "E0261" in codes(r), codes(r)
    assert not calls(lines, "DWELL")  # neither half of the block runs
    assert [a[:3] for _, a in calls(lines, "STRAIGHT_FEED")] == [[1.0, 0.0, 0.0], [1.0, 2.0, 0.0]]


@pytest.mark.parametrize("dialect", ["syntec", "fanuc", "szgh", "series8"])
def test_g04_x_alone_is_still_a_dwell(dialect: str) -> None:
    lines, r = canon(prog(dialect, "G01 X1. F100.", "G04 X2.5"), dialect)
    assert not [c for c in codes(r) if c.startswith("E")], codes(r)
    assert [a for _, a in calls(lines, "DWELL")] == [[2.5]]
    assert [a[0] for _, a in calls(lines, "STRAIGHT_FEED")] == [1.0]  # X2.5 is a time, not a move


def test_axis_words_taken_by_another_code_are_not_silent() -> None:
    _, r = canon("G21 G90\nG92 X0 G01 Y5. F100.\nM30\n", "fanuc")
    assert "W0262" in codes(r)
