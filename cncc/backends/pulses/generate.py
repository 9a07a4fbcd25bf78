"""The pulse generator: Trajectory + MachineModel -> stream of :class:`StepChunk`.

Per window (a group of trajectory segments in exact mode, of interpolation periods
in interp mode) every axis' raw steps (:mod:`.solve` or :mod:`.interp`) go through:

1. **reversals**: a stretch of motion whose direction differs from the axis' last
   one starts at the reversal instant ``t_r``;
2. **pauses** (:mod:`.pauses`): the reversal delays (SZGH Axis P68, found for the whole
   trajectory before the first window) and the pauses of commands without motion
   (dwells, tool changes, ...: ``pauses=``) are inserted into the time line; every
   later event of every axis moves by them;
3. **backlash** (:mod:`.backlash`): ``backlash_steps`` pulses in the new direction,
   starting at ``t_r`` (mode A at a constant rate, mode B ramped), superposed on the
   commanded steps in exact mode (a burst still running at a window's end holds the
   axis' later events back to the next window), added to the period counts in
   interpolation mode;
4. rounding to integer nanoseconds; a step after a direction change is delayed, if
   needed, to ``previous step + pulse_width_ns + dir_setup_ns`` (W0705), and the
   direction line changes ``dir_setup_ns`` before it;
5. limit checks (E0701/E0702) and the chunk.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass

import numpy as np

from cncc import diagnostics as diag
from cncc.backends.pulses.backlash import B, BurstMerger, PeriodBacklash, Train, add_period_counts
from cncc.backends.pulses.blocks import blockwise
from cncc.backends.pulses.chunk import AxisSteps, PulseLayout, StepChunk
from cncc.backends.pulses.interp import SZGH_PERIOD_S, interp_window, period_count, phase_at
from cncc.backends.pulses.limits import Reporter, check_soft_limits, check_spacing
from cncc.backends.pulses.pauses import (
    ReversalKey,
    ReversalPauses,
    TimeLine,
    delay_ns,
    exact_reversals,
    flips,
    interp_reversals,
)
from cncc.backends.pulses.solve import (
    F64,
    I8,
    I32,
    I64,
    RawSteps,
    Segments,
    exact_axis_steps,
    segment,
    windows,
)
from cncc.backends.pulses.spec import AxisPulseSpec, axis_spec, backlash_offsets_s
from cncc.diagnostics import DiagnosticSink
from cncc.ir.machine import Axis, MachineModel
from cncc.ir.trajectory import Trajectory, axis_bounds
from cncc.source import NO_SPAN, Span

MODES = ("exact", "interp")
DEFAULT_CHUNK_STEPS = 1 << 18
FAR_FUTURE_NS = 1 << 62


@dataclass(slots=True)
class _AxisState:
    last_t_ns: int | None = None
    last_dir: int = 1  # direction of the last pulse (the line's initial level means +1)
    last_motion: int = 1  # direction of the last commanded motion (homing was positive)


def build_specs(traj: Trajectory, machine: MachineModel,
                sink: DiagnosticSink | None) -> tuple[tuple[AxisPulseSpec, ...], tuple[int, ...]]:
    """Specs of the trajectory axes that the machine has, or that move; and their columns."""
    specs: list[AxisPulseSpec] = []
    cols: list[int] = []
    for i, name in enumerate(traj.axes):
        axis = machine.axis(name)
        moves = traj.phase_count > 0 and bool(
            np.any(traj.v0_mm_s[:, i]) or np.any(traj.a0_mm_s2[:, i]) or np.any(traj.j_mm_s3[:, i])
            or np.ptp(traj.p0_mm[:, i]) > 0)
        if axis is None:
            if not moves:
                continue
            axis = Axis(name)
            if sink is not None:
                sink.emit(diag.AXIS_NOT_IN_MACHINE, NO_SPAN, f"axis {name} is not in machine {machine.name!r}")
        spec, ok = axis_spec(axis)
        if not ok and sink is not None:
            sink.emit(diag.BAD_PITCH_TABLE, NO_SPAN, f"axis {name}: pitch-error table slope below -1")
        specs.append(spec)
        cols.append(i)
    return tuple(specs), tuple(cols)


def generate_pulses(traj: Trajectory, machine: MachineModel, *, mode: str = "exact",
                    spans: Sequence[Span] | None = None, sink: DiagnosticSink | None = None,
                    chunk_steps: int = DEFAULT_CHUNK_STEPS, period_s: float = SZGH_PERIOD_S,
                    pauses: Sequence[tuple[int, int]] = (),
                    reversals: ReversalPauses | None = None) -> Iterator[StepChunk]:
    """Stream the step/dir pulses of ``traj`` on ``machine`` in chunks of about ``chunk_steps`` steps.

    ``mode`` is ``"exact"`` (every step at its crossing time) or ``"interp"`` (counted per
    ``period_s`` and spread evenly, as the SZGH interpolator).  ``spans[cmd_index]`` locates
    the command responsible for a diagnostic in ``sink``.  ``pauses``: ``(command index, ns)``
    of the commands without motion that take time (dwells, tool changes, ...), inserted into
    the time line before the next command's motion.  ``reversals``: the reversal pauses from
    :func:`reversal_pauses` for the same trajectory, machine and options (found here when
    not given, or given for other options).
    """
    if mode not in MODES:
        raise ValueError(f"pulse mode must be one of {MODES}, not {mode!r}")
    specs, cols = build_specs(traj, machine, sink)
    layout = PulseLayout(specs, mode)
    rep = Reporter(traj, spans, sink)
    check_soft_limits(traj, specs, cols, rep)
    budget = max(int(chunk_steps), 16)
    key = _reversal_key(mode, period_s, budget)
    if traj.phase_count == 0:
        post = _Post(layout, rep, period_s, TimeLine.of(ReversalPauses.none(key), traj.cmd_index, pauses))
        yield post.finish([RawSteps.empty() for _ in specs], 0.0, True, 0)
        return
    if mode == "exact":
        seg = segment(traj, _steps_per_mm(traj, specs, cols), budget)
        wins = windows(seg, budget)
        if reversals is None or reversals.key != key:
            reversals = _none_or(key, specs) or exact_reversals(traj, seg, wins, specs, cols, key)
        post = _Post(layout, rep, period_s, TimeLine.of(reversals, traj.cmd_index, pauses))
        yield from _exact(traj, specs, cols, post, seg, wins)
    else:
        if reversals is None or reversals.key != key:
            reversals = _none_or(key, specs) or interp_reversals(traj, specs, cols, period_s, key)
        post = _Post(layout, rep, period_s, TimeLine.of(reversals, traj.cmd_index, pauses))
        yield from _interp(traj, specs, cols, post, budget, period_s)


def reversal_pauses(traj: Trajectory, machine: MachineModel, *, mode: str = "exact",
                    chunk_steps: int = DEFAULT_CHUNK_STEPS, period_s: float = SZGH_PERIOD_S) -> ReversalPauses:
    """The reversal pauses :func:`generate_pulses` inserts with the same arguments (none when no
    axis has a ``reversal_delay_s``); ``by_command(traj.cmd_index)`` charges them to commands."""
    if mode not in MODES:
        raise ValueError(f"pulse mode must be one of {MODES}, not {mode!r}")
    specs, cols = build_specs(traj, machine, None)
    budget = max(int(chunk_steps), 16)
    key = _reversal_key(mode, period_s, budget)
    found = _none_or(key, specs)
    if found is not None or traj.phase_count == 0:
        return found or ReversalPauses.none(key)
    if mode == "exact":
        seg = segment(traj, _steps_per_mm(traj, specs, cols), budget)
        return exact_reversals(traj, seg, windows(seg, budget), specs, cols, key)
    return interp_reversals(traj, specs, cols, period_s, key)


def _reversal_key(mode: str, period_s: float, budget: int) -> ReversalKey:
    return (mode, period_s if mode == "interp" else 0.0, budget if mode == "exact" else 0)


def _none_or(key: ReversalKey, specs: tuple[AxisPulseSpec, ...]) -> ReversalPauses | None:
    """No reversal pauses when no axis has a delay (skips the search); None otherwise."""
    return None if any(delay_ns(s) > 0 for s in specs) else ReversalPauses.none(key)


def _steps_per_mm(traj: Trajectory, specs: tuple[AxisPulseSpec, ...], cols: tuple[int, ...]) -> F64:
    r = np.zeros(len(traj.axes))
    for spec, i in zip(specs, cols, strict=True):
        r[i] = spec.rate_factor()
    return r


def _exact(traj: Trajectory, specs: tuple[AxisPulseSpec, ...], cols: tuple[int, ...], post: _Post,
           seg: Segments, wins: list[tuple[int, int]]) -> Iterator[StepChunk]:
    for w, (lo, hi) in enumerate(wins):
        raws = [exact_axis_steps(traj, seg, lo, hi, i, spec) for spec, i in zip(specs, cols, strict=True)]
        t_end = float(traj.t0_s[seg.phase[hi - 1]] + seg.tb_s[hi - 1])
        yield post.finish(raws, t_end, w == len(wins) - 1, int(seg.phase[hi - 1]))


def _interp(traj: Trajectory, specs: tuple[AxisPulseSpec, ...], cols: tuple[int, ...], post: _Post,
            budget: int, period_s: float) -> Iterator[StepChunk]:
    r = _steps_per_mm(traj, specs, cols)
    vmax = blockwise(axis_bounds, traj)[0].max(axis=0)  # arcs included
    per_period = float((r * vmax).sum() * period_s) + 1.0
    k_win = int(min(max(budget / per_period, 1.0), 1 << 20))
    total = period_count(traj, period_s)
    sub = traj.select_axes(list(cols))
    for k0 in range(0, max(total, 1), k_win):
        k1 = min(k0 + k_win, total)
        raws = interp_window(sub, specs, k0, k1, period_s)
        phase_end = int(phase_at(sub, np.array([(k1 - 0.5) * period_s]))[0]) if k1 > k0 else 0
        yield post.finish(raws, k1 * period_s, k1 >= total, phase_end)


Flips = tuple[F64, I8, I32]  # reversal instants (s), new directions, phases


class _Post:
    """Steps 1-5 of the module docstring, with the state carried between windows."""

    def __init__(self, layout: PulseLayout, rep: Reporter, period_s: float, timeline: TimeLine) -> None:
        self.layout = layout
        self.rep = rep
        self.period_s = period_s
        self.timeline = timeline
        self.state = [_AxisState() for _ in layout.specs]
        bursts = [backlash_offsets_s(s) for s in layout.specs]
        self.merger = [BurstMerger(off, length) for off, length in bursts]
        self.per_period = [PeriodBacklash.of(off, period_s) for off, _ in bursts]
        self.index = 0
        self.t_start_ns = 0
        self.phase_end = 0  # the previous window's last phase

    def finish(self, raws: list[RawSteps], t_end_s: float, final: bool, phase_end: int) -> StepChunk:
        """The chunk of a window ending at trajectory time ``t_end_s`` whose steps are in phases up to
        ``phase_end`` (ignored when ``final``)."""
        specs = self.layout.specs
        flipped = [self._flips(raw, st) for raw, st in zip(raws, self.state, strict=True)]
        flags: list[B | None] = [None] * len(specs)
        if self.layout.mode == "interp":
            for i, raw in enumerate(raws):
                raws[i], flags[i] = self._period_backlash(i, raw, flipped[i], t_end_s, final)
        end_ns, rev_ns, ev_ns = self.timeline.window_end(t_end_s, phase_end, final)
        axes = [self._axis(i, spec, raws[i], flipped[i], flags[i], end_ns, final) for i, spec in enumerate(specs)]
        horizon = FAR_FUTURE_NS if final else end_ns - self.layout.max_dir_setup_ns - 1
        holds = [m.hold_ns for m in self.merger if m.hold_ns is not None]
        if holds:
            horizon = min(horizon, min(holds) - self.layout.max_dir_setup_ns - 1)
        chunk = StepChunk(self.layout, self.index, self.t_start_ns, end_ns, horizon, tuple(axes), rev_ns, ev_ns)
        self.index += 1
        self.t_start_ns = end_ns
        self.phase_end = max(self.phase_end, phase_end)
        return chunk

    @staticmethod
    def _flips(raw: RawSteps, st: _AxisState) -> Flips:
        found = flips(raw.run_t_s, raw.run_dir, raw.run_phase, st.last_motion)
        if raw.run_dir.size:
            st.last_motion = int(raw.run_dir[-1])
        return found

    def _period_backlash(self, i: int, raw: RawSteps, flip: Flips, t_end_s: float,
                         final: bool) -> tuple[RawSteps, B | None]:
        """Interpolation mode: the compensation added to the period counts (see :mod:`.backlash`)."""
        pb = self.per_period[i]
        if pb.per_period.size and flip[0].size:
            pb.add(np.rint(flip[0] / self.period_s).astype(np.int64), flip[1], flip[2])
        if not pb.pending:
            return raw, None
        k1 = None if final else round(t_end_s / self.period_s)
        bl_k, bl_c, bl_ph = pb.take(k1)
        periods = np.rint(raw.run_t_s / self.period_s).astype(np.int64)
        counts: I64 = np.diff(np.append(raw.run_first, raw.t_s.shape[0])) * raw.run_dir.astype(np.int64)
        t_s, d, ph, bl, keys, run_dir, run_ph, first = add_period_counts(
            periods, counts, raw.run_phase, bl_k, bl_c, bl_ph, self.period_s)
        if run_ph.size:  # a period with backlash pulses only keeps the flip's phase: never go back in phases
            run_mono = np.maximum.accumulate(np.maximum(run_ph, self.phase_end))
            if not np.array_equal(run_mono, run_ph):
                run_ph = run_mono.astype(np.int32)
                ph = np.repeat(run_ph, np.diff(np.append(first, t_s.shape[0])))
        run_t_s: F64 = keys.astype(np.float64) * self.period_s
        return RawSteps(t_s, d, ph, run_t_s, run_dir, run_ph, first), bl

    def _axis(self, i: int, spec: AxisPulseSpec, raw: RawSteps, flip: Flips, flags: B | None,
              end_ns: int, final: bool) -> AxisSteps:
        st = self.state[i]
        merger = self.merger[i]
        t_ns = self.timeline.to_ns(raw.t_s, raw.phase)
        backlash = flags if flags is not None else np.zeros(t_ns.shape, np.bool_)
        train = Train(t_ns, raw.direction, raw.phase, backlash)
        dir_idx: I64 | None = None
        if self.layout.mode == "exact" and (not merger.idle or (merger.offsets_s.size and flip[0].size)):
            train = merger.merge(train, self.timeline.to_s(flip[0], flip[2]), flip[1], flip[2], end_ns, final)
        else:
            dir_idx = self._run_changes(raw, st)
        if train.t_ns.size == 0:
            return AxisSteps.empty()
        dir_idx, dt = self._enforce(i, spec, train, dir_idx)
        level = ((train.direction[dir_idx] > 0) ^ spec.direction_invert).astype(np.uint8)
        dir_t = train.t_ns[dir_idx] - spec.dir_setup_ns
        check_spacing(spec, train.t_ns, dt, train.phase, st.last_t_ns, self.rep)
        st.last_t_ns = int(train.t_ns[-1])
        st.last_dir = int(train.direction[-1])
        return AxisSteps(train.t_ns, train.direction, train.phase, train.backlash, dir_t, level)

    @staticmethod
    def _run_changes(raw: RawSteps, st: _AxisState) -> I64:
        """Indices of the steps where the direction changes, from the runs (all steps of a run share it)."""
        if raw.run_dir.size == 0:
            return np.zeros(0, np.int64)
        prev = np.empty_like(raw.run_dir)
        prev[0] = st.last_dir
        prev[1:] = raw.run_dir[:-1]
        changes: I64 = raw.run_first[raw.run_dir != prev]
        return changes

    def _enforce(self, i: int, spec: AxisPulseSpec, train: Train, idx: I64 | None) -> tuple[I64, I64]:
        """Delay steps after direction changes, keep times strictly increasing; (change indices, diff)."""
        st = self.state[i]
        t_ns, direction = train.t_ns, train.direction
        if idx is None:
            prev = np.empty_like(direction)
            prev[0] = st.last_dir
            prev[1:] = direction[:-1]
            idx = np.flatnonzero(direction != prev)
        gap = spec.pulse_width_ns + spec.dir_setup_ns
        for k in idx.tolist():
            if k > 0:
                before = int(t_ns[k - 1])
            else:  # at the very start, a virtual step at -pulse_width: DIR may change at t = 0
                before = st.last_t_ns if st.last_t_ns is not None else -spec.pulse_width_ns
            if t_ns[k] < before + gap:
                self.rep.emit(diag.DIR_SETUP_DELAY, spec.name, int(train.phase[k]),
                              f"step delayed by {before + gap - int(t_ns[k])} ns for the direction set-up time")
                t_ns[k] = before + gap
        dt = np.diff(t_ns)
        first_ok = st.last_t_ns is None or int(t_ns[0]) > st.last_t_ns
        if not first_ok or (dt.size and int(dt.min()) <= 0):  # rare: equal ns after rounding
            base = np.arange(t_ns.shape[0], dtype=np.int64)
            u = t_ns - base
            if st.last_t_ns is not None:
                u[0] = max(int(u[0]), st.last_t_ns + 1)
            t_ns[:] = np.maximum.accumulate(u) + base
            dt = np.diff(t_ns)
        return idx, dt
