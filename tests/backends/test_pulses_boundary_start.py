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


@pytest.mark.parametrize("level", [1, 2])
@pytest.mark.parametrize("start", [(-40.0, 30.5, 5.0), (-40.5, 30.0, 5.0), (3.5, -7.1, 5.0)])
def test_steps_sit_on_their_boundaries(coarse_machine: Path, level: int, start: tuple[float, float, float]) -> None:
    common = {"dialect": "syntec", "machine": str(coarse_machine), "start_machine_mm": start, "opt_level": level}
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        pulses = compile_text(PROGRAM, emit="pulses", pulse_format="csv", **common)
    assert pulses.ok, [(d.code, d.message) for d in pulses.sink.items]
    assert not [d.code for d in pulses.sink.items if d.code.startswith("E")]
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
