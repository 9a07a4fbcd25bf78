"""Step times on arcs and helices planned on their exact geometry (issue 14): every step
lies on its step boundary of the true circle, and the counts at phase ends are exact."""

from __future__ import annotations

import numpy as np

from cncc.api import compile_commands
from cncc.backends.pulses.generate import generate_pulses
from cncc.diagnostics import DiagnosticSink
from cncc.machines import load_machine
from cncc.passes.plan import plan_commands

PROGRAM = """G21 G90 G17 G94
G0 X0.0 Y0.0 Z0.0
G1 X10.0 F3000
G3 X20.0 Y10.0 I0.0 J10.0
G2 X30.0 Y20.0 I10.0 J0.0 Z-2.0
G3 X30.0 Y20.0 I-3.0 J0.0 Z-3.0
M30
"""


def test_arc_steps_sit_on_the_step_boundaries_of_the_circle() -> None:
    cmds, _ = compile_commands(PROGRAM, emit="timing")
    machine = load_machine("generic-mill")
    traj = plan_commands(cmds, machine, level=2, sink=DiagnosticSink())
    assert traj.curved.sum() >= 3  # the arcs are curved phases, not chords
    sink = DiagnosticSink()
    chunks = list(generate_pulses(traj, machine, sink=sink))
    assert not sink.has_errors
    layout = chunks[0].layout
    for i, spec in enumerate(layout.specs):
        col = traj.axes.index(spec.name)
        t_ns = np.concatenate([c.axes[i].t_ns for c in chunks])
        direction = np.concatenate([c.axes[i].direction for c in chunks]).astype(np.int64)
        if t_ns.size == 0:
            continue
        h = spec.steps_den / spec.steps_num  # mm per step; boundaries at (n + 1/2) h (spec.py)
        x = traj.sample(t_ns * 1e-9)[0][:, col]  # the exact position at each step time
        off = x / h - 0.5
        # within the ns rounding: |v| * 1 ns, far below a hundredth of a step
        assert np.abs(off - np.round(off)).max() < 1e-3, spec.name
        # the count telescopes to the commanded end position
        start = int(spec.motor_steps(traj.p0_mm[:1, col])[0])
        end = traj.end_states()[0][-1:, col]
        assert start + int(direction.sum()) == int(spec.motor_steps(end)[0]), spec.name
    assert sum(int(c.step_count) for c in chunks) > 0
