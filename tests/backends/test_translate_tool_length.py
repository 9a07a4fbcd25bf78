"""Tool length in a translation: an H number the source programs is the target's H number.

SYNTEC Mill v8.20 §4.21 (/work/shared/spec/syntec-mill-v8.20.md): ``{G43|G44} Z_ H_`` applies the
length that H holds in the control's table (Z_eff = Z + H value), ``G49`` cancels it; FANUC, SZGH
and LinuxCNC have the same codes.  So ``G43 Z15. H01`` becomes ``G43 H1`` in the target, whatever
length cncc assumed for H1 (no ``--tools`` table: 0, warning W0513): the target's table applies, as
the source's does.  It is written once, not before every move (the bug: a zero length with an H
number was written as G49 before every motion block).
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from cncc.api import compile_commands, compile_text
from tests.helpers import codes
from tests.translate.motion import difference, motion

POCKET = """%
O2001;
G71 G90 G94 G17 G40 G49 G80;
T1 M06;
S5000 M03;
G54 G00 X0. Y0.;
G43 Z15. H01;
G00 Z5.;
G01 Z-0.5 F300.;
G01 X10. Y1.;
G01 X10. Y10.;
G01 X0. Y10.;
G00 Z15.;
G49 G00 Z50.;
M30;
%
"""

LENGTH_CODES = re.compile(r"\bG4[349]\b")
TARGETS = ("fanuc", "szgh", "syntec", "linuxcnc")


def length_blocks(text: str) -> list[str]:
    return [line.rstrip(";") for line in text.splitlines() if LENGTH_CODES.search(line)]


@pytest.mark.parametrize("target", TARGETS)
def test_an_h_number_without_a_table_is_written_once_as_the_targets_g43(target: str) -> None:
    r = compile_text(POCKET, dialect="syntec", emit="gcode", target=target)
    assert "W0513" in codes(r)  # no tool table: H1 is taken as 0 here
    # the source: G43 H01 (once), the G49 of the last move block (once); nothing between the moves
    blocks = length_blocks(r.output)
    assert blocks == ["G43 H1", "G49"], r.output


@pytest.mark.parametrize("target", TARGETS)
def test_the_translation_moves_like_the_source_with_a_table(target: str, tmp_path: Path) -> None:
    """With a tool table (H1 = 25 mm) the moves of the re-read translation are the source's."""
    tools = tmp_path / "tools.toml"
    tools.write_text("units = \"mm\"\n[tools.1]\nlength_mm = 25.0\nradius_mm = 0.0\n")
    assert compile_text(POCKET, dialect="syntec", emit="canon", tools_file=str(tools)).ok
    out = compile_text(POCKET, dialect="syntec", emit="gcode", target=target, tools_file=str(tools))
    assert length_blocks(out.output)[0].split() == ["G43", "H1"], out.output
    want = motion(compile_commands(POCKET, dialect="syntec", tools_file=str(tools))[0])
    got = motion(compile_commands(out.output, dialect=target, tools_file=str(tools))[0])
    assert want[1] == ("rapid", (0.0, 0.0, 15.0 + 25.0, 0.0, 0.0, 0.0))  # G43 Z15. H01: Z + H1 (machine terms)
    assert not difference(want, got, 1e-3), out.output


def test_a_zero_g44_stays_g44() -> None:
    """G44 H2 with a zero length (-0.0 in the frame) is the target's G44 H2, not G43."""
    text = "G90 G00 X0 Y0 Z50.\nG44 Z20. H02\nG01 X5. F100\nG49 G00 Z50.\nM30\n"
    r = compile_text(text, dialect="syntec", emit="gcode", target="fanuc")
    assert length_blocks(r.output) == ["G44 H2", "G49"], r.output


# Found by tests/pipeline/test_unmoved_axes.py: G43 on a block whose Z is the one written last.  A
# target without G43 (series8 here) gets the length folded into Z, and the tool goes up by it; the
# block wrote nothing for Z ("G00 Y0."), so the arc after it started 40 mm too low (E0253 on re-read).
SAME_Z = ("G71 G90 G94 G19 G40 G49 G80\nG00 Y0. Z0.\nG00 G43 Z0. H1\nG91 G02 Y-8. Z-8. R6.157 F300.\nG90\n"
          "G49 G00 Z0.\nM30\n")


@pytest.mark.parametrize("target", ["series8", "fanuc", "grbl", "linuxcnc", "szgh", "haas"])
def test_a_length_on_an_unchanged_z_moves_the_tool(target: str, tmp_path: Path) -> None:
    tools = tmp_path / "tools.toml"
    tools.write_text("units = \"mm\"\n[tools.1]\nlength_mm = 40.0\nradius_mm = 0.0\n")
    out = compile_text(SAME_Z, dialect="syntec", emit="gcode", target=target, tools_file=str(tools))
    assert out.ok, [(d.code, d.message) for d in out.sink.items]
    cmds, again = compile_commands(out.output, dialect=target, tools_file=str(tools))
    assert not [d.code for d in again.sink.items if d.code.startswith("E")], out.output
    want = motion(compile_commands(SAME_Z, dialect="syntec", tools_file=str(tools))[0])
    assert want[1][1][2] == 40.0  # G43 Z0. H1: Z + H1 in machine terms (SYNTEC §4.21)
    assert not difference(want, motion(cmds), 1e-3), out.output
