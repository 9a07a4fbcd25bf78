"""Nominal (-O0) trajectories: constant-velocity phases with length / feed times."""

from __future__ import annotations

import math
import random
from collections.abc import Sequence

import numpy as np
import pytest

from cncc.backends import nominal
from cncc.backends.nominal import nominal_timing, nominal_trajectory
from cncc.ir import IDENTITY_FRAME, Arc, Command, Dwell, Linear, Plane, Rapid
from cncc.ir.machine import Axis, MachineModel, RapidMode
from cncc.ir.trajectory import Limit
from cncc.source import Span

SP = Span(0, 0, 1)


def v6(x: float = 0.0, y: float = 0.0, z: float = 0.0) -> tuple[float, float, float, float, float, float]:
    return (x, y, z, 0.0, 0.0, 0.0)


def machine(mode: RapidMode = RapidMode.INTERPOLATED) -> MachineModel:
    return MachineModel("m", (Axis("X", rapid_mm_min=6000.0), Axis("Y", rapid_mm_min=3000.0),
                              Axis("Z", rapid_mm_min=3000.0)), rapid_mode=mode)


def test_line_takes_length_over_feed() -> None:
    cmds = [Linear(SP, IDENTITY_FRAME, v6(), v6(30.0, 40.0), 600.0)]  # 50 mm at 10 mm/s
    t = nominal_trajectory(cmds, machine())
    assert t.phase_count == 1
    assert math.isclose(t.duration_total_s, 5.0)
    assert np.allclose(t.v0_mm_s[0, :2], [6.0, 8.0])
    assert t.limit[0] == Limit.FEED


def test_quarter_arc_time_and_end_point() -> None:
    # G02 from (10,0) to (0,-10) about the origin: a clockwise quarter of r = 10
    arc = Arc(SP, IDENTITY_FRAME, v6(10.0), v6(0.0, -10.0), v6(), -1, Plane.XY, 600.0)
    t = nominal_trajectory([arc], machine())
    assert math.isclose(t.duration_total_s, (math.pi * 10 / 2) / 10.0)
    assert t.phase_count == 9  # 90 degrees in chords of at most 10 degrees
    end, _, _ = t.end_state(t.phase_count - 1)
    assert np.allclose(end[:2], [0.0, -10.0])
    mid, _, _ = t.end_state(3)  # after 4 of 9 chords: 40 degrees clockwise from +X
    assert np.allclose(mid[:2], [10 * math.cos(math.radians(-40)), 10 * math.sin(math.radians(-40))])


def test_interpolated_rapid_is_one_straight_phase() -> None:
    cmds = [Rapid(SP, IDENTITY_FRAME, v6(), v6(10.0, 10.0))]
    t = nominal_trajectory(cmds, machine())
    assert t.phase_count == 1
    assert math.isclose(t.duration_total_s, 10 / 50.0)  # Y at 50 mm/s is the slowest axis


def test_independent_rapid_is_a_dog_leg() -> None:
    cmds = [Rapid(SP, IDENTITY_FRAME, v6(), v6(10.0, 10.0))]
    t = nominal_trajectory(cmds, machine(RapidMode.INDEPENDENT))
    assert t.phase_count == 2
    assert np.allclose(t.duration_s, [0.1, 0.1])  # X arrives after 10/100 s, Y after 10/50 s
    assert np.allclose(t.p0_mm[1, :2], [10.0, 5.0])
    assert np.allclose(t.v0_mm_s[1, :2], [0.0, 50.0])


def test_phases_are_contiguous_and_match_the_plain_sums() -> None:
    cmds = [Rapid(SP, IDENTITY_FRAME, v6(), v6(0, 0, 5.0)),
            Linear(SP, IDENTITY_FRAME, v6(0, 0, 5.0), v6(20.0, 0, 5.0), 1200.0),
            Dwell(SP, IDENTITY_FRAME, 1.5),
            Arc(SP, IDENTITY_FRAME, v6(20.0, 0, 5.0), v6(20.0, 0, 5.0), v6(30.0, 0, 5.0), 1, Plane.XY, 600.0)]
    t = nominal_trajectory(cmds, machine(RapidMode.INDEPENDENT))
    for k in range(t.phase_count - 1):
        p, _, _ = t.end_state(k)
        assert np.allclose(p, t.p0_mm[k + 1])
        assert math.isclose(t.t0_s[k] + t.duration_s[k], t.t0_s[k + 1])
    motion_s = nominal_timing(cmds, machine()).total_s - 1.5
    assert math.isclose(t.duration_total_s, motion_s)
    assert set(t.cmd_index.tolist()) == {0, 1, 3}  # the dwell is an event, not a phase


def _scalar_nominal(cmds: list[Command], m: MachineModel) -> tuple[list[float], list[list[float]], list[list[float]],
                                                                  list[int]]:
    """The per-chord reference (the scalar formula the report used before the numpy chords):
    (durations, start points, velocities, command indices) of every phase."""
    from cncc.backends.nominal import arc_chords, arc_length_mm, arc_sweep_rad, feed_time_s, linear_time_s

    dur: list[float] = []
    p0: list[list[float]] = []
    vel: list[list[float]] = []
    idx: list[int] = []

    def add(d: float, a: Sequence[float], b: Sequence[float], i: int) -> None:
        if d > 0.0:
            dur.append(d)
            p0.append(list(a))
            vel.append([(y - x) / d for x, y in zip(a, b, strict=True)])
            idx.append(i)

    for i, c in enumerate(cmds):
        if isinstance(c, Linear):
            add(linear_time_s(c), c.start, c.end, i)
        elif isinstance(c, Arc):
            total = feed_time_s(arc_length_mm(c), c.feed_mm_min)
            sweep = arc_sweep_rad(c)
            n = arc_chords(sweep)
            pi, pj = c.plane.first, c.plane.second
            r0 = math.hypot(c.start[pi] - c.center[pi], c.start[pj] - c.center[pj])
            r1 = math.hypot(c.end[pi] - c.center[pi], c.end[pj] - c.center[pj])
            a0 = math.atan2(c.start[pj] - c.center[pj], c.start[pi] - c.center[pi])
            prev: Sequence[float] = c.start
            for k in range(1, n + 1):
                u = k / n
                if k == n:
                    nxt: Sequence[float] = c.end
                else:
                    r, a = r0 + (r1 - r0) * u, a0 + sweep * u
                    q = [s + (e - s) * u for s, e in zip(c.start, c.end, strict=True)]
                    q[pi] = c.center[pi] + r * math.cos(a)
                    q[pj] = c.center[pj] + r * math.sin(a)
                    nxt = q
                add(total / n, prev, nxt, i)
                prev = nxt
    return dur, p0, vel, idx


@pytest.mark.parametrize("per_chunk", [4096, 7, 1])
def test_numpy_chords_are_the_scalar_chords_bit_for_bit(per_chunk: int, monkeypatch: pytest.MonkeyPatch) -> None:
    """Arcs in all three planes, helices of several turns, both directions, radius changes
    (an end off the start's circle), zero-feed arcs, between lines: the phases are exactly
    the per-chord formula's, in command order."""
    monkeypatch.setattr(nominal, "ARCS_PER_CHUNK", per_chunk)  # chunks of arcs, cut anywhere
    rng = random.Random(14)
    cmds: list[Command] = []
    p = [0.0, 0.0, 0.0]
    for _ in range(300):
        q = [p[0] + rng.uniform(-5, 5), p[1] + rng.uniform(-5, 5), p[2] + rng.uniform(-1, 1)]
        if rng.random() < 0.3:
            cmds.append(Linear(SP, IDENTITY_FRAME, v6(*p), v6(*q), rng.choice([0.0, 600.0, 1500.0])))
        else:
            plane = rng.choice([Plane.XY, Plane.ZX, Plane.YZ])
            cen = [p[0] + rng.uniform(-3, 3), p[1] + rng.uniform(-3, 3), p[2] + rng.uniform(-3, 3)]
            turns = rng.choice([1, 2, 5, -1, -3])
            cmds.append(Arc(SP, IDENTITY_FRAME, v6(*p), v6(*q), v6(*cen), turns, plane,
                            rng.choice([0.0, 800.0, 2000.0])))
        p = q
    t = nominal_trajectory(cmds, machine())
    dur, p0, vel, idx = _scalar_nominal(cmds, machine())
    assert t.duration_s.tolist() == dur
    assert t.cmd_index.tolist() == idx
    assert t.p0_mm[:, :3].tolist() == [row[:3] for row in p0]
    assert t.v0_mm_s[:, :3].tolist() == [row[:3] for row in vel]
    assert t.p0_mm.tolist() == p0 and t.v0_mm_s.tolist() == vel
