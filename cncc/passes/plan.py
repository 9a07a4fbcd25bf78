"""The ``plan`` pass: time parameterisation under the machine's limits -> Trajectory.

API (for the driver and the backends)::

    from cncc.passes.plan import plan_commands
    traj = plan_commands(cmds, machine, level=2, sink=sink)   # cncc.ir.trajectory.Trajectory

``cmds`` is a sequence of IR commands in machine coordinates (after ``frames`` and,
normally, ``blend``); ``Trajectory.cmd_index`` refers to positions in ``cmds``.
``level`` is the ``-O`` level:

* ``0`` nominal: every segment at its speed cap, no acceleration (what CAM systems
  estimate); velocity steps everywhere, so verify it with ``check_dynamics=False``.
* ``1`` controller emulation: trapezoids with grbl/Klipper junction deviation, or the
  SZGH-990MDb rules (speed step per axis, take-off speed, reversal speed, every G00 a
  stop, dog-leg rapids) on machines whose ``corner_rule`` is ``speed-step``.
* ``2`` (default) jerk-limited, near time-optimal: corners rounded within the blend
  tolerance, TOPP (acceleration-limited optimum) on widened caps, then a moving-average
  jerk filter on the path coordinate (``planning/fir.py``), each segment's piece then
  re-timed by ruckig between the vertex states (``planning/windows.py``); single moves
  and dog-leg rapids use ruckig's time-optimal 7-phase profile.
* ``3`` like 2, then each run re-optimised with CasADi/IPOPT over windows
  (``planning/optimal.py``): for studies and for judging ``-O2``.

Stops: a run between two stops starts and ends at rest.  A non-motion command that
forces a stop (dwell, tool change, spindle, stop, wait; M/S/T on SZGH — see
:func:`cncc.passes.blend.forces_stop`) adds **no phase**: the trajectory simply has
``v = 0`` at the boundary between the phases of the motions before and after it, and
the timing backend adds the command's own time there.  Positions are continuous
between runs as long as each motion starts where the previous one ended.

Corner rule of a plan: :func:`cncc.machines.effective_corner_rule` ``(machine,
level)``; pass it to ``verify`` so that -O1's junction-deviation corners are judged by
the rule they follow.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Sequence
from contextlib import AbstractContextManager
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, ClassVar

from cncc.diagnostics import DiagnosticSink
from cncc.ir.commands import Command
from cncc.ir.machine import CornerRule, MachineModel
from cncc.passes import Pass, PassContext, register

if TYPE_CHECKING:
    from cncc.ir.trajectory import Trajectory
    from cncc.passes.planning.emit import Rows
    from cncc.passes.planning.limits import AxisLimits
    from cncc.passes.planning.profile import Phases
    from cncc.passes.planning.segments import Segments


O2_PROFILE = "scurve"
"""-O2's path profile: ``"scurve"`` (closed form, ``planning/scurve.py``) or ``"filter"``
(the jerk filter and ruckig re-timing that -O3 starts from; kept for comparisons)."""


def plan_commands(cmds: Sequence[Command], machine: MachineModel, level: int = 2,
                  sink: DiagnosticSink | None = None, progress: Callable[[int], None] | None = None) -> Trajectory:
    """Plan ``cmds`` at ``-O<level>`` (0..3) on ``machine``; see the module docstring.

    ``progress(done)`` is called after each run with the number of commands planned."""

    sink = sink if sink is not None else DiagnosticSink()
    level = max(0, min(3, level))
    if level == 3:  # -O3 optimises the chord structure; it never returns a plan slower than -O2's,
        # nor one that verify would refuse (its chords' velocity steps under strict continuity)
        best = _plan_level(cmds, machine, 3, sink, progress)
        o2 = _plan_level(cmds, machine, 2, DiagnosticSink(), None)
        if o2.duration_total_s < best.duration_total_s or not _verifies(best, cmds, machine):
            return o2
        return best
    return _plan_level(cmds, machine, level, sink, progress)


def _verifies(traj: Trajectory, cmds: Sequence[Command], machine: MachineModel) -> bool:
    """``traj`` passes verify's dynamic checks at -O3 (soft limits aside: they need the work offsets)."""
    from cncc.machines import effective_corner_rule
    from cncc.passes.verify import verify_trajectory

    report = verify_trajectory(traj, cmds, machine, DiagnosticSink(), corner_rule=effective_corner_rule(machine, 3),
                               check_dynamics=True, jerk_limited=True, check_soft_limits=False)
    return report.count == 0


def _plan_level(cmds: Sequence[Command], machine: MachineModel, level: int, sink: DiagnosticSink,
                progress: Callable[[int], None] | None) -> Trajectory:
    from cncc.passes.planning.emit import assemble

    return assemble(list(plan_pieces(cmds, machine, level, sink, progress)))


def plan_pieces(cmds: Sequence[Command], machine: MachineModel, level: int = 2,
                sink: DiagnosticSink | None = None, progress: Callable[[int], None] | None = None
                ) -> Iterator[Rows]:
    """The plan at ``-O<level>`` (0..2) piece by piece: the rows of each run (rest to rest),
    in order, as soon as the run is planned, times local to the run (``Rows.t0`` from 0).

    The streaming interface (``docs/planning.md``, "Streaming and memory"): a consumer that
    handles one piece at a time keeps the planner's memory to the longest run;
    :func:`cncc.passes.planning.emit.assemble` of all pieces is :func:`plan_commands`."""
    from cncc.machines import effective_corner_rule
    from cncc.passes.planning.emit import merge_axes
    from cncc.passes.planning.geometry import IndependentRapid, build_runs
    from cncc.passes.planning.limits import axis_limits
    from cncc.passes.planning.onedim import independent_axes

    sink = sink if sink is not None else DiagnosticSink()
    limits = axis_limits(machine)
    rule = effective_corner_rule(machine, level)
    for run in build_runs(cmds, machine, limits, level, sink):
        if isinstance(run, IndependentRapid):
            take_off = limits.start_mm_s if rule is CornerRule.SPEED_STEP else limits.start_mm_s * 0
            profiles = independent_axes(run.start, run.end, level, limits.rapid_mm_s, limits.amax_mm_s2,
                                        limits.jmax_mm_s3, take_off)
            yield merge_axes(profiles, run.start, run.cmd, _rapid_limit())
            if progress is not None:
                progress(run.cmd + 1)
            continue
        yield from _plan_path(run, machine, limits, level, rule, sink)
        if progress is not None and run.cmd.size:
            progress(int(run.cmd[-1]) + 1)


def _rapid_limit() -> int:
    from cncc.ir.trajectory import Limit

    return int(Limit.RAPID)


def _plan_path(run: object, machine: MachineModel, limits: AxisLimits, level: int, rule: CornerRule,
               sink: DiagnosticSink) -> list[Rows]:
    from cncc.passes.planning.emit import path_rows
    from cncc.passes.planning.geometry import PathRun
    from cncc.passes.planning.segments import make_segments, split_at_stops

    assert isinstance(run, PathRun)
    whole = level == 2 and O2_PROFILE == "scurve"  # the S-curve plans its stops itself: no parts
    if level >= 2 and rule is CornerRule.BLEND and run.cmd.size > 1:  # a single piece has no corner to round
        from cncc.passes.planning.corners import plan_blended

        parts = plan_blended(run, machine, limits, lambda part: _profile(part, machine, limits, level, rule, sink),
                             decide_stops=level >= 3, whole=whole)
        if level >= 3:
            from cncc.passes.planning.optimal import accel_step_caps, optimise

            period_s = machine.interpolation_period_s
            return [_judged_rows(part, ph, optimise(part, ph, sink, vertex_acap=accel_step_caps(
                part, limits.jmax_mm_s3, period_s)), machine, limits, sink) for part, ph in parts]
        return [path_rows(part, ph) for part, ph in parts]
    seg = make_segments(run, limits, machine)
    if seg is None:
        return []
    _corner_caps(seg, limits, machine, level, rule)
    out = []
    for part in [seg] if whole else split_at_stops(seg):
        ph = _profile(part, machine, limits, level, rule, sink)
        if level >= 3 and part.count > 1:
            from cncc.passes.planning.optimal import accel_step_caps, optimise

            ph = optimise(part, ph, sink, vertex_acap=accel_step_caps(part, limits.jmax_mm_s3,
                                                                      machine.interpolation_period_s))
        out.append(path_rows(part, ph))
    return out


def _rows_within(rows: Rows, limits: AxisLimits) -> bool:
    """Per-axis jerk and acceleration (both ends of every row) within the machine's limits."""
    import numpy as np

    d = rows.dur[:, None]
    a_end = rows.a0 + rows.j * d
    amax = limits.amax_mm_s2[None, :] * (1 + 1e-6) + 1e-9
    return bool(np.all(np.abs(rows.j) <= limits.jmax_mm_s3[None, :] * (1 + 1e-6) + 1e-9)
                and np.all(np.abs(rows.a0) <= amax) and np.all(np.abs(a_end) <= amax))


def _judged_rows(part: Segments, start: Phases, best: Phases, machine: MachineModel, limits: AxisLimits,
                 sink: DiagnosticSink) -> Rows:
    """-O3's rows of a part: the optimised profile, else its start, else -O2's S-curve,
    whichever first keeps every axis within its jerk and acceleration limits."""
    from dataclasses import replace

    from cncc.passes.planning.blending import reduce_accel
    from cncc.passes.planning.emit import path_rows
    from cncc.passes.planning.scurve import scurve_profile

    for ph in (best, start):
        rows = path_rows(part, ph)
        if _rows_within(rows, limits):
            return rows
    raw = part.acap
    seg = replace(part, acap=reduce_accel(part, limits, machine.interpolation_period_s))
    return path_rows(seg, scurve_profile(seg, raw, limits.jmax_mm_s3, machine.interpolation_period_s))


def _corner_caps(seg: Segments, limits: AxisLimits, machine: MachineModel, level: int, rule: CornerRule) -> None:
    """Fill ``seg.vvert`` (interior vertices) by the plan's corner rule."""
    import numpy as np

    from cncc.passes.planning.blending import velocity_step_caps
    from cncc.passes.planning.segments import junction_deviation, speed_step

    if seg.count < 2 or level == 0:
        return
    same_cmd = seg.cmd[1:] == seg.cmd[:-1]
    if level == 1:
        caps = junction_deviation(seg, limits, machine.junction_deviation_mm)
        if rule is CornerRule.SPEED_STEP:
            caps = speed_step(seg, limits)
    else:
        caps = velocity_step_caps(seg, limits, machine.interpolation_period_s)
    if rule is CornerRule.EXACT_STOP:
        caps = np.where(same_cmd, caps, 0.0)
    seg.vvert[1:-1] = np.minimum(seg.vvert[1:-1], caps)


def _profile(seg: Segments, machine: MachineModel, limits: AxisLimits, level: int, rule: CornerRule,
             sink: DiagnosticSink) -> Phases:
    """The path profile of one part (rest to rest) at -O0..-O2 (-O3 starts from -O2's)."""
    import numpy as np

    from cncc.ir.trajectory import Limit
    from cncc.passes.planning.blending import reduce_accel
    from cncc.passes.planning.fir import fir_profile
    from cncc.passes.planning.onedim import ruckig_move
    from cncc.passes.planning.profile import Phases, boundary_speeds, trapezoids
    from cncc.passes.planning.scurve import scurve_profile
    from cncc.passes.planning.segments import take_off_speed
    from cncc.passes.planning.windows import replan_segments

    if level == 0:
        t = seg.length / seg.vcap
        return Phases(np.concatenate([[0.0], np.cumsum(t)[:-1]]), t, seg.s0[:-1], seg.vcap.copy(),
                      np.zeros_like(t), np.zeros_like(t), seg.vlim.copy(), np.arange(seg.count))
    if level == 1:
        if rule is CornerRule.SPEED_STEP:
            seg.vvert[0], seg.vvert[-1] = take_off_speed(seg, limits, machine)
        x = boundary_speeds(seg.length, seg.vcap, seg.acap, seg.vvert**2)
        return trapezoids(seg.length, seg.vcap, seg.acap, x, seg.vlim, int(Limit.ACCEL))
    raw_acap = seg.acap
    seg.acap = reduce_accel(seg, limits, machine.interpolation_period_s)
    if seg.count == 1:
        ph = ruckig_move(float(seg.length[0]), float(seg.vcap[0]), float(seg.acap[0]), float(seg.jcap[0]),
                         int(seg.vlim[0]))
        if ph is not None:
            return ph
        from cncc import diagnostics as dg
        from cncc.source import NO_SPAN

        sink.emit(dg.PLAN_FALLBACK, NO_SPAN, "ruckig could not plan a move; the filtered profile is used")
    if level >= 3 or O2_PROFILE == "filter":
        return replan_segments(seg, fir_profile(seg))
    return scurve_profile(seg, raw_acap, limits.jmax_mm_s3, machine.interpolation_period_s)


Estimate = Callable[[Sequence[Command], MachineModel], "Trajectory"]
ProgressBar = Callable[[str, int], AbstractContextManager[Callable[[int], None]]]


@register
@dataclass(frozen=True, kw_only=True)
class Plan(Pass):
    """Time-parameterise the motion at ``level`` on ``ctx.machine``; the Trajectory goes to
    ``ctx.trajectory`` (how it was made to ``ctx.plan_how``).

    Commands pass through unchanged, in order, so ``Trajectory.cmd_index`` indexes them and
    ``verify`` and the backends still see them.  ``estimate`` replaces the planner (the
    pipeline builder gives -O0 the nominal estimate of :mod:`cncc.backends.nominal`, which
    passes may not import); ``progress`` draws a bar over the planned commands.
    """

    name: ClassVar[str] = "plan"
    stage: ClassVar[str] = "plan"
    level: int = 2  # the -O level
    estimate: Estimate | None = field(default=None, compare=False, repr=False)
    progress: ProgressBar | None = field(default=None, compare=False, repr=False)

    def run(self, cmds: Iterable[Command], ctx: PassContext) -> Iterator[Command]:
        items = list(cmds)
        machine = ctx.machine
        if machine is None:
            from cncc.machines import load_machine

            machine = load_machine("generic-mill")
        ctx.plan_level = self.level
        if self.estimate is not None:
            ctx.trajectory, ctx.plan_how = self.estimate(items, machine), "nominal: length / feed"
            return iter(items)
        if self.progress is None:
            ctx.trajectory = plan_commands(items, machine, self.level, ctx.sink)
        else:
            with self.progress(f"planning -O{self.level} on {machine.name}", len(items)) as update:
                ctx.trajectory = plan_commands(items, machine, self.level, ctx.sink, progress=update)
        ctx.plan_how = f"planned -O{self.level}"
        return iter(items)
