"""A translation never writes a number for an axis the source leaves where the machine is.

An axis the program has not positioned (``Frame.held_axes``: not named since the start) is at
the machine's start, which the translation does not know.  SYNTEC Mill §1.2 (/work/shared/spec/
syntec-mill-v8.20.md): a block moves only the axes it names; a canned-cycle hole is at the
named X/Y, the others where the tool is; an omitted G51 centre coordinate is the current
position.  So the kept cycle and the kept scaling must not name the held axis (``X0.``, ``Z0.``
would move it from wherever it is to 0), and read back from any start the axis stays put.
"""

from __future__ import annotations

import re

import pytest

from cncc.api import compile_commands, compile_text
from cncc.ir import Arc, Linear, Rapid

START = (13.0, -7.0, 25.0)


def positions(text: str, dialect: str, axis: int) -> set[float]:
    cmds, r = compile_commands(text, dialect=dialect, start_machine_mm=START)
    assert r.ok, [(d.code, d.message) for d in r.sink]
    return {round(p[axis] + c.frame.total_offset_mm[axis], 6) for c in cmds if isinstance(c, Rapid | Linear | Arc)
            for p in (c.start, c.end)}


CYCLE = "G71 G90 G17 G00 Y0. Z10.\nG99 G81 Y5. Z-3. R2. F150.\nY12.\nG80\nM30\n"  # X never named


@pytest.mark.parametrize("target", ["fanuc", "syntec", "szgh"])
def test_a_kept_cycle_names_no_held_plane_axis(target: str) -> None:
    out = compile_text(CYCLE, dialect="syntec", emit="gcode", target=target).output
    assert re.search(r"G81 Y5\. Z-3\. R2\. F150\.", out), out  # the first hole: Y only, as programmed
    assert not re.search(r"\bX", out), out
    assert positions(out, target, 0) == positions(CYCLE, "syntec", 0) == {START[0]}


def test_a_repeat_at_a_held_point_drills_where_the_tool_is() -> None:
    text = "G71 G90 G17 G00 Z10.\nG99 G81 Z-3. R2. F150. K2\nG80\nM30\n"  # X and Y never named
    out = compile_text(text, dialect="syntec", emit="gcode", target="fanuc").output
    assert not re.search(r"\b[XY]", out), out
    assert out.count("Z-3.") == 2, out  # two holes: the data block, then the depth word again


SCALE = "G71 G90 G17 G00 X0. Y0.\nG51 X0. Y0. P2.\nG01 X10. F500.\nG00 Y5.\nG50\nM30\n"  # Z never named


@pytest.mark.parametrize("target", ["fanuc", "syntec"])
def test_a_kept_scaling_leaves_out_the_centre_of_a_held_axis(target: str) -> None:
    out = compile_text(SCALE, dialect="syntec", emit="gcode", target=target).output
    assert "G51 X0. Y0. P2." in out, out
    assert positions(out, target, 2) == positions(SCALE, "syntec", 2) == {START[2]}


def test_szgh_scales_named_axes_only_so_cncc_applies_the_scaling() -> None:
    # SZGH G36 scales the axes it names (spec szgh-990mdb §3.22): G36 X0. Y0. R2. would leave Z unscaled
    # and G36 X0. Y0. Z0. R2. would assume Z starts at 0, so the output carries scaled coordinates
    r = compile_text(SCALE, dialect="syntec", emit="gcode", target="szgh")
    assert "G36" not in r.output and "N0802" in {d.code for d in r.sink}, r.output
    assert positions(r.output, "szgh", 2) == {START[2]}
    assert positions(r.output, "szgh", 0) == positions(SCALE, "syntec", 0)
