"""The planner caps every axis by what its step output can emit (issue 26): syntec-900m rapids."""

from __future__ import annotations

from pathlib import Path

import pytest

from cncc.cli import main
from cncc.machines import load_machine
from cncc.passes.planning.limits import axis_limits

# syntec-900m: G00 600 mm/s per axis (36000 mm/min), 1000 steps/mm, 1 MHz, pulses 2 us high
PROGRAM = "G21 G90 G17\nG0 X0 Y0 Z0\nG0 X-300 Y0\nG0 X-300 Y-200 Z-50\nG1 X-310 F600\nG0 X0 Y0 Z0\nM30\n"


def test_axis_rate_is_capped_by_the_minimum_pulse_spacing() -> None:
    machine = load_machine("syntec-900m")
    x = machine.axis("X")
    assert x is not None
    spacing_s = 2 * x.step.pulse_width_ns * 1e-9  # high time plus as long low
    assert 1 / spacing_s < x.step.max_step_rate_hz  # the spacing is the binding limit here
    limits = axis_limits(machine)
    assert limits.rapid_mm_s[0] * x.step.steps_per_mm <= 1 / spacing_s
    assert limits.rapid_mm_s[0] * x.step.steps_per_mm >= 0.999 / spacing_s


def test_syntec_rapids_emit_pulses_without_spacing_errors(tmp_path: Path, capsys: pytest.CaptureFixture[str]
                                                          ) -> None:
    src = tmp_path / "rapids.nc"
    src.write_text(PROGRAM, encoding="ascii")
    rc = main([str(src), "-m", "syntec-900m", "--emit=pulses", "-o", str(tmp_path / "out.vcd")])
    err = capsys.readouterr().err
    assert "E0702" not in err and "E0701" not in err
    assert rc == 0
