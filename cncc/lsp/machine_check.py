"""The second analysis phase: the program on the configured machine.

After the first phase has published its diagnostics, the server runs
``machine_phase(analysis, result, check)`` as a background job
(:mod:`cncc.lsp.guard`: it waits while a fresh edit is analysed, and a new edit
stops it at once).  It

1. compiles the document again in machine coordinates (work offsets and tool
   lengths applied, as the planner's backends see it);
2. when a machine is configured, builds the nominal trajectory (every move at its
   programmed feed or the rapid rate) and reports, once per command and axis, the
   worst of: a soft limit crossed (E0703), a step rate above the axis' maximum
   (E0701), an axis velocity above its maximum (E0610);
3. plans at the configured ``opt_level`` (the inlay hints then show the planner's
   times) and runs the ``verify`` pass over that trajectory; what verify finds on a
   command that step 2 did not flag is added (axis velocity; soft limits too when
   the planned trajectory is not the nominal one step 2 checked).

``result`` is filled step by step, so a run stopped at its budget still gives what
it found before; ``result.step`` says where it stopped.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

from cncc import diagnostics as dg
from cncc.diagnostics import Diagnostic, DiagnosticSink, Severity
from cncc.ir import Command
from cncc.ir.machine import Axis, MachineModel
from cncc.lsp.analysis import CHECK_EVERY, MAX_COMMANDS, Analysis
from cncc.lsp.pipeline import compile_commands
from cncc.source import SourceMap, Span

if TYPE_CHECKING:
    from cncc.ir.trajectory import Trajectory

MAX_REPORTS = 500  # machine diagnostics per document
LIMITS_CAPPED = "more machine limit violations are not listed"
VERIFY_KEPT = frozenset({dg.VERIFY_VELOCITY, dg.VERIFY_SOFT_LIMIT})  # verify codes that concern the program
REL = 1e-9  # relative slack on the limits (floating point)
TOL_MM = 1e-6


@dataclass(slots=True)
class MachineCheck:
    diagnostics: list[Diagnostic] = field(default_factory=list)
    line_time_s: dict[int, float] | None = None  # planned times (opt_level > 0)
    sources: SourceMap = field(default_factory=SourceMap)
    step: str = "starting"
    stopped: str | None = None


def wanted(a: Analysis) -> bool:
    """Whether the document gets a second phase (a machine configured, or planned inlay times)."""
    settings = a.request.settings
    return a.stopped is None and a.machine is not None and a.dialect is not None and bool(a.text.strip()) \
        and (bool(settings.machine) or settings.opt_level > 0)


def warm_up() -> None:
    """Import what the phase needs (run where a forced stop cannot cut an import in half)."""
    import numpy  # noqa: F401

    import cncc.backends.nominal
    import cncc.passes.plan
    import cncc.passes.verify  # noqa: F401


def machine_phase(a: Analysis, out: MachineCheck, check: Callable[[], None]) -> None:
    """Fill ``out`` (the guarded work of the background job)."""
    from cncc import driver

    machine = a.machine
    assert machine is not None
    settings = a.request.settings
    configured = bool(settings.machine)
    out.step = "compiling in machine coordinates"
    sink = DiagnosticSink(max_count=5000)
    cmds: list[Command] = []
    assert a.dialect is not None
    for c in compile_commands(a.request, a.dialect, machine, out.sources, sink, machine_coords=True):
        if len(cmds) % CHECK_EVERY == 0:
            check()
        cmds.append(c)
        if len(cmds) > MAX_COMMANDS:
            out.diagnostics.append(Diagnostic(dg.ANALYSIS_STOPPED, Severity.NOTE, Span(0, 0, 0),
                                              f"more than {MAX_COMMANDS} commands: the machine checks are skipped"))
            return
    out.diagnostics.extend(_new(sink, a.diagnostics))
    covered: set[Span] = set()
    blind = False  # soft limits checked without the work offsets
    if configured:
        check()
        out.step = "checking limits"
        nominal, _ = driver.plan_trajectory(cmds, machine, 0, DiagnosticSink())
        check()
        found = limit_diagnostics(nominal, cmds, machine)
        covered = {d.span for d in found}
        blind = offsets_missing(settings, a.text, found)
        if blind:
            found = without_offsets(found, settings.offsets)
        out.diagnostics.extend(found)
    level = max(0, min(3, settings.opt_level))
    traj = nominal if configured and level == 0 else None
    if level > 0:
        check()
        out.step = f"planning at -O{level}"
        plan_sink = DiagnosticSink()
        try:
            traj, _ = driver.plan_trajectory(cmds, machine, level, plan_sink)
        except Exception as exc:  # the planner is young: keep the nominal times, say why
            out.diagnostics.append(Diagnostic(dg.NOT_SUPPORTED, Severity.NOTE, Span(0, 0, 0),
                                              f"-O{level} planning failed ({type(exc).__name__}: {exc}); "
                                              "inlay hints show nominal times"))
            return
        if configured:  # the planner's notes about this machine (a feed above its cap ...)
            out.diagnostics.extend(plan_sink)
        out.line_time_s = planned_times(a, cmds, traj, machine)
    if configured and traj is not None:
        check()
        out.step = "verifying the trajectory"
        checked = verify_diagnostics(traj, cmds, machine, level, covered)
        if blind:  # the soft limits were summed up above
            checked = [d for d in checked if d.code != dg.VERIFY_SOFT_LIMIT]
        out.diagnostics.extend(checked)
    out.step = "done"


_WORK_RE = re.compile(r"G[ \t]*0*5[4-9](?:\.[1-9])?(?![\d.])", re.IGNORECASE)


MANY_CROSSINGS = 10  # more moves than this beyond the limits, and no offsets table: a missing table


def region_first(a: Analysis, old: Analysis, check: Callable[[], None]) -> MachineCheck | None:
    """The machine checks of an incremental analysis, quickly: the old second phase's
    diagnostics outside the re-run region (shifted), and the soft limits, step rates and axis
    speeds of the region's own moves (its first-phase commands taken to machine coordinates by
    the frame passes).  None when there is nothing to start from (the full phase follows
    anyway and replaces this)."""
    from cncc import driver
    from cncc.passes import PassContext
    from cncc.pipeline import PipelineConfig, builder
    from cncc.pipeline.manager import PassManager

    prev = old.machine_check
    if (a.region is None or prev is None or prev.stopped or a.machine is None or a.dialect is None
            or not a.request.settings.machine
            or any(d.code in (dg.NO_OFFSETS_TABLE, dg.ANALYSIS_STOPPED) for d in prev.diagnostics)):
        return None
    lo, hi_new, hi_old = a.region
    delta = hi_new - hi_old
    kept = []
    for d in prev.diagnostics:
        s = d.span
        if s.source_id != 0 or s.start < lo:
            kept.append(d)
        elif s.start >= hi_old:
            kept.append(replace(d, span=Span(0, s.start + delta, s.end + delta)))
    check()
    cmds = [c for c in a.commands_between(lo, hi_new) if lo <= c.span.start < hi_new]
    if cmds:
        ctx = PassContext(sink=DiagnosticSink(), dialect=a.dialect, machine=a.machine)
        passes = builder.frame_passes(PipelineConfig(machine_coords=True), a.dialect)
        moved = list(PassManager().run(passes, cmds, ctx))
        check()
        traj, _ = driver.plan_trajectory(moved, a.machine, 0, DiagnosticSink())
        kept += limit_diagnostics(traj, moved, a.machine)
    return MachineCheck(diagnostics=kept, step="the changed region")


def offsets_missing(settings: Any, text: str, found: Sequence[Diagnostic]) -> bool:
    """Whether the soft-limit checks lack the work offsets: a configured offsets file cannot be
    read; or none is configured while the program selects a work system (G54 ... G59.x) or
    more than :data:`MANY_CROSSINGS` moves cross the limits (a CAM program's coordinates are
    work coordinates: taken as machine positions, nearly every block crosses)."""
    import os

    if settings.offsets:
        return not os.path.isfile(settings.path(settings.offsets))
    if _WORK_RE.search(text) is not None:
        return True
    return len({d.span.start for d in found if d.code == dg.SOFT_LIMIT}) > MANY_CROSSINGS


def without_offsets(found: list[Diagnostic], offsets: str | None) -> list[Diagnostic]:
    """``found`` with its soft-limit diagnostics replaced by one warning (W0775) on the first:
    without a work offsets table every G54 ... position is a machine position, so a program
    written for a fixture offset crosses the limits on nearly every block."""
    soft = [d for d in found if d.code == dg.SOFT_LIMIT]
    if not soft:
        return found
    capped = any(d.code == dg.ANALYSIS_STOPPED and LIMITS_CAPPED in d.message for d in found)
    rest = [d for d in found if d.code != dg.SOFT_LIMIT and not (d.code == dg.ANALYSIS_STOPPED
                                                                  and LIMITS_CAPPED in d.message)]
    why = (f"the work offsets file {offsets!r} cannot be read" if offsets
           else "no work offsets table is configured (offsets = \"offsets.toml\" in cncc.toml)")
    lines = len({d.span.start for d in soft})
    first = min(soft, key=lambda d: (d.span.source_id != 0, d.span.start))
    count = f"more than {lines} moves" if capped else f"{lines} move(s)"
    message = (f"{count} cross the machine's soft limits, the first here ({first.message}); "
               f"but {why}, so program positions were checked as machine positions")
    return [Diagnostic(dg.NO_OFFSETS_TABLE, Severity.WARNING, first.span, message), *rest]


def _new(sink: DiagnosticSink, seen: Sequence[Diagnostic]) -> list[Diagnostic]:
    """Diagnostics of the machine-coordinate compile that the first phase did not have."""
    old = {(d.code, d.span, d.message) for d in seen}
    return [d for d in sink if (d.code, d.span, d.message) not in old]


# ---- limits on the nominal trajectory --------------------------------------------------
@dataclass(slots=True)
class _Phases:
    """The nominal trajectory reduced to what the limit checks read (arrays of shape (n, 6) / (n,))."""

    lo: Any  # smallest and largest position of each axis in each phase (beyond its start)
    hi: Any
    speed: Any  # largest |velocity| of each axis in each phase
    cmd: Any  # command index of each phase
    rapid: Any  # the phase belongs to a rapid


def limit_diagnostics(traj: Trajectory, cmds: Sequence[Command], machine: MachineModel) -> list[Diagnostic]:
    """Soft limits, step rates and axis velocities of ``traj`` (a nominal trajectory of ``cmds``),
    one diagnostic per (code, command, axis) with the worst value."""
    import numpy as np

    from cncc.ir import Rapid

    if traj.phase_count == 0 or not cmds:
        return []
    d = traj.duration_s[:, None]
    p0, v0, a0, j = traj.p0_mm, traj.v0_mm_s, traj.a0_mm_s2, traj.j_mm_s3
    p1 = p0 + v0 * d + a0 * d * d / 2 + j * d * d * d / 6
    v1 = v0 + a0 * d + j * d * d / 2
    ci = np.clip(traj.cmd_index, 0, len(cmds) - 1)
    # a move is flagged where it ends up beyond a limit (one that starts out there is the previous
    # move's fault); nominal phases are straight, so their ends are their extremes
    ph = _Phases(p1, p1, np.maximum(np.abs(v0), np.abs(v1)), ci,
                 np.array([isinstance(c, Rapid) for c in cmds])[ci])
    worst: dict[tuple[int, str, str], tuple[float, str]] = {}
    for i, name in enumerate(traj.axes):
        ax = machine.axis(name)
        if ax is not None:
            for key, excess, message in _axis_violations(ph, i, ax):
                if key not in worst or excess > worst[key][0]:
                    worst[key] = (excess, message)
    out: list[Diagnostic] = []
    for (k, code, _axis), (_excess, message) in sorted(worst.items()):
        if len(out) >= MAX_REPORTS:
            out.append(Diagnostic(dg.ANALYSIS_STOPPED, Severity.NOTE, Span(0, 0, 0),
                                  f"{len(worst) - MAX_REPORTS} {LIMITS_CAPPED} (the first {MAX_REPORTS} are)"))
            break
        out.append(Diagnostic(code, dg.CODES[code].severity, cmds[k].span, message))
    return out


def _axis_violations(ph: _Phases, i: int, ax: Axis) -> Iterator[tuple[tuple[int, str, str], float, str]]:
    """((command, code, axis), how far over, message) for every phase where axis ``i`` breaks a limit."""
    import numpy as np

    name = ax.name
    lo, hi, v = ph.lo[:, i], ph.hi[:, i], ph.speed[:, i]
    if ax.soft_max_mm is not None:
        for k in np.flatnonzero(hi > ax.soft_max_mm + TOL_MM).tolist():
            yield ((int(ph.cmd[k]), dg.SOFT_LIMIT, name), float(hi[k] - ax.soft_max_mm),
                   f"{name} reaches {hi[k]:.3f} (machine coordinates), above its soft limit {ax.soft_max_mm:.3f}")
    if ax.soft_min_mm is not None:
        for k in np.flatnonzero(lo < ax.soft_min_mm - TOL_MM).tolist():
            yield ((int(ph.cmd[k]), dg.SOFT_LIMIT, name), float(ax.soft_min_mm - lo[k]),
                   f"{name} reaches {lo[k]:.3f} (machine coordinates), below its soft limit {ax.soft_min_mm:.3f}")
    steps_per_mm = ax.step.steps_per_mm * ax.step.gear_cmr / max(ax.step.gear_cmd, 1)
    step_mm_s = ax.step.max_step_rate_hz / steps_per_mm
    axis_mm_s = np.where(ph.rapid, ax.rapid_mm_min, ax.max_velocity_mm_min) / 60.0
    fast_step = v > step_mm_s * (1 + REL) + 1e-12
    for k in np.flatnonzero(fast_step).tolist():
        yield ((int(ph.cmd[k]), dg.STEP_RATE, name), float(v[k] / step_mm_s),
               f"{name} would step at {_hz(v[k] * steps_per_mm)} {_at(bool(ph.rapid[k]))} "
               f"({v[k] * 60:.0f} mm/min along {name}); its maximum step rate is {_hz(ax.step.max_step_rate_hz)} "
               f"({step_mm_s * 60:.0f} mm/min)")
    for k in np.flatnonzero((v > axis_mm_s * (1 + REL) + 1e-12) & ~fast_step).tolist():
        yield ((int(ph.cmd[k]), dg.VERIFY_VELOCITY, name), float(v[k] / axis_mm_s[k]),
               f"{name} would move at {v[k] * 60:.0f} mm/min {_at(bool(ph.rapid[k]))}; "
               f"its maximum is {axis_mm_s[k] * 60:.0f} mm/min")


def _hz(rate_hz: float) -> str:
    return f"{rate_hz / 1000:.1f} kHz" if rate_hz >= 1000 else f"{rate_hz:.0f} Hz"


def _at(rapid: bool) -> str:
    return "at the rapid rate" if rapid else "at the programmed feed"


# ---- planning and verify ---------------------------------------------------------------
def planned_times(a: Analysis, cmds: Sequence[Command], traj: Trajectory, machine: MachineModel
                  ) -> dict[int, float]:
    """Seconds per document line: the planner's for motions, the nominal ones for the rest."""
    from cncc.backends.nominal import command_time_s
    from cncc.ir import MOTION_TYPES

    per_cmd = [0.0] * len(cmds)
    for k, dur in zip(traj.cmd_index.tolist(), traj.duration_s.tolist(), strict=True):
        if 0 <= k < len(per_cmd):
            per_cmd[k] += dur
    line_of = a.index.line_of
    times: dict[int, float] = {}
    for c, t_motion in zip(cmds, per_cmd, strict=True):
        if c.span.source_id != 0:
            continue
        t = t_motion if isinstance(c, MOTION_TYPES) else command_time_s(c, machine)[0]
        if t > 0.0:
            line = line_of(c.span.start)
            times[line] = times.get(line, 0.0) + t
    return times


def verify_diagnostics(traj: Trajectory, cmds: Sequence[Command], machine: MachineModel, level: int,
                       covered: set[Span]) -> list[Diagnostic]:
    """What the verify pass finds on commands the limit checks did not flag already."""
    from cncc.machines import effective_corner_rule
    from cncc.passes.verify import verify_trajectory

    sink = DiagnosticSink(max_count=5000)
    verify_trajectory(traj, list(cmds), machine, sink, corner_rule=effective_corner_rule(machine, level),
                      check_dynamics=level > 0)
    kept = VERIFY_KEPT if level > 0 else VERIFY_KEPT - {dg.VERIFY_SOFT_LIMIT}  # -O0: the limit checks saw the same
    out = []
    for d in sink:
        if d.code in kept and d.span.source_id >= 0 and d.span not in covered:
            covered.add(d.span)
            out.append(d)
    return out
