"""What LinuxCNC refuses while cutter compensation is on (cncc/frontend/linuxcnc/comp_rules.py).
The expected verdicts and texts were measured on LinuxCNC 2.9's stand-alone rs274 (the oracle
suite compares generated programs of this class with it: tests/oracle/gen_comp_rules.py)."""

from __future__ import annotations

import pytest

from cncc.api import compile_text
from tests.helpers import codes

_PROGRAM = "G21 F100\nT1 M6\nG0 X-20 Y-20\n{on}\n{code}\nG1 X10 Y10\nG40 G1 X30 Y30\nM2\n"
_ON_MOVED = "G41.1 D2 G1 X0 Y0\nG1 X10"


def _run(code: str, on: str = _ON_MOVED) -> tuple[list[str], str]:
    r = compile_text(_PROGRAM.format(on=on, code=code), dialect="linuxcnc", emit="canon")
    errors = [d for d in r.sink if d.code.startswith("E")]
    return codes(r), errors[0].message if errors else ""


@pytest.mark.parametrize(("code", "text"), [
    ("G53 G0 X0", "Cannot use g53 with cutter radius comp"),
    ("G28", "Cannot use g28 or g30 with cutter radius comp"),
    ("G30 X1", "Cannot use g28 or g30 with cutter radius comp"),
    ("G28.1", "Cannot set reference point with cutter compensation in effect"),
    ("G92 X0", "Cannot change axis offsets with cutter radius comp"),
    ("G52 X1", "Cannot change axis offsets with cutter radius comp"),
    ("G10 L2 P1 X1", "Cannot change the active coordinate system with cutter radius compensation on"),
    ("G10 L20 P0 X1", "Cannot change the active coordinate system with cutter radius compensation on"),
    ("G55", "Cannot change coordinate systems with cutter radius compensation on"),
    ("G54", "Cannot change coordinate systems with cutter radius compensation on"),
    ("G98", "Cannot change retract mode with cutter radius compensation on"),
    ("G64", "Cannot change control mode with cutter radius compensation on"),
    ("T1 M6", "Cannot change tools with cutter radius compensation on"),
    ("G40 M6", "Cannot change tools with cutter radius compensation on"),  # M6 runs before G40
    ("G43 H1", "Cannot change tool offset with cutter radius compensation on"),
    ("G49", "Cannot change tool offset with cutter radius compensation on"),
    ("G81 X1 Y1 Z-1 R1", "Cannot use canned cycles with cutter compensation on"),
    ("G42 D1", "Cannot turn cutter radius comp on when on"),
    ("M50 P0", "Cannot disable overrides with cutter radius compensation on"),
    ("#1 = #5420", "Cannot read current position with cutter radius compensation on"),
])
def test_refused_with_rs274s_text(code: str, text: str) -> None:
    got, message = _run(code)
    assert "E0572" in got
    assert message.startswith(text)


@pytest.mark.parametrize("code", ["G10 L2 P2 X1", "T1", "G40 G53 G0 X0", "G55 G40", "G40 G28",
                                  "G81 X1 Y1 Z-1 R1 G40", "(debug, #5420)", "M8", "G4 P0.1", "G21"])
def test_allowed_as_rs274_allows_it(code: str) -> None:
    got, _ = _run(code)
    assert "E0572" not in got


def test_compensation_turned_on_without_a_move_already_counts() -> None:
    got, message = _run("G53 G0 X0", on="G41.1 D2")
    assert "E0572" in got and message.startswith("Cannot use g53")


def test_g41_in_the_block_turns_it_on_before_g28() -> None:
    text = "G21 F100\nG0 X-20 Y-20\nG41.1 D2 G28\nG40\nM2\n"
    r = compile_text(text, dialect="linuxcnc", emit="canon")
    assert "E0572" in codes(r)


def test_other_dialects_keep_their_rules() -> None:
    r = compile_text("G21 F100\nG0 X-20 Y-20\nG41 D1 G1 X0 Y0\nG1 X10\nG53 G0 X0\nG40\nM30\n", dialect="fanuc")
    assert "E0572" not in codes(r)


def test_g92_1_is_ignored_while_compensation_is_on() -> None:
    # rs274 2.9 runs G92.1/G92.2/G92.3 as nothing while compensation is on: no SET_G92_OFFSET
    text = "G21 F100\nG0 X-20 Y-20\nG92 X3\nG41.1 D2 G1 X0 Y0\nG92.1\nG1 X10\nG40 G1 X30\nM2\n"
    r = compile_text(text, dialect="linuxcnc", emit="canon")
    assert not r.sink.has_errors
    offsets = [ln.split("N.....")[1].strip() for ln in r.output.splitlines() if "SET_G92_OFFSET" in ln]
    assert offsets[1:] == ["SET_G92_OFFSET(-23.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)"]  # G92 X3 only
