"""Memory of the -O2 checks on long arc programs (issue 14): bounded working sets, seen through
hooks (the size of every query), not through timings or RSS."""

from __future__ import annotations

import numpy as np
import pytest

from cncc.diagnostics import DiagnosticSink
from cncc.ir import IDENTITY_FRAME, Arc, Command, Plane
from cncc.ir.trajectory import Trajectory
from cncc.machines import effective_corner_rule, load_machine
from cncc.passes import verify_physics as vp
from cncc.passes.plan import plan_commands
from cncc.passes.verify import verify_trajectory
from cncc.source import Span

SP = Span(0, 0, 1)


def _s_bends(n: int) -> list[Command]:
    """``n`` half circles of radius 1 mm, alternating direction (an S-bend chain, tangent joints)."""
    out: list[Command] = []
    for k in range(n):
        x = 2.0 * k
        out.append(Arc(SP, IDENTITY_FRAME, (x, 0.0, -1.0, 0.0, 0.0, 0.0), (x + 2.0, 0.0, -1.0, 0.0, 0.0, 0.0),
                       (x + 1.0, 0.0, -1.0, 0.0, 0.0, 0.0), -1 if k % 2 == 0 else 1, Plane.XY, 3000.0))
    return out


def test_strict_verify_samples_the_curved_phases_in_bounded_chunks(monkeypatch: pytest.MonkeyPatch) -> None:
    """The dense sampling of verify's strict checks queries at most 1,024 phases x 17 instants
    at once, whatever the program's length (it queried 8,192 phases at once: ~150 MB of
    transient states at 10k arcs); the extremes are those of one whole query."""
    machine = load_machine("generic-mill")
    cmds = _s_bends(1500)
    traj = plan_commands(cmds, machine, 2, DiagnosticSink())
    curved = np.flatnonzero(traj.curved)
    assert curved.size > 2 * 1024  # more curved phases than one chunk holds

    sizes: list[int] = []
    original = Trajectory.sample

    def spy(self: Trajectory, t_s: np.ndarray) -> tuple[np.ndarray, ...]:
        sizes.append(int(np.shape(t_s)[0]))
        return original(self, t_s)

    monkeypatch.setattr(Trajectory, "sample", spy)
    verify_trajectory(traj, cmds, machine, DiagnosticSink(), corner_rule=effective_corner_rule(machine, 2),
                      check_dynamics=True, jerk_limited=True, strict_continuity=True)
    assert sizes and max(sizes) <= 1024 * 17
    chunked = vp.dense_extremes(traj, phases=curved)
    monkeypatch.setattr(Trajectory, "sample", original)
    whole = vp.dense_extremes(traj, phases=curved, chunk_phases=curved.size)
    for c, w in zip(chunked, whole, strict=True):
        assert np.array_equal(c, w)
