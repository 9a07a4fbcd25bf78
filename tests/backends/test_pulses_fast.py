"""Differential test of the vectorised step-time path (issue 14): on planned trajectories with
lines, blend arcs, arcs, helices and random walks, and on hand-built S-curves, every step of
every axis is the one the previous exact algorithm (frozen in ``pulses_reference.py``) finds,
to the integer-nanosecond rounding."""

from __future__ import annotations

import math
import random

import numpy as np
import pytest

from cncc.api import compile_commands
from cncc.backends.pulses import solve
from cncc.diagnostics import DiagnosticSink
from cncc.ir.trajectory import Trajectory
from cncc.machines import load_machine
from cncc.passes.plan import plan_commands
from tests.backends import pulses_reference as ref
from tests.backends.pulse_trajectories import s_curve
from tests.backends.pulses_pairs import assert_same_ns, axis_pairs

HEAD = "G21 G90 G17 G94\nG0 X10 Y10 Z0\n"


def _raster(n: int) -> str:
    rows = [f"G1 X{10 + 0.2 * (c if r % 2 == 0 else 39 - c):.4f} Y{10 + 0.5 * r:.4f} "
            f"Z{-1 + math.sin(c / 7) * math.cos(r / 3):.4f} F3000" for r in range(n // 40) for c in range(40)]
    return HEAD + "\n".join(rows) + "\nM30\n"


def _arcs_and_helices() -> str:
    return HEAD + """G1 X20 F2000
G3 X30 Y20 I0 J10
G2 X40 Y30 I10 J0 Z-2
G3 X40 Y30 I-3 J0 Z-3
G18 G2 X50 Z-3 I5 K0
G19 G3 Y40 Z-3 J5 K0
G17 G1 X45 Y35
G2 X45 Y35 I2.5 J0 Z-5 F900
M30
"""


def _random_walk(n: int, seed: int) -> str:
    rnd = random.Random(seed)
    x, y, out = 50.0, 50.0, []
    for _ in range(n):
        a = rnd.uniform(0, 2 * math.pi)
        x, y = x + math.cos(a), y + math.sin(a)
        out.append(f"G1 X{x:.4f} Y{y:.4f} F{rnd.choice([600, 2000, 6000])}")
    return HEAD + "\n".join(out) + "\nM30\n"


def _planned(text: str, level: int) -> Trajectory:
    cmds, _ = compile_commands(text, emit="timing")
    return plan_commands(cmds, load_machine("generic-mill"), level=level, sink=DiagnosticSink())


def _compare(traj: Trajectory, budget: int) -> int:
    """Assert the fast path equals the reference on every window and axis; the steps compared."""
    compared = 0
    for name, _, _, new, old in axis_pairs(traj, budget):
        # the times agree far below the ns rounding
        assert np.abs(new.t_s - old.t_s).max(initial=0.0) < 1e-11, name
        assert_same_ns(new.t_s, old.t_s, name)
        compared += int(new.t_s.size)
    return compared


@pytest.mark.parametrize(("name", "text", "level"), [
    ("raster", _raster(400), 2),
    ("arcs and helices", _arcs_and_helices(), 2),
    ("arcs and helices -O1", _arcs_and_helices(), 1),
    ("random walk", _random_walk(150, 5), 2),
])
def test_fast_path_equals_the_previous_exact_algorithm(name: str, text: str, level: int) -> None:
    traj = _planned(text, level)
    if level == 2 and name.startswith("arcs"):
        assert traj.curved.sum() >= 5  # arcs and helices are curved phases at -O2 (chords at -O1)
    assert _compare(traj, 1 << 14) > 10_000, name


def test_fast_path_equals_the_previous_exact_algorithm_on_straight_s_curves() -> None:
    traj = s_curve(100.0, 1000.0, 20000.0, 0.05, sign=-1.0)
    assert _compare(traj, 4096) > 1000


def _trains(seed: int) -> list[np.ndarray]:
    """Step-time trains of every shape the compressor meets: random gaps, accelerating and
    decelerating runs (intervals shrinking to a few ns, where the last-interval >= 1 rule of a
    negative ``add`` binds), constant rate with jitter, a sine-modulated rate."""
    rng = np.random.default_rng(seed)
    out = []
    for r in range(24):
        n = int(rng.integers(2, 2500))
        k = np.arange(n)
        kind = r % 4
        if kind == 0:
            gaps = rng.integers(1, 200_000, n)
        elif kind == 1:
            gaps = np.maximum(int(rng.integers(2_000, 60_000)) - int(rng.integers(1, 40)) * k, 1)
        elif kind == 2:
            gaps = np.full(n, int(rng.integers(3, 30_000))) + rng.integers(0, 7, n)
        else:
            gaps = np.maximum((20_000 + 15_000 * np.sin(k / 40)).astype(np.int64), 1)
        out.append(np.cumsum(gaps).astype(np.int64) + int(rng.integers(1, 500)))
    return out


@pytest.mark.parametrize("e", [1, 1000, 25_000])
def test_queue_compressor_equals_the_previous_one(e: int) -> None:
    from cncc.backends.pulses.queue import compress_run

    for seed in range(3):
        for r, t in enumerate(_trains(seed)):
            final = r % 3 != 0
            last = int(t[0]) - 1 - r
            assert compress_run(t, last, e, final) == ref.compress_run(t, last, e, final), (seed, r)


def test_blocks_of_phases_give_the_whole_trajectory_result(monkeypatch: pytest.MonkeyPatch) -> None:
    from cncc.backends.pulses.blocks import blockwise
    from cncc.ir.trajectory import axis_bounds, position_bounds

    traj = _planned(_arcs_and_helices(), 2)
    assert traj.phase_count > 50
    for fn in (position_bounds, axis_bounds):
        for whole, blocked in zip(fn(traj), blockwise(fn, traj, size=7), strict=True):
            np.testing.assert_array_equal(whole, blocked)
    monkeypatch.setattr(solve, "BLOCK_PHASES", 7)  # segment() a few phases at a time
    assert _compare(traj, 1 << 12) > 10_000
