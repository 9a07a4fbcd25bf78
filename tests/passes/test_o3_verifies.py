"""-O3 never returns a plan that verify refuses (issue 26): its chord optimisation is kept only
when it passes every check -- strict velocity continuity included -- and is faster than -O2."""

from __future__ import annotations

from cncc.api import compile_commands
from cncc.diagnostics import DiagnosticSink
from cncc.machines import effective_corner_rule, load_machine
from cncc.passes.plan import plan_commands
from cncc.passes.verify import verify_trajectory

# non-tangent arcs joined by short lines: chords of -O3 would step the velocity at every vertex
PROGRAM = """G21 G90 G17 G94
G0 X0 Y0 Z1
G1 Z-1 F600
G1 X10 F1500
G2 X20 Y0 I5 J0
G3 X30 Y5 I5 J2.5
G1 X32 Y-3
G2 X40 Y-3 I4 J0
G1 X40 Y10
G3 X20 Y10 I-10 J0
G0 Z5
M30
"""


def test_o3_plan_passes_verify_and_is_not_slower_than_o2() -> None:
    cmds, _ = compile_commands(PROGRAM, emit="timing")
    machine = load_machine("generic-mill")
    sink = DiagnosticSink()
    o3 = plan_commands(cmds, machine, 3, sink)
    o2 = plan_commands(cmds, machine, 2, DiagnosticSink())
    report = verify_trajectory(o3, cmds, machine, sink, corner_rule=effective_corner_rule(machine, 3),
                               check_dynamics=True, jerk_limited=True, check_soft_limits=False)
    assert report.count == 0, [d.message for d in sink]
    assert o3.duration_total_s <= o2.duration_total_s * (1 + 1e-9)
