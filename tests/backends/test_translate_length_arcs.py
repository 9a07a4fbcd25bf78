"""Tool length changes before arcs, translated to LinuxCNC and read back (cncc, and rs274 when installed).

The bug: a Fanuc-family source applies ``G49`` (or ``G43 H_``) with its next move, so a following arc
without a Z word ends at the programmed Z in the new offset; LinuxCNC shifts the program position by
the offset change at once (rs274ngc ``convert_tool_length_offset``), so the translation's arc with no Z
word stayed 50 mm higher, and the next arc that named Z (G18/G19) was read back with E0208 ("radius to
end of arc differs from radius to start") by cncc and by rs274.  Since the fix the move after a tool
length block always names the tool axis.

The programs are generated: G43 H1/H2 and G49 between G17 arcs (with or without a Z word) and G18/G19
arcs after a Z move; the check is that the re-read translation has no errors and reaches the source's
machine positions (:mod:`tests.translate.motion`), and that rs274 2.9 runs it without an error.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from cncc.api import compile_commands, compile_text
from tests.oracle.harness import rs274_path, run_rs274
from tests.translate.motion import close, motion

TOOLS = Path(__file__).parents[1] / "translate" / "tools.toml"  # H1 = 50 mm, H2 = 42.5 mm
RS274_TOOLS = "T1 P1 Z1.968504\nT2 P2 Z1.673228\n"  # the same lengths in inches (rs274's machine units)
LENGTH = ("G43 H1", "G43 H2", "G49")


def _arc(plane: str, k: int, z_word: bool) -> list[str]:
    """A half circle of radius 5 in ``plane`` from where the tool is (X and Y on a 10 mm grid, Z at 2)."""
    if plane == "G17":
        x = 10.0 * (k + 1)
        return [f"G2 X{x:.1f} Y0.{' Z2.' if z_word else ''} I5. J0."]
    if plane == "G18":
        x = 10.0 * (k + 1)
        return ["G1 Z2.", f"G18 G2 X{x:.1f} Z2. I5. K0.", "G17"]
    return ["G1 Z2.", "G19 G2 Y10. Z2. J5. K0.", "G19 G2 Y0. Z2. J-5. K0.", "G17"]


@st.composite
def programs(draw: st.DrawFn) -> str:
    lines = ["G17 G21 G90", "G0 X0. Y0.", "G43 H1 Z5.", "G1 Z2. F100."]
    x = 0
    for _ in range(draw(st.integers(1, 4))):
        lines.append(draw(st.sampled_from(LENGTH)))
        for _ in range(draw(st.integers(1, 3))):
            plane = draw(st.sampled_from(("G17", "G18", "G19")))
            if plane == "G19":
                lines += _arc(plane, x, False)
            else:
                lines += _arc(plane, x, draw(st.booleans()))
                x += 1
    lines += ["G49", "G0 Z50.", "M30"]
    return "\n".join(lines) + "\n"


def _positions(text: str, dialect: str) -> list[tuple[float, ...]]:
    return [m[1] for m in motion(compile_commands(text, dialect=dialect, tools_file=str(TOOLS))[0])]


@pytest.mark.parametrize("source", ["fanuc", "linuxcnc"])
@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(text=programs())
def test_tool_length_then_arcs_read_back_without_errors(source: str, text: str) -> None:
    src = compile_text(text, dialect=source, emit="canon", tools_file=str(TOOLS))
    assert src.ok, [str(d) for d in src.diagnostics]
    out = compile_text(text, dialect=source, emit="gcode", target="linuxcnc", tools_file=str(TOOLS))
    assert out.ok, [str(d) for d in out.diagnostics]
    back = compile_text(out.output, dialect="linuxcnc", emit="canon", tools_file=str(TOOLS))
    assert back.ok, (out.output, [str(d) for d in back.diagnostics])
    want, got = _positions(text, source), _positions(out.output, "linuxcnc")
    assert len(want) == len(got), out.output
    for k, (w, g) in enumerate(zip(want, got, strict=True)):
        assert close(w, g, 1e-3), (k, w, g, out.output)
    if rs274_path() is not None:
        r = run_rs274(out.output, RS274_TOOLS)
        assert r.ok, (r.error, out.output)


def test_the_arc_after_g49_names_z() -> None:
    """The case of the report: Fanuc G49, an XY arc with no Z word, then an XZ arc (was E0208 on read-back)."""
    text = "G17 G21 G90\nG0 X0. Y0.\nG43 H1 Z5.\nG1 Z2. F100.\nG49\nG2 X10. Y0. I5. J0.\nG18\nG2 X20. I5. K0.\nM30\n"
    out = compile_text(text, dialect="fanuc", emit="gcode", target="linuxcnc", tools_file=str(TOOLS))
    arc = next(line for line in out.output.splitlines() if line.startswith("G02 X10."))
    assert " Z2." in arc, out.output  # the tool tip's Z with no offset: where the Fanuc source's arc ends
    back = compile_text(out.output, dialect="linuxcnc", emit="canon", tools_file=str(TOOLS))
    assert back.ok, [str(d) for d in back.diagnostics]
    if rs274_path() is not None:
        r = run_rs274(out.output, RS274_TOOLS)
        assert r.ok, (r.error, out.output)


def test_a_flat_arc_after_g49_keeps_its_feed_in_a_fanuc_translation() -> None:
    """LinuxCNC G49 shifts the program Z at once, so its next XY arc with no Z word is flat on the machine
    (Z stays where the tool is).  The Fanuc translation names Z (that same machine Z, now with no offset)
    and, the arc being flat, keeps F: before, the writer took the offset change for a 50 mm rise and
    wrote the projection feed of that helix (F29.972 for F100)."""
    text = "G17 G21 G90\nG0 X0. Y0.\nG43 H1 Z5.\nG1 Z2. F100.\nG49\nG2 X10. Y0. I5. J0.\nM30\n"
    out = compile_text(text, dialect="linuxcnc", emit="gcode", target="fanuc", tools_file=str(TOOLS))
    arc = next(line for line in out.output.splitlines() if line.startswith("G02 X10."))
    assert " Z52." in arc and " F" not in arc, out.output  # 2 + 50 (H1): the tool did not move in Z
