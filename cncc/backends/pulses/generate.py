"""The pulse generator: Trajectory + MachineModel -> stream of :class:`StepChunk`.

Per window (a group of trajectory segments in exact mode, of interpolation periods
in interp mode) every axis' raw steps (:mod:`.solve` or :mod:`.interp`) go through:

1. **reversals**: a stretch of motion whose direction differs from the axis' last
   one starts at the reversal instant ``t_r``;
2. **reversal delay** (SZGH Axis P68): a pause of ``reversal_delay_s`` is inserted
   into the time line at ``t_r`` (coinciding reversals pause once, the longest);
   every later event of every axis moves by it;
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
from typing import Literal

import numpy as np

from cncc import diagnostics as diag
from cncc.backends.pulses.backlash import B, BurstMerger, PeriodBacklash, Train, add_period_counts
from cncc.backends.pulses.chunk import AxisSteps, PulseLayout, StepChunk
from cncc.backends.pulses.interp import SZGH_PERIOD_S, interp_window, period_count
from cncc.backends.pulses.limits import Reporter, check_soft_limits, check_spacing
from cncc.backends.pulses.solve import F64, I8, I32, I64, RawSteps, exact_axis_steps, segment, speed_max, windows
from cncc.backends.pulses.spec import AxisPulseSpec, axis_spec, backlash_offsets_s
from cncc.diagnostics import DiagnosticSink
from cncc.ir.machine import Axis, MachineModel
from cncc.ir.trajectory import Trajectory
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
                    chunk_steps: int = DEFAULT_CHUNK_STEPS, period_s: float = SZGH_PERIOD_S) -> Iterator[StepChunk]:
    """Stream the step/dir pulses of ``traj`` on ``machine`` in chunks of about ``chunk_steps`` steps.

    ``mode`` is ``"exact"`` (every step at its crossing time) or ``"interp"`` (counted per
    ``period_s`` and spread evenly, as the SZGH interpolator).  ``spans[cmd_index]`` locates
    the command responsible for a diagnostic in ``sink``.
    """
    if mode not in MODES:
        raise ValueError(f"pulse mode must be one of {MODES}, not {mode!r}")
    specs, cols = build_specs(traj, machine, sink)
    layout = PulseLayout(specs, mode)
    rep = Reporter(traj, spans, sink)
    check_soft_limits(traj, specs, cols, rep)
    post = _Post(layout, rep, period_s)
    budget = max(int(chunk_steps), 16)
    if traj.phase_count == 0:
        yield post.finish([RawSteps.empty() for _ in specs], 0.0, True)
        return
    if mode == "exact":
        yield from _exact(traj, specs, cols, post, budget)
    else:
        yield from _interp(traj, specs, cols, post, budget, period_s)


def _steps_per_mm(traj: Trajectory, specs: tuple[AxisPulseSpec, ...], cols: tuple[int, ...]) -> F64:
    r = np.zeros(len(traj.axes))
    for spec, i in zip(specs, cols, strict=True):
        r[i] = spec.rate_factor()
    return r


def _exact(traj: Trajectory, specs: tuple[AxisPulseSpec, ...], cols: tuple[int, ...], post: _Post,
           budget: int) -> Iterator[StepChunk]:
    seg = segment(traj, _steps_per_mm(traj, specs, cols), budget)
    wins = windows(seg, budget)
    for w, (lo, hi) in enumerate(wins):
        raws = [exact_axis_steps(traj, seg, lo, hi, i, spec) for spec, i in zip(specs, cols, strict=True)]
        t_end = float(traj.t0_s[seg.phase[hi - 1]] + seg.tb_s[hi - 1])
        yield post.finish(raws, t_end, w == len(wins) - 1)


def _interp(traj: Trajectory, specs: tuple[AxisPulseSpec, ...], cols: tuple[int, ...], post: _Post,
            budget: int, period_s: float) -> Iterator[StepChunk]:
    r = _steps_per_mm(traj, specs, cols)
    vmax = speed_max(traj.v0_mm_s, traj.a0_mm_s2, traj.j_mm_s3, traj.duration_s[:, None]).max(axis=0)
    per_period = float((r * vmax).sum() * period_s) + 1.0
    k_win = int(min(max(budget / per_period, 1.0), 1 << 20))
    total = period_count(traj, period_s)
    sub = Trajectory(traj.t0_s, traj.duration_s, traj.p0_mm[:, cols], traj.v0_mm_s[:, cols],
                     traj.a0_mm_s2[:, cols], traj.j_mm_s3[:, cols], traj.cmd_index, traj.limit,
                     tuple(traj.axes[i] for i in cols))
    for k0 in range(0, max(total, 1), k_win):
        k1 = min(k0 + k_win, total)
        raws = interp_window(sub, specs, k0, k1, period_s)
        yield post.finish(raws, k1 * period_s, k1 >= total)


@dataclass(frozen=True, slots=True)
class _Warp:
    """Time line with the reversal pauses inserted: ``t -> t + pauses at or before t``."""

    offset_s: float
    ev_t_s: F64  # distinct pause instants, sorted
    ev_cum_s: F64  # (e + 1,) cumulative pause before each instant

    def __call__(self, t_s: F64, side: Literal["left", "right"] = "right") -> F64:
        if self.ev_t_s.size == 0:
            return t_s + self.offset_s
        return t_s + self.offset_s + self.ev_cum_s[np.searchsorted(self.ev_t_s, t_s, side=side)]

    def to_ns(self, t_s: F64) -> I64:
        if self.ev_t_s.size == 0:
            t = t_s * 1e9
            t += self.offset_s * 1e9
        else:
            t = self(t_s) * 1e9
        return np.rint(t, out=t).astype(np.int64)


Flips = tuple[F64, I8, I32]  # reversal instants (s), new directions, phases


class _Post:
    """Steps 1-5 of the module docstring, with the state carried between windows."""

    def __init__(self, layout: PulseLayout, rep: Reporter, period_s: float) -> None:
        self.layout = layout
        self.rep = rep
        self.period_s = period_s
        self.state = [_AxisState() for _ in layout.specs]
        bursts = [backlash_offsets_s(s) for s in layout.specs]
        self.merger = [BurstMerger(off, length) for off, length in bursts]
        self.per_period = [PeriodBacklash.of(off, period_s) for off, _ in bursts]
        self.offset_s = 0.0
        self.index = 0
        self.t_start_ns = 0
        self.total_pause_s = 0.0

    def finish(self, raws: list[RawSteps], t_end_s: float, final: bool) -> StepChunk:
        specs = self.layout.specs
        flips = [self._flips(raw, st) for raw, st in zip(raws, self.state, strict=True)]
        flags: list[B | None] = [None] * len(specs)
        if self.layout.mode == "interp":
            for i, raw in enumerate(raws):
                raws[i], flags[i] = self._period_backlash(i, raw, flips[i], t_end_s, final)
        ev_t, ev_cum = self._pauses(flips)
        warp = _Warp(self.offset_s, ev_t, ev_cum)
        end_ns = int(np.rint(warp(np.array([t_end_s]))[0] * 1e9))
        axes = [self._axis(i, spec, raws[i], flips[i], flags[i], warp, end_ns, final) for i, spec in enumerate(specs)]
        pause = float(ev_cum[-1]) if ev_cum.size else 0.0
        self.offset_s += pause
        self.total_pause_s += pause
        horizon = FAR_FUTURE_NS if final else end_ns - self.layout.max_dir_setup_ns - 1
        holds = [m.hold_ns for m in self.merger if m.hold_ns is not None]
        if holds:
            horizon = min(horizon, min(holds) - self.layout.max_dir_setup_ns - 1)
        chunk = StepChunk(self.layout, self.index, self.t_start_ns, end_ns, horizon, tuple(axes),
                          round(self.total_pause_s * 1e9))
        self.index += 1
        self.t_start_ns = end_ns
        return chunk

    @staticmethod
    def _flips(raw: RawSteps, st: _AxisState) -> Flips:
        if raw.run_dir.size == 0:
            return np.zeros(0), np.zeros(0, np.int8), np.zeros(0, np.int32)
        prev = np.empty_like(raw.run_dir)
        prev[0] = st.last_motion
        prev[1:] = raw.run_dir[:-1]
        sel = raw.run_dir != prev
        st.last_motion = int(raw.run_dir[-1])
        return raw.run_t_s[sel], raw.run_dir[sel], raw.run_phase[sel]

    def _pauses(self, flips: list[Flips]) -> tuple[F64, F64]:
        """Pause instants (sorted, distinct) and cumulative pause before each position."""
        ts: list[F64] = []
        ds: list[F64] = []
        for spec, (t, _, _) in zip(self.layout.specs, flips, strict=True):
            if spec.reversal_delay_s > 0 and t.size:
                ts.append(t)
                ds.append(np.full(t.shape, spec.reversal_delay_s))
        if not ts:
            return np.zeros(0), np.zeros(0)
        t_all, d_all = np.concatenate(ts), np.concatenate(ds)
        order = np.argsort(t_all, kind="stable")
        t_all, d_all = t_all[order], d_all[order]
        key = np.rint(t_all * 1e9)
        starts = np.flatnonzero(np.diff(key, prepend=np.nan) != 0)
        t_u = t_all[starts]
        d_u = np.maximum.reduceat(d_all, starts)
        return t_u, np.concatenate([[0.0], np.cumsum(d_u)])

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
        run_t_s: F64 = keys.astype(np.float64) * self.period_s
        return RawSteps(t_s, d, ph, run_t_s, run_dir, run_ph, first), bl

    def _axis(self, i: int, spec: AxisPulseSpec, raw: RawSteps, flip: Flips, flags: B | None, warp: _Warp,
              end_ns: int, final: bool) -> AxisSteps:
        st = self.state[i]
        merger = self.merger[i]
        t_ns = warp.to_ns(raw.t_s)
        backlash = flags if flags is not None else np.zeros(t_ns.shape, np.bool_)
        train = Train(t_ns, raw.direction, raw.phase, backlash)
        dir_idx: I64 | None = None
        if self.layout.mode == "exact" and (not merger.idle or (merger.offsets_s.size and flip[0].size)):
            train = merger.merge(train, warp(flip[0], "left"), flip[1], flip[2], end_ns, final)
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
