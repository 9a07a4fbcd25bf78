"""LinuxCNC's trace imitation is the canon backend's: the interpreter's COMMENT lines and the
M2 resets are in the canon trace (as rs274 2.9 prints them) and in no translation."""

from __future__ import annotations

from pathlib import Path

import pytest

from cncc.api import compile_text

PROGRAM = ("G21 G17 G90 F100\nG40 G80\nG1 X1\nG54\nG91 G1 X1\nG90\nG90.1\nG91.1\nG98\nG99\nM3 S100\nM8\n"
           "G81 X1 Y1 Z-1 R1\nG80\nG93 G1 X3 F2\nG94 F20\nG95 F1\nG94 F20\nG1 X2\nM2\n")
EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "linuxcnc_pocket.ngc"


def test_canon_trace_has_the_reports() -> None:
    out = compile_text(PROGRAM, dialect="linuxcnc", emit="canon").output
    for text in ("cutter radius compensation off", "motion mode set to none", "continuing to use same coordinate",
                 "distance mode changed to incremental", "IJK distance mode changed to absolute",
                 "retract mode set to old_z", "feed mode set to inverse time", "feed mode set to units per minute"):
        assert f'COMMENT("interpreter: {text}' in out, text
    end = out.splitlines()[-10:]  # the M2 resets before PROGRAM_END
    assert [ln for ln in end if "STOP_SPINDLE" in ln or "FLOOD_OFF" in ln] and "PROGRAM_END()" in end[-3]


@pytest.mark.parametrize("target", ["fanuc", "linuxcnc", "grbl"])
def test_translation_has_no_interpreter_trace(target: str) -> None:
    for text in (PROGRAM, EXAMPLE.read_text()):
        r = compile_text(text, dialect="linuxcnc", emit="gcode", target=target)
        assert "interpreter" not in r.output.lower()
        assert r.ok, [d.message for d in r.sink]
