"""LinuxCNC's work-system rotation (G10 L2 R) reaches every output, and G28/G30 as LinuxCNC has them.

The canon trace keeps rs274's program coordinates (the oracle suite compares it); a translation,
-E and the machine-coordinate backends carry the rotated point: LinuxCNC places a program point
at ``R(theta) (p + g92) + g5x``.  Expected values are computed here from that formula.
"""

from __future__ import annotations

import math
import re

import pytest

from tests.helpers import calls, canon, compile_commands, compile_text

ROTATED = "G21 G90\nG10 L2 P1 X10 R30\nG0 X10 Y0\nG1 F100 X10 Y10\nG1 Z-2\nG91 G1 X5\nG90\nM2\n"


def _turn(x: float, y: float, deg: float) -> tuple[float, float]:
    a = math.radians(deg)
    return math.cos(a) * x - math.sin(a) * y, math.sin(a) * x + math.cos(a) * y


def _axis_words(text: str) -> list[dict[str, float]]:
    out = []
    for line in text.splitlines():
        if re.match(r"^G0[01]\b", line):
            out.append({m.group(1): float(m.group(2)) for m in re.finditer(r"([XYZ])(-?[\d.]+)", line)})
    return out


@pytest.mark.parametrize("target", ["fanuc", "grbl"])
def test_translation_writes_the_rotated_points(target: str) -> None:
    r = compile_text(ROTATED, dialect="linuxcnc", emit="gcode", target=target)
    assert r.ok, [(d.code, d.message) for d in r.sink]
    words = _axis_words(r.output)
    ends = [_turn(10, 0, 30), _turn(10, 10, 30)]
    assert words[0]["X"] == pytest.approx(ends[0][0], abs=1e-3) and words[0]["Y"] == pytest.approx(ends[0][1], abs=1e-3)
    assert words[1]["X"] == pytest.approx(ends[1][0], abs=1e-3) and words[1]["Y"] == pytest.approx(ends[1][1], abs=1e-3)
    assert set(words[2]) == {"Z"}  # a Z move stays a Z move: no axis the program does not move
    inc = _turn(15, 10, 30)  # G91 X5 from (10, 10): the increment turns with the system
    assert words[3]["X"] == pytest.approx(inc[0], abs=1e-3) and words[3]["Y"] == pytest.approx(inc[1], abs=1e-3)
    assert "N0801" in {d.code for d in r.sink}  # the note that cncc applied the rotation


def test_expanded_program_has_the_rotated_points() -> None:
    r = compile_text(ROTATED, dialect="linuxcnc", emit="gcode", expand=True)
    assert r.ok
    words = _axis_words(r.output)
    end = _turn(10, 10, 30)
    assert words[1]["X"] == pytest.approx(end[0], abs=1e-3) and words[1]["Y"] == pytest.approx(end[1], abs=1e-3)
    assert set(words[2]) == {"Z"}
    assert not re.search(r"G10 L2 [^\n]*R", r.output)  # the rotation is in the points, not written again


def test_canon_trace_keeps_program_coordinates() -> None:
    lines, r = canon(ROTATED, dialect="linuxcnc")
    assert r.ok
    ends = [tuple(a[:2]) for _, a in calls(lines, "STRAIGHT_TRAVERSE", "STRAIGHT_FEED")]
    assert ends[:2] == [(10.0, 0.0), (10.0, 10.0)]


def test_machine_positions_are_rotated_with_g92_inside() -> None:
    # LinuxCNC adds the G92 offset before it turns the point: machine = R (p + g92) + g5x.
    text = "G21 G90\nG10 L2 P1 X10 R90\nG0 X0 Y0\nG92 X-2\nG1 F100 X1 Y1\nM2\n"
    cmds, r = compile_commands(text, dialect="linuxcnc", emit="timing")
    assert r.ok
    ends = [c.end for c in cmds if type(c).__name__ in ("Rapid", "Linear")]
    g5x, g92 = (10.0, 0.0), (2.0, 0.0)
    want = _turn(1 + g92[0], 1 + g92[1], 90)
    assert ends[-1][0] == pytest.approx(want[0] + g5x[0]) and ends[-1][1] == pytest.approx(want[1] + g5x[1])


def test_g28_with_axis_words_homes_only_those_axes() -> None:
    # LinuxCNC: through the given point, then only the named axes go home (rs274 2.9 prints the same).
    lines, r = canon("G21\nG0 X5 Y6 Z7\nG28 X1\nG0 X5\nG28\nM2\n", dialect="linuxcnc")
    assert r.ok
    ends = [tuple(a[:3]) for _, a in calls(lines, "STRAIGHT_TRAVERSE")]
    assert ends == [(5, 6, 7), (1, 6, 7), (0, 6, 7), (5, 6, 7), (5, 6, 7), (0, 0, 0)]


def test_g28_home_leg_under_rotation_is_the_machine_home() -> None:
    text = "G21\nG10 L2 P1 X10 Y5 R30\nG0 X3 Y4\nG28 X1 Y1\nM2\n"
    lines, _ = canon(text, dialect="linuxcnc")
    home = [a for _, a in calls(lines, "STRAIGHT_TRAVERSE")][-1]
    want = _turn(-10, -5, -30)  # machine (0, 0) in the rotated system
    assert home[0] == pytest.approx(want[0], abs=1e-4) and home[1] == pytest.approx(want[1], abs=1e-4)


def test_g10_l20_under_rotation_gives_the_named_coordinate() -> None:
    # The current point takes X0 in the rotated system and keeps its Y there.
    text = "G21\nG10 L2 P1 X10 Y5 R30\nG0 X3 Y4\nG10 L20 P0 X0\nG0 Z1\nM2\n"
    lines, _ = canon(text, dialect="linuxcnc")
    g5x = [a for _, a in calls(lines, "SET_G5X_OFFSET")][-2]
    m = _turn(3, 4, 30)
    m = (m[0] + 10, m[1] + 5)
    keep = _turn(0, 4, 30)
    assert g5x[1] == pytest.approx(m[0] - keep[0], abs=1e-4) and g5x[2] == pytest.approx(m[1] - keep[1], abs=1e-4)
    assert calls(lines, "STRAIGHT_TRAVERSE")[-1][1][:2] == [0.0, 4.0]


def test_r_on_g10_l20_is_an_error() -> None:
    r = compile_text("G21\nG10 L20 P1 X1 R30\nM2\n", dialect="linuxcnc")
    assert not r.ok and any("R not allowed in G10 L20" in d.message for d in r.sink)
