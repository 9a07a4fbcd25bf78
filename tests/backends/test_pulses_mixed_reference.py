"""The fast exact step path against the frozen previous algorithm (``pulses_reference.py``) on
generated programs that mix lines, arcs and helices in the three planes, dwells and exact
stops (G61.1, G61, G64 P), each started from several positions (on a half-step boundary or
not) and planned at -O1 and -O2: the same steps, directions, phases and runs, times within
10 ps -- except the reference's known 0/0 at a move from rest that starts on a boundary (see
``_compare``); and the whole stream (``generate_pulses``, with the dwells' pauses) has every
axis at ``N(p)`` of each phase's end."""

from __future__ import annotations

import math
import random

import numpy as np
import pytest

from cncc.api import compile_commands
from cncc.backends.pulses import generate_pulses
from cncc.backends.timing import event_pauses
from cncc.diagnostics import DiagnosticSink
from cncc.ir.trajectory import Trajectory
from cncc.machines import load_machine
from cncc.passes.plan import plan_commands
from tests.backends.pulses_pairs import assert_same_ns, axis_pairs

# inside generic-mill's soft limits (X, Y from -1, Z to +1); 1/1600 mm is a half step
STARTS = [(50.0, 50.0, -50.0), (60.000625, 33.3, -41.7), (120.5, 75.25, -80.000625)]


def _compare(traj: Trajectory, budget: int) -> tuple[int, int]:
    """(steps compared, steps where the reference is known wrong): as ``_compare`` of
    ``test_pulses_fast.py``, except at a move from rest that starts on a step boundary, where the
    frozen reference's 0/0 put the step at the end of the piece (fixed in 91366be): there the new
    step must be at the start of its phase, the position there on the half step."""
    compared = known = 0
    for name, i, rate, new, old in axis_pairs(traj, budget):
        off = np.flatnonzero(np.abs(new.t_s - old.t_s) >= 1e-11)
        for k in off.tolist():
            ph = int(new.phase[k])
            assert abs(new.t_s[k] - traj.t0_s[ph]) < 1e-12, (name, k)  # at the start of its phase
            assert not np.any(traj.v0_mm_s[ph]), (name, k)  # a move from rest
            y = rate * traj.p0_mm[ph, i] - 0.5
            assert abs(y - round(y)) < 1e-6, (name, k)  # standing on a step boundary
        same = np.setdiff1d(np.arange(new.t_s.size), off)
        assert_same_ns(new.t_s[same], old.t_s[same], name)
        compared += int(new.t_s.size)
        known += int(off.size)
    return compared, known


def _mixed(seed: int, start: tuple[float, float, float], n: int = 40) -> str:
    """Lines, semicircle arcs and helices (G17/G18/G19), dwells and path-mode changes."""
    rnd = random.Random(seed)
    x, y, z = start
    out = ["G21 G90 G94 G17", f"G0 X{x:.6f} Y{y:.6f} Z{z:.6f}"]
    for _ in range(n):
        kind = rnd.random()
        f = rnd.choice([300, 1200, 3000, 6000])
        if kind < 0.35:
            a = rnd.uniform(0, 2 * math.pi)
            d = rnd.uniform(0.05, 4.0)
            x, y = x + d * math.cos(a), y + d * math.sin(a)
            z += rnd.choice([0.0, 0.0, rnd.uniform(-0.5, 0.5)])
            out.append(f"G1 X{x:.4f} Y{y:.4f} Z{z:.4f} F{f}")
        elif kind < 0.65:
            plane = rnd.choice(["G17", "G18", "G19"])
            r = rnd.uniform(0.3, 3.0)
            a = rnd.uniform(0, 2 * math.pi)
            ci, cj = r * math.cos(a), r * math.sin(a)
            g = rnd.choice(["G2", "G3"])
            lift = rnd.choice([0.0, rnd.uniform(-1.0, 1.0)])  # a helix when not 0
            if plane == "G17":
                x, y, z = x + 2 * ci, y + 2 * cj, z + lift
                out.append(f"G17 {g} X{x:.4f} Y{y:.4f} Z{z:.4f} I{ci:.4f} J{cj:.4f} F{f}")
            elif plane == "G18":
                x, z, y = x + 2 * ci, z + 2 * cj, y + lift
                out.append(f"G18 {g} X{x:.4f} Z{z:.4f} Y{y:.4f} I{ci:.4f} K{cj:.4f} F{f}")
            else:
                y, z, x = y + 2 * ci, z + 2 * cj, x + lift
                out.append(f"G19 {g} Y{y:.4f} Z{z:.4f} X{x:.4f} J{ci:.4f} K{cj:.4f} F{f}")
        elif kind < 0.75:
            out.append(f"G4 P{rnd.choice([0.1, 0.25])}")
        elif kind < 0.85:
            out.append(rnd.choice(["G61.1", "G61", "G64 P0.01", "G64"]))
        else:  # a short move that ends on a half step of X
            x = round(x * 800) / 800 + 1 / 1600
            out.append(f"G1 X{x:.6f} F{f}")
    out += ["G17 G64", "M30"]
    return "\n".join(out) + "\n"


@pytest.mark.parametrize("level", [1, 2])
@pytest.mark.parametrize("start", STARTS)
def test_mixed_programs_equal_the_reference_from_several_starts(start: tuple[float, float, float],
                                                                 level: int) -> None:
    machine = load_machine("generic-mill")
    steps = known = 0
    for seed in (1, 2):
        cmds, _ = compile_commands(_mixed(seed, start), emit="timing")
        sink = DiagnosticSink()
        traj = plan_commands(cmds, machine, level=level, sink=sink)
        assert (traj.duration_s > 0).any()
        n, k = _compare(traj, 1 << 12)
        steps, known = steps + n, known + k
        # the stream with the dwells' pauses: at the end of every phase each axis has made
        # N(p_end) - N(p_start) net steps (positions within 1e-6 step of a boundary skipped)
        chunks = list(generate_pulses(traj, machine, sink=sink, pauses=event_pauses(cmds, traj.cmd_index, machine)))
        assert not sink.has_errors, [f"{d.code} {d.message}" for d in sink][:3]
        ends = traj.end_positions()
        for i, name in enumerate(chunks[0].layout.axes):
            col = traj.axes.index(name)
            r = 800.0  # generic-mill: 800 steps/mm, gear 1:1, no pitch table
            phase = np.concatenate([c.axes[i].phase for c in chunks])
            net = np.zeros(traj.phase_count, np.int64)
            np.add.at(net, phase, np.concatenate([c.axes[i].direction for c in chunks]).astype(np.int64))
            y = r * ends[:, col] + 0.5
            clear = np.abs(y - np.rint(y)) > 1e-6
            want = np.floor(y).astype(np.int64) - math.floor(r * traj.p0_mm[0, col] + 0.5)
            np.testing.assert_array_equal(np.cumsum(net)[clear], want[clear], err_msg=name)
            assert clear.sum() > traj.phase_count // 2
    assert steps > 5_000 and known <= 2 * 2 * 3  # a few half-step starts per program, no more
