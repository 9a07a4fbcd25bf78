"""The ``verify`` pass: an independent check that a Trajectory obeys the machine.

API::

    from cncc.passes.verify import verify_trajectory
    report = verify_trajectory(traj, cmds, machine, sink, corner_rule=rule, check_dynamics=True)
    report.count        # number of violations (each also emitted, first few per kind)

It shares no code with the planners: it reads only the Trajectory, the commands and
the machine model, and checks each constant-jerk phase analytically: phase ends exactly
(``Trajectory.end_states``, arcs included), per-axis extremes by
:func:`cncc.ir.trajectory.axis_bounds` (exact on straight phases, a rigorous bound on
arcs and helices).

* E0616 continuity: phases contiguous in time and position.
* E0610 velocity: per-axis ``|v|`` (endpoints and the stationary point of the
  quadratic) against ``max_velocity`` (feed moves) or ``rapid`` (rapids) and the step
  rate ``max_step_rate_hz / steps_per_mm``.
* E0611 / E0612 acceleration / jerk within phases (``check_dynamics``).
* E0618 acceleration steps between phases (``jerk_limited`` plans): a step of axis
  acceleration is spread by the controller over one interpolation period ``T`` like a
  velocity step, so it must stay within ``max_jerk * T``.  Trapezoid plans (-O1) step
  their acceleration by design and are checked with ``jerk_limited=False``.
* E0617 corner: velocity steps between phases.  ``junction-deviation``: grbl's
  junction speed for the step's angle; ``speed-step``: per-axis step <= the axis'
  speed step (take-off speed from or to rest, or on both sides of a stop); ``blend`` / ``exact-stop``: the
  controller spreads a step over one interpolation period ``T``, so the axis sees
  ``a(t) + sum(steps in (t - T, t]) / T``, which must stay within ``max_accel``.
* ``strict_continuity`` (:mod:`cncc.passes.verify_physics`, through the Trajectory API
  only): E0617 becomes velocity continuity at every boundary -- a per-axis velocity
  step only where the machine declares one (SZGH speed-step corners, take-off from
  or to rest, a stop through rest at the take-off speed) or the plan's corner rule
  makes one (-O1 junction deviation); no smeared steps -- and E0618 becomes the
  averaged jerk ``|a(t) - a(t - T)| <= max_jerk * T`` at every instant (steps inside
  one period add up).  Axes that are not cubics within a phase are checked for
  E0610-E0612 by dense sampling.  Default :data:`STRICT_CONTINUITY`.
* E0614 feed: path speed above the programmed (and machine-capped) feed.
* E0613 path (``check_path``): positions farther than the blend tolerance (+ arc
  tolerance) from the programmed path of the responsible command or its motion
  neighbours.  The driver skips it for the -O0 nominal trajectory of the timing
  backend, which draws arcs as 10-degree chords for its plots.
* E0615 soft limits (``check_soft_limits``: the driver checks them only when the work
  offsets are known, i.e. with ``--offsets``).
Returns a :class:`VerifyReport`; the ``verify`` pass reads ``ctx.trajectory`` (left by ``plan``).
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink
from cncc.ir.commands import Arc, Command, Linear, Rapid
from cncc.ir.frame import AXES
from cncc.ir.machine import CornerRule, MachineModel, RapidMode
from cncc.ir.trajectory import FloatArray, Trajectory, axis_bounds, position_bounds
from cncc.passes import Pass, PassContext, register
from cncc.source import NO_SPAN

REL = 1e-6  # relative slack on every limit (floating point)
MAX_REPORTS = 5  # diagnostics per kind; the rest are counted
PLAN_MIN_FEED_MM_MIN = 0.1  # the planners' documented smallest feed (docs/planning.md, W0606)
STRICT_CONTINUITY = True  # default of the strict rule (-O2 plans arcs on their path coordinate and blends every corner)
STRICT_JERK = True
"""Default of the averaged-jerk half of the strict rule (E0618 as ``|a(t) - a(t - T)| <= max_jerk * T``).
On: -O2 coasts at the block boundaries where the curvature jumps and ends a block at a vertex inside
one where the step with the neighbouring ramp's jerk is not proven within ``j T``
(``planning/scurve.py``, ``unsafe_steps``).  ``verify{strict_jerk=false}`` turns it off (the
per-boundary E0618 rule stays on)."""


@dataclass
class VerifyReport:
    counts: dict[str, int] = field(default_factory=dict)

    @property
    def count(self) -> int:
        return sum(self.counts.values())

    def add(self, code: str, n: int) -> None:
        if n:
            self.counts[code] = self.counts.get(code, 0) + n


@dataclass
class _Cmds:
    """Per-command data as arrays indexed like ``cmds``."""

    rapid: np.ndarray
    feed_mm_s: FloatArray
    tol_mm: FloatArray
    motion: np.ndarray


def _limits(machine: MachineModel) -> dict[str, FloatArray]:
    by = {a.name: a for a in machine.axes}
    axes = [by.get(n, machine.axes[0]) for n in AXES]
    step = np.array([a.step.max_step_rate_hz * max(a.step.gear_cmd, 1) / (a.step.steps_per_mm * a.step.gear_cmr)
                     for a in axes])
    return {
        "v": np.minimum(np.array([a.max_velocity_mm_min / 60 for a in axes]), step),
        "rapid": np.minimum(np.array([a.rapid_mm_min / 60 for a in axes]), step),
        "a": np.array([a.max_accel_mm_s2 for a in axes]),
        "j": np.array([a.max_jerk_mm_s3 for a in axes]),
        "step": np.array([a.max_speed_step_mm_min / 60 for a in axes]),
        "start": np.array([a.start_speed_mm_min / 60 for a in axes]),
        "lo": np.array([-np.inf if a.soft_min_mm is None else a.soft_min_mm for a in axes]),
        "hi": np.array([np.inf if a.soft_max_mm is None else a.soft_max_mm for a in axes]),
    }


def _cmd_table(cmds: Sequence[Command], machine: MachineModel) -> _Cmds:
    n = len(cmds)
    rapid, motion = np.zeros(n, bool), np.zeros(n, bool)
    feed, tol = np.full(n, np.inf), np.full(n, machine.blend_tolerance_mm)
    for i, c in enumerate(cmds):
        if isinstance(c, Rapid | Linear | Arc):
            motion[i] = True
            rapid[i] = isinstance(c, Rapid)
            if not isinstance(c, Rapid):
                programmed = c.feed_mm_min if c.feed_mm_min > 0 else machine.default_feed_mm_min
                feed[i] = min(max(programmed, PLAN_MIN_FEED_MM_MIN), machine.max_feed_mm_min) / 60
            if c.motion.blend_tolerance_mm is not None:
                tol[i] = c.motion.blend_tolerance_mm
    return _Cmds(rapid, feed, tol, motion)


def verify_trajectory(traj: Trajectory, cmds: Sequence[Command], machine: MachineModel, sink: DiagnosticSink,
                      *, corner_rule: CornerRule | None = None, check_dynamics: bool = True,
                      jerk_limited: bool = True, check_soft_limits: bool = True,
                      check_path: bool = True, strict_continuity: bool | None = None,
                      strict_jerk: bool | None = None) -> VerifyReport:
    """Check ``traj`` (planned from ``cmds``) against ``machine``; see the module docstring."""
    report = VerifyReport()
    if traj.phase_count == 0:
        return report
    lim = _limits(machine)
    table = _cmd_table(cmds, machine)
    rule = corner_rule if corner_rule is not None else machine.corner_rule
    strict = STRICT_CONTINUITY if strict_continuity is None else strict_continuity
    averaged_jerk = STRICT_JERK if strict_jerk is None else strict_jerk
    ci = np.clip(traj.cmd_index, 0, max(len(cmds) - 1, 0))

    def emit(code: str, bad: Any, what: str) -> None:
        idx = np.flatnonzero(np.asarray(bad))
        report.add(code, idx.size)
        for k in idx[:MAX_REPORTS]:
            span = cmds[int(ci[k])].span if len(cmds) else NO_SPAN
            sink.emit(code, span, f"{what} (phase {int(k)}, t = {traj.t0_s[k]:.6f} s)")
        if idx.size > MAX_REPORTS:
            sink.emit(code, NO_SPAN, f"{idx.size - MAX_REPORTS} more of: {what}")

    v0 = traj.v0_mm_s
    p_end, v_end, a_end, _ = traj.end_states()  # exact, arcs included
    _continuity(traj, p_end, emit)
    vmax = np.where(table.rapid[ci][:, None], lim["rapid"][None, :], lim["v"][None, :])
    peak, a_peak, j_peak = axis_bounds(traj)
    bad_v = (peak > vmax * (1 + REL) + 1e-9).any(axis=1)
    emit(dg.VERIFY_VELOCITY, bad_v, "an axis velocity exceeds its limit")
    if check_dynamics:
        amax = lim["a"][None, :] * (1 + REL) + 1e-9
        emit(dg.VERIFY_ACCEL, (a_peak > amax).any(axis=1), "an axis acceleration exceeds its limit")
        emit(dg.VERIFY_JERK, (j_peak > lim["j"][None, :] * (1 + REL) + 1e-9).any(axis=1),
             "an axis jerk exceeds its limit")
        if strict:
            _strict(traj, lim, rule, machine, jerk_limited and averaged_jerk, emit)
        else:
            bad_c = _corners(traj, v_end, a_end, lim, rule, machine)
            emit(dg.VERIFY_CORNER, bad_c, f"a velocity step exceeds the corner rule '{rule.value}'")
        if jerk_limited:
            emit(dg.VERIFY_ACCEL_STEP, _accel_steps(traj, a_end, lim["j"], machine.interpolation_period_s),
                 "an acceleration step exceeds the jerk limit over one interpolation period")
    p_mid, v_mid, _, _ = traj.states(np.arange(traj.phase_count), traj.duration_s / 2)
    speed = np.maximum(np.linalg.norm(v0, axis=1), np.linalg.norm(v_end, axis=1))
    speed = np.maximum(speed, np.linalg.norm(v_mid, axis=1))
    emit(dg.VERIFY_FEED, speed > table.feed_mm_s[ci] * (1 + REL) + 1e-9, "the path speed exceeds the programmed feed")
    if check_path:
        independent = table.rapid[ci] & (machine.rapid_mode is RapidMode.INDEPENDENT)
        dev = _deviation(traj, p_mid, p_end, cmds, table, ci)
        allowed = table.tol_mm[ci] + machine.arc_tolerance_mm + 1e-6
        emit(dg.VERIFY_PATH, (dev > allowed) & ~independent, "the trajectory leaves the programmed path")
    if not check_soft_limits:
        return report
    lo, hi = position_bounds(traj)
    emit(dg.VERIFY_SOFT_LIMIT, ((lo < lim["lo"] - 1e-6) | (hi > lim["hi"] + 1e-6)).any(axis=1),
         "an axis leaves its soft limits")
    return report


def _strict(traj: Trajectory, lim: dict[str, FloatArray], rule: CornerRule, machine: MachineModel,
            jerk_limited: bool, emit: Any) -> None:
    """The ``strict_continuity`` checks (API only, see :mod:`cncc.passes.verify_physics`)."""
    from cncc.passes import verify_physics as vp

    n = traj.phase_count
    b = vp.boundary_states(traj)
    declared = lim["step"] if machine.corner_rule is CornerRule.SPEED_STEP or rule is CornerRule.SPEED_STEP \
        else np.zeros_like(lim["step"])
    bad = vp.velocity_steps_bad(b, declared, lim["start"], np.maximum(lim["v"], lim["rapid"]))
    if rule is CornerRule.JUNCTION_DEVIATION:
        bad &= ~_jd_ok(b.v_before, b.v_after, lim["a"], machine.junction_deviation_mm)
    bad[n - 1] |= bad[n]
    emit(dg.VERIFY_CORNER, bad[:n], f"a velocity step that neither the machine nor the corner rule "
                                    f"'{rule.value}' allows (strict continuity)")
    if jerk_limited:
        jerky = vp.smeared_jerk_bad(traj, b, lim["j"], machine.interpolation_period_s)
        jerky[n - 1] |= jerky[n]
        emit(dg.VERIFY_ACCEL_STEP, jerky[:n], "the acceleration changes by more than the jerk limit "
                                              "within one interpolation period")
    if not _is_cubic(traj):
        # axis_bounds (checked in verify_trajectory) is exact on straight phases: sample the curved ones
        curved = np.asarray(getattr(traj, "curved", np.ones(n, bool)), bool)
        rows = np.flatnonzero(curved)
        v_rows, a_rows, j_rows = vp.dense_extremes(traj, phases=rows)  # rows of the curved phases only

        def over(x: FloatArray, limit: FloatArray) -> np.ndarray:
            bad = np.zeros(n, bool)  # per phase (straight ones are never over here)
            bad[rows] = (x > limit * (1 + REL) + 1e-9).any(axis=1)
            return bad

        emit(dg.VERIFY_VELOCITY, over(v_rows, np.maximum(lim["v"], lim["rapid"])),
             "an axis velocity exceeds its limit (sampled)")
        emit(dg.VERIFY_ACCEL, over(a_rows, lim["a"]), "an axis acceleration exceeds its limit (sampled)")
        emit(dg.VERIFY_JERK, over(j_rows, lim["j"]),
             "an axis jerk exceeds its limit (sampled)")


def _is_cubic(traj: Trajectory) -> bool:
    """Per-axis cubic rows (this module's exact per-phase extremes apply): the row arrays are
    there and no phase is marked ``curved`` (phases on an arc, whose rows are only a start)."""
    curved = getattr(traj, "curved", None)
    if curved is not None and bool(np.asarray(curved).any()):
        return False
    return all(isinstance(getattr(traj, name, None), np.ndarray) for name in ("v0_mm_s", "a0_mm_s2", "j_mm_s3"))


def _continuity(traj: Trajectory, p_end: FloatArray, emit: object) -> None:
    t_end = traj.t0_s + traj.duration_s
    bad = np.zeros(traj.phase_count, bool)
    bad[1:] = (np.abs(traj.t0_s[1:] - t_end[:-1]) > 1e-9) | (np.abs(traj.p0_mm[1:] - p_end[:-1]) > 1e-6).any(axis=1)
    bad |= traj.duration_s < 0
    emit(dg.VERIFY_CONTINUITY, bad, "the trajectory jumps in time or position")  # type: ignore[operator]


def _corners(traj: Trajectory, v_end: FloatArray, a_end: FloatArray, lim: dict[str, FloatArray],
             rule: CornerRule, machine: MachineModel) -> np.ndarray:
    """Phase k is flagged when the velocity step at its start breaks the rule."""
    n, m = traj.v0_mm_s.shape
    before = np.vstack([np.zeros((1, m)), v_end])  # velocity before each boundary (rest at the ends)
    after = np.vstack([traj.v0_mm_s, np.zeros((1, m))])
    step = after - before  # (n+1, m)
    period = machine.interpolation_period_s
    small = (np.abs(step) <= lim["a"] * period * (1 + REL) + 1e-9).all(axis=1)
    if rule is CornerRule.JUNCTION_DEVIATION:
        ok = small | _jd_ok(before, after, lim["a"], machine.junction_deviation_mm)
    elif rule is CornerRule.SPEED_STEP:
        from cncc.passes.verify_physics import steps_declared

        ok = small | steps_declared(before, after, lim["step"], lim["start"], 1e-9)
    else:
        return _smeared(traj, step, a_end, lim["a"], period)[:n]
    bad = ~ok
    bad[n - 1] |= bad[n]
    out: np.ndarray = bad[:n]
    return out


def _accel_steps(traj: Trajectory, a_end: FloatArray, jmax: FloatArray, period_s: float) -> np.ndarray:
    """Phase k is flagged when the acceleration step at its start (or, for the last
    phase, at its end) exceeds ``max_jerk * T`` on some axis."""
    n, m = traj.a0_mm_s2.shape
    before = np.vstack([np.zeros((1, m)), a_end])
    after = np.vstack([traj.a0_mm_s2, np.zeros((1, m))])
    bad = (np.abs(after - before) > jmax * period_s * (1 + REL) + 1e-6).any(axis=1)
    bad[n - 1] |= bad[n]
    out: np.ndarray = bad[:n]
    return out


def _jd_ok(before: FloatArray, after: FloatArray, amax: FloatArray, dev_mm: float) -> np.ndarray:
    sb, sa = np.linalg.norm(before, axis=1), np.linalg.norm(after, axis=1)
    ub = before / np.maximum(sb, 1e-300)[:, None]
    ua = after / np.maximum(sa, 1e-300)[:, None]
    cos_t = -np.einsum("ij,ij->i", ub, ua)
    jv = ua - ub
    jv /= np.maximum(np.linalg.norm(jv, axis=1), 1e-300)[:, None]
    with np.errstate(divide="ignore"):
        acc = np.where(np.abs(jv) > 1e-12, amax / np.maximum(np.abs(jv), 1e-300), np.inf).min(axis=1)
    sh = np.sqrt(np.clip(0.5 * (1 - cos_t), 0, 1))
    with np.errstate(divide="ignore", invalid="ignore"):
        vj = np.sqrt(np.maximum(acc * dev_mm * sh / (1 - sh), 0))
    vj = np.where(cos_t < -0.999999, np.inf, vj)
    same_speed = np.abs(sb - sa) <= 1e-6 * np.maximum(sb, 1.0)
    ok: np.ndarray = same_speed & (np.maximum(sb, sa) <= vj * (1 + REL) + 1e-9)
    return ok


def _smeared(traj: Trajectory, step: FloatArray, a_end: FloatArray, amax: FloatArray, period: float) -> np.ndarray:
    """``|a(t) + sum(steps in (t - T, t]) / T| <= amax`` at every event time."""
    n = traj.phase_count
    t_b = np.concatenate([traj.t0_s, [traj.t0_s[-1] + traj.duration_s[-1]]])
    cum = np.vstack([np.zeros((1, step.shape[1])), np.cumsum(step, axis=0)])

    def box(t: FloatArray, include_t: bool) -> FloatArray:
        hi = np.searchsorted(t_b, t, side="right" if include_t else "left")
        lo = np.searchsorted(t_b, t - period, side="right")
        out: FloatArray = (cum[hi] - cum[lo]) / period
        return out

    start_ok = np.abs(traj.a0_mm_s2 + box(t_b[:-1], True)) <= amax * (1 + REL) + 1e-6
    end_ok = np.abs(a_end + box(t_b[1:], False)) <= amax * (1 + REL) + 1e-6
    bad: np.ndarray = np.asarray(~(start_ok.all(axis=1) & end_ok.all(axis=1)))
    t_box = t_b + period  # the smear of each step ends here
    k = np.clip(np.searchsorted(traj.t0_s, t_box, side="left") - 1, 0, n - 1)
    tau = np.clip(t_box - traj.t0_s[k], 0, traj.duration_s[k])
    _, _, a_at, _ = traj.states(k, tau)
    inside = (t_box < t_b[-1])[:, None]
    box_ok = np.abs(np.where(inside, a_at, 0.0) + box(t_box, True)) <= amax * (1 + REL) + 1e-6
    bad_box = np.asarray(~box_ok.all(axis=1))
    np.logical_or.at(bad, k, bad_box)
    return bad


def _deviation(traj: Trajectory, mid: FloatArray, p_end: FloatArray, cmds: Sequence[Command], table: _Cmds,
               ci: np.ndarray) -> FloatArray:
    """Distance of each phase's start, middle and end to the programmed path nearby."""
    from cncc.passes.verify_geometry import distance_to_commands

    dist = np.zeros(traj.phase_count)
    for pts in (traj.p0_mm, mid, p_end):
        dist = np.maximum(dist, distance_to_commands(pts, ci, cmds, table.motion))
    return dist


@register
@dataclass(frozen=True, kw_only=True)
class Verify(Pass):
    """Check ``ctx.trajectory`` (left there by ``plan``) against ``ctx.machine`` under the corner
    rule of ``ctx.plan_level``; the report goes to ``ctx.verify_report``.  Commands pass
    through unchanged."""

    name: ClassVar[str] = "verify"
    stage: ClassVar[str] = "plan"
    check_dynamics: bool = True  # accelerations, jerks and corners (-O1 and above)
    jerk_limited: bool = True  # acceleration steps too (-O2 and above)
    soft_limits: bool = False  # the machine's soft limits (only meaningful with the work offsets known)
    strict_continuity: bool | None = None  # None: STRICT_CONTINUITY (velocity continuity)
    strict_jerk: bool | None = None  # None: STRICT_JERK (the averaged jerk, with strict_continuity)

    def run(self, cmds: Iterable[Command], ctx: PassContext) -> Iterator[Command]:
        items = list(cmds)
        traj = ctx.trajectory
        if isinstance(traj, Trajectory) and ctx.machine is not None:
            from cncc.machines import effective_corner_rule

            ctx.verify_report = verify_trajectory(traj, items, ctx.machine, ctx.sink,
                                                  corner_rule=effective_corner_rule(ctx.machine, ctx.plan_level),
                                                  check_dynamics=self.check_dynamics,
                                                  jerk_limited=self.jerk_limited,
                                                  check_soft_limits=self.soft_limits,
                                                  strict_continuity=self.strict_continuity,
                                                  strict_jerk=self.strict_jerk)
        return iter(items)
