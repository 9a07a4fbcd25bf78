"""Progress on long pulse runs (issue 14): a rich bar with percentage and ETA on a terminal,
for planning and for the pulses, quiet on a pipe and with -q."""

from __future__ import annotations

import io
import re
import sys
from pathlib import Path

import pytest

from cncc.api import compile_commands
from cncc.backends.pulses import generate_pulses, progress
from cncc.backends.timing import progress as timing_progress
from cncc.cli import main
from cncc.diagnostics import DiagnosticSink
from cncc.machines import load_machine
from cncc.passes.plan import plan_commands


class Tty(io.StringIO):
    def isatty(self) -> bool:
        return True


PROGRAM = "G21 G90 G17 G94\nG0 X0. Y0. Z0.\n" + "".join(
    f"G1 X{40.0 * (k % 2):.1f} Y{0.5 * k:.1f} F3000.\n" for k in range(60)) + "M30\n"


def _traj():  # type: ignore[no-untyped-def]
    cmds, _ = compile_commands(PROGRAM, emit="pulses")
    machine = load_machine("generic-mill")
    return plan_commands(cmds, machine, level=2, sink=DiagnosticSink()), machine


def test_estimated_steps_is_the_net_travel_in_steps() -> None:
    traj, machine = _traj()
    # lines k = 1..59 of the zig-zag (k = 0 stays at the origin): 40 mm in X and 0.5 mm in Y each,
    # at 800 steps/mm (generic-mill)
    want = 59 * (40 + 0.5) * 800
    assert progress.estimated_steps(traj, machine) == pytest.approx(want, rel=1e-6)


def test_pulse_bar_on_a_terminal_only_and_not_with_quiet(monkeypatch: pytest.MonkeyPatch) -> None:
    traj, machine = _traj()
    chunks = list(generate_pulses(traj, machine, chunk_steps=2000))
    total = chunks[-1].t_end_ns
    monkeypatch.setattr(progress, "MIN_STEPS", 1000)
    for stream, quiet, drawn in ((Tty(), False, True), (Tty(), True, False), (io.StringIO(), False, False)):
        assert list(progress.track(iter(chunks), total, 10**6, quiet, stream)) == chunks
        text = stream.getvalue()
        assert (len(text) > 0) is drawn
        if drawn:
            assert "pulses" in text and "100%" in text
    small = Tty()
    assert list(progress.track(iter(chunks), total, 999, False, small)) == chunks
    assert small.getvalue() == ""


@pytest.mark.parametrize(("quiet", "tty", "drawn"), [(False, True, True), (True, True, False), (False, False, False)])
def test_cli_pulses_report_planning_and_pulses(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, quiet: bool,
                                               tty: bool, drawn: bool) -> None:
    src = tmp_path / "zigzag.nc"
    src.write_text(PROGRAM)
    monkeypatch.setattr(progress, "MIN_STEPS", 1000)
    monkeypatch.setattr(timing_progress, "PLAN_MIN_ITEMS", 10)
    err = Tty() if tty else io.StringIO()
    monkeypatch.setattr(sys, "stderr", err)
    args = [str(src), "--emit=pulses", "--pulse-format=queue", "-o", str(tmp_path / "out.queue")]
    assert main([*args, "-q"] if quiet else args) == 0
    text = re.sub(r"\x1b\[[0-9;?]*[A-Za-z]", "", err.getvalue())
    assert ("planning -O2" in text) is drawn
    assert ("pulses (" in text) is drawn
    assert (tmp_path / "out.queue").read_text().count("queue_step") > 0
