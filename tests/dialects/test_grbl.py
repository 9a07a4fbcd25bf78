"""grbl 1.1: programs grbl rejects are rejected with grbl's error number and reason."""

from __future__ import annotations

import pytest

from cncc.dialects import load_dialect
from tests.helpers import canon, moves

HEAD = "G21 G90 G17 G94\nG0 X0 Y0 Z0\n"


def grbl_errors(text: str) -> list[tuple[int, int]]:
    """(line, grbl error number) of every rejected block."""
    _, r = canon(text, "grbl")
    out = []
    for d in r.sink:
        if d.code == "E0250":
            number = int(d.message.split("error:")[1].split()[0])
            line = r.sources.get(d.span.source_id).position(d.span.start).line  # type: ignore[union-attr]
            out.append((line, number))
    return out


# (block after HEAD, grbl's error number); each expectation follows grbl 1.1's gcode.c checks.
REJECTED = [
    ("G41 D1 X5", 20),            # no cutter compensation
    ("G81 X1 Y1 Z-1 R1", 20),     # no canned cycles
    ("G1 X1 Q3 F100", 20),        # no Q word
    ("G1 A10 F100", 20),          # three axes only
    ("M6", 20),                   # no tool changer
    ("M98 P100", 20),             # no subprograms
    ("G43 H1", 20),               # only G43.1
    ("G90.1", 20),                # arc centres always incremental
    ("G61.1", 20),
    ("G28.2", 20),
    ("G59.1", 23),                # G59.x
    ("G1.5 X1", 23),              # not an integer command
    ("M3.5", 23),
    ("G17 G18", 21),              # modal group
    ("G0 G1 X1", 24),             # grbl checks the axis-command conflict first
    ("M7 M8", 21),                # M7 and M8 share grbl's coolant group
    ("M3 M4", 21),
    ("G1 G92 X0 F10", 24),        # two commands use the axis words
    ("G1 X1 X2 F10", 25),         # repeated word
    ("F-3", 4),                   # negative value
    ("S-100", 4),
    ("T256", 38),                 # MAX_TOOL_NUMBER 255
    ("N10000001 G0 X1", 27),      # line number range
    ("G1 X10", 22),               # no feed yet
    ("G4", 28),                   # dwell without P
    ("G10 L2 X1", 28),            # G10 without P
    ("G10 L3 P1 X1", 20),         # only L2/L20
    ("G10 L2 P7 X0", 29),         # G54-G59 only
    ("G10 L20 P1", 26),           # no axis words
    ("G92", 26),
    ("G2 G53 X1 Y1 I1 F10", 30),  # G53 with G0/G1 only
    ("G43.1 X5", 37),             # G43.1 takes Z only
    ("G2 I5 F100", 26),           # arc without axis words
    ("G2 Z5 I5 F100", 32),        # no in-plane axis word
    ("G2 X10 F100", 35),          # no in-plane offset
    ("G2 X10 Y0 R4 F100", 34),    # radius below half the chord (4 < 5)
    ("G2 X0 Y0 R4 F100", 33),     # R arc ending where it starts
    ("G80\nX5", 31),              # axis words with no motion mode
    ("G0 X1 P2", 36),             # P not used
    ("G2 X10 Y0 R5 I5 F100", 36), # I unused in radius mode
    ("#1=5", 1),                  # no parameters
    ("G1 X[1+2] F10", 1),         # no expressions
    ("G1 X" + "1" * 80 + " F10", 11),  # line overflow
]


@pytest.mark.parametrize("block, number", REJECTED)
def test_rejected_with_grbls_error(block: str, number: int) -> None:
    errors = grbl_errors(HEAD + block + "\n")
    assert errors and errors[-1][1] == number, errors


def test_arc_radius_rules() -> None:
    # From (0,0) to (10,0) about (5,j): both radii equal whatever j -> accepted.
    assert grbl_errors(HEAD + "G2 X10 Y0 I5 J1 F100\n") == []
    # End radius 5.0, start radius hypot(5, 0.1) = 5.000999: 0.001 mm difference: accepted (< 0.005).
    assert grbl_errors(HEAD + "G2 X10 Y0.2 I5 J0.1 F100\n") == []
    # Centre (5,0): start radius 5, end (10,0.1) radius hypot(5,0.1): diff 0.001 -> fine; end (10,1):
    # radius 5.0990, diff 0.099 mm > 0.005 and > 0.1 % of 5 mm (0.005) -> error 33.
    assert grbl_errors(HEAD + "G2 X10 Y1 I5 J0 F100\n") == [(3, 33)]
    # Radius 1000 mm: a 0.3 mm difference is within 0.1 % (1 mm) and under 0.5 mm -> accepted;
    # a 0.7 mm difference is over the 0.5 mm cap -> error 33.
    assert grbl_errors(HEAD + "G2 X2000 Y0.3 I1000 J0 F100\n") == []
    assert grbl_errors(HEAD + "G2 X2000.7 Y0 I1000 J0 F100\n") == [(3, 33)]


def test_rejected_block_does_not_run() -> None:
    got = moves(HEAD + "G1 X5 F100\nG1 X9 Q1\nG1 X7\n", "grbl")
    assert [m[1][0] for m in got] == [0.0, 5.0, 7.0]


def test_accepted_program_runs() -> None:
    prog = HEAD + "G43.1 Z2\nG92 X0\nG92.1\nG10 L20 P1 X5\nG1 X1 F300\nG91.1\nG93 G1 X2 F60\nM7\nM8\nM9\nM30\n"
    errors = grbl_errors(prog)
    assert errors == []


def test_unsupported_table_is_shared_data() -> None:
    d = load_dialect("grbl")
    assert d.unsupported_reason("G", 410) is not None  # the LSP and the translator read this table
    assert d.unsupported_reason("G", 10) is None
    assert d.unsupported_reason("Q") is not None
