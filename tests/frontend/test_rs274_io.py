"""M62-M68 in the IR: kept with their words in LinuxCNC output, said to be dropped elsewhere.

(Their checks and the empty canon trace are judged by rs274 2.9: tests/oracle/cases.py, io_*.)
"""

from __future__ import annotations

from cncc.api import compile_text

PROGRAM = "G21\nM62 P3\nG1 X1 F100\nM66 P1 L1 Q2.5\nM68 E0 Q-2.5\nM2\n"


def test_linuxcnc_writes_them_back_with_their_words() -> None:
    r = compile_text(PROGRAM, dialect="linuxcnc", emit="gcode")
    assert r.ok
    lines = r.output.splitlines()
    assert "M62 P3" in lines and "M66 P1 L1 Q2.5" in lines and "M68 E0 Q-2.5" in lines
    again = compile_text(r.output, dialect="linuxcnc", emit="gcode")
    assert again.ok
    io = [ln for ln in r.output.splitlines() if ln.startswith(("M62", "M66", "M68"))]
    assert [ln for ln in again.output.splitlines() if ln.startswith(("M62", "M66", "M68"))] == io


def test_another_dialect_is_told_they_are_dropped() -> None:
    r = compile_text(PROGRAM, dialect="linuxcnc", emit="gcode", target="grbl")
    assert r.ok
    assert not any(line.startswith(("M62", "M66", "M68")) for line in r.output.splitlines())
    assert any(d.code == "W0810" and "M62" in d.message for d in r.sink.items)


def test_they_take_no_time_and_move_nothing() -> None:
    with_io = compile_text(PROGRAM, dialect="linuxcnc", emit="timing", opt_level=1, quiet=True)
    plain = compile_text("G21\nG1 X1 F100\nM2\n", dialect="linuxcnc", emit="timing", opt_level=1, quiet=True)
    assert with_io.ok and plain.ok
    assert with_io.runs[0].trajectory is not None and plain.runs[0].trajectory is not None
    assert abs(with_io.runs[0].trajectory.duration_total_s - plain.runs[0].trajectory.duration_total_s) < 1e-9
