"""A start position exactly on a step boundary: the first step is at once, not lost and bunched later.

At 5 steps/mm the position 30.5 mm is the boundary between motor counts 152 and 153
(``N(p) = floor(5 p + 1/2)``).  Moving down from it crosses that boundary at t = 0; the
constant-acceleration root ``d / (v/2 + sqrt(v^2/4 + a d/2))`` is 0/0 there when the move
starts from rest.  The check is independent of the pulse generator: every step of an axis
must sit where the sampled trajectory crosses that step's boundary.
"""

from __future__ import annotations

import re
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from cncc.api import compile_text

MACHINES = Path(__file__).resolve().parents[2] / "cncc" / "machines"
STEPS_PER_MM = 5.0
PROGRAM = "G71 G90 G94 G17\nG00 X0. Y0.\nM30\n"


@pytest.fixture(scope="module")
def coarse_machine(tmp_path_factory: pytest.TempPathFactory) -> Path:
    text = (MACHINES / "generic-mill.toml").read_text()
    text = re.sub(r"steps_per_mm = [0-9.]+", f"steps_per_mm = {STEPS_PER_MM}", text)
    text = re.sub(r"soft_min_mm = [-0-9.]+", "soft_min_mm = -1000.0", text)
    text = re.sub(r"soft_max_mm = [-0-9.]+", "soft_max_mm = 1000.0", text)
    path = tmp_path_factory.mktemp("machine") / "coarse.toml"
    path.write_text(text)
    return path


def _clean_pulses(program: str, common: dict[str, Any]) -> Any:
    """The CSV pulses of ``program``, asserted free of errors and of numpy RuntimeWarnings (NaN, 0 * inf)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        pulses = compile_text(program, emit="pulses", pulse_format="csv", **common)
    assert pulses.ok, [(d.code, d.message) for d in pulses.sink.items]
    assert not [d.code for d in pulses.sink.items if d.code.startswith("E")]
    return pulses


@pytest.mark.parametrize("level", [1, 2])
@pytest.mark.parametrize("start", [(-40.0, 30.5, 5.0), (-40.5, 30.0, 5.0), (3.5, -7.1, 5.0)])
def test_steps_sit_on_their_boundaries(coarse_machine: Path, level: int, start: tuple[float, float, float]) -> None:
    common = {"dialect": "syntec", "machine": str(coarse_machine), "start_machine_mm": start, "opt_level": level}
    pulses = _clean_pulses(PROGRAM, common)
    timing = compile_text(PROGRAM, emit="timing", keep_trajectory=True, **common)
    traj = timing.runs[0].trajectory
    assert traj is not None
    rows = [line.split(",") for line in pulses.output.splitlines()[1:]]
    for col, name in enumerate("XY"):
        steps = np.array([int(r[0]) for r in rows if r[1] == name and r[2] == "step"], dtype=np.int64)
        n0 = int(np.floor(start[col] * STEPS_PER_MM + 0.5))
        n1 = 0  # the program ends at X0 Y0 (no work offset on generic-mill)
        assert steps.size == abs(n1 - n0)
        assert np.all(np.diff(steps) > 1000)  # no bunching: at most 250 mm/s, a step per 800 us
        direction = -1 if n1 < n0 else 1
        boundary = (n0 + direction * np.arange(1, steps.size + 1) - 0.5 * direction) / STEPS_PER_MM
        at = traj.sample(steps * 1e-9)[0][:, col]
        # ns rounding and the direction set-up delay (5 us) at most 250 mm/s: within 2 um
        assert np.max(np.abs(at - boundary)) < 2e-3


# Found by tests/pipeline/test_unmoved_axes.py: the G01 of the subprogram ends Z on -2.5 mm
# (a half step at 5 steps/mm); the rapid after it holds Z, but the phases join 1 ulp apart
# there, so the still phase counted a step that no time solves (0 * inf: E0701 at 1 GHz).
STILL_ON_BOUNDARY = """G71 G90 G94 G19 G40 G49 G80
G00 Y0. Z0.
M98 H100
G00 Y0.
G91 G03 Y4. Z-8. R4.972 F300.
G90
G00 Y0.
M30
N100
G91 G01 Y-8. Z-2.5 F600.
G90
M99
"""


@pytest.mark.parametrize("level", [1, 2])
@pytest.mark.parametrize("start", [None, (13.0, -7.0, 25.0), (-40.0, 30.5, 5.0)])
def test_a_still_phase_on_a_boundary_makes_no_step(coarse_machine: Path, level: int,
                                                   start: tuple[float, float, float] | None) -> None:
    common = {"dialect": "syntec", "machine": str(coarse_machine), "start_machine_mm": start, "opt_level": level}
    pulses = _clean_pulses(STILL_ON_BOUNDARY, common)
    rows = [line.split(",") for line in pulses.output.splitlines()[1:]]
    steps = np.array([int(r[0]) for r in rows if r[1] == "Z" and r[2] == "step"], dtype=np.int64)
    assert np.all(np.diff(steps) > 1000)  # Z never exceeds ~250 mm/s here: one step per 800 us at most
    # independent count: Z's boundary crossings on the planned trajectory, sampled every 10 us
    # (positions rounded to 1 nm first, so the 1-ulp joins themselves do not count)
    timing = compile_text(STILL_ON_BOUNDARY, emit="timing", keep_trajectory=True, **common)
    crossings = 0
    for run in timing.runs:
        if run.label.startswith("nominal"):
            continue  # the report's -O0 column, not the plan the pulses follow
        traj = run.trajectory
        assert traj is not None
        t = np.linspace(0.0, traj.duration_total_s, int(traj.duration_total_s / 1e-5) + 2)
        z = np.round(traj.sample(t)[0][:, list(traj.axes).index("Z")], 9)
        crossings += int(np.abs(np.diff(np.floor(z * STEPS_PER_MM + 0.5))).sum())
    assert crossings > 50
    assert steps.size == crossings
