"""The pulse generator: Trajectory + MachineModel -> stream of :class:`StepChunk`.

Per window (a group of trajectory segments in exact mode, of interpolation periods
in interp mode) every axis' raw steps (:mod:`.solve` or :mod:`.interp`) go through:

1. **reversals**: a stretch of motion whose direction differs from the axis' last
   one starts at the reversal instant ``t_r``;
2. **reversal delay** (SZGH Axis P68): a pause of ``reversal_delay_s`` is inserted
   into the time line at ``t_r`` (coinciding reversals pause once, the longest);
   every later event of every axis moves by it;
3. **backlash**: ``backlash_steps`` pulses in the new direction, starting at ``t_r``
   (mode A at a constant rate, mode B ramped), merged into the axis' stream; pulses
   past the window's end carry into the next;
4. rounding to integer nanoseconds; a step after a direction change is delayed, if
   needed, to ``previous step + pulse_width_ns + dir_setup_ns`` (W0705), and the
   direction line changes ``dir_setup_ns`` before it;
5. limit checks (E0701/E0702) and the chunk.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

from cncc import diagnostics as diag
from cncc.backends.pulses.chunk import AxisSteps, PulseLayout, StepChunk
from cncc.backends.pulses.interp import SZGH_PERIOD_S, interp_window, period_count
from cncc.backends.pulses.limits import Reporter, check_soft_limits, check_spacing
from cncc.backends.pulses.solve import F64, I64, RawSteps, exact_axis_steps, segment, speed_max, windows
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
    pend_t: I64 = field(default_factory=lambda: np.zeros(0, np.int64))
    pend_dir: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int8))  # type: ignore[type-arg]
    pend_phase: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int32))  # type: ignore[type-arg]


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
    post = _Post(layout, rep)
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


class _Post:
    """Steps 1-5 of the module docstring, with the state carried between windows."""

    def __init__(self, layout: PulseLayout, rep: Reporter) -> None:
        self.layout = layout
        self.rep = rep
        self.state = [_AxisState() for _ in layout.specs]
        self.burst = [backlash_offsets_s(s) for s in layout.specs]
        self.offset_s = 0.0
        self.index = 0
        self.t_start_ns = 0

    def finish(self, raws: list[RawSteps], t_end_s: float, final: bool) -> StepChunk:
        specs = self.layout.specs
        flips = [self._flips(raw, st) for raw, st in zip(raws, self.state, strict=True)]
        ev_t, ev_cum = self._pauses(flips)
        warp = _Warp(self.offset_s, ev_t, ev_cum)
        end_ns = int(np.rint(warp(np.array([t_end_s]))[0] * 1e9))
        axes = []
        for i, spec in enumerate(specs):
            axes.append(self._axis(i, spec, raws[i], flips[i], warp, end_ns, final))
        self.offset_s += float(ev_cum[-1]) if ev_cum.size else 0.0
        horizon = FAR_FUTURE_NS if final else end_ns - self.layout.max_dir_setup_ns - 1
        chunk = StepChunk(self.layout, self.index, self.t_start_ns, end_ns, horizon, tuple(axes))
        self.index += 1
        self.t_start_ns = end_ns
        return chunk

    @staticmethod
    def _flips(raw: RawSteps, st: _AxisState) -> tuple[F64, np.ndarray, np.ndarray]:  # type: ignore[type-arg]
        if raw.run_dir.size == 0:
            return np.zeros(0), np.zeros(0, np.int8), np.zeros(0, np.int32)
        prev = np.empty_like(raw.run_dir)
        prev[0] = st.last_motion
        prev[1:] = raw.run_dir[:-1]
        sel = raw.run_dir != prev
        st.last_motion = int(raw.run_dir[-1])
        return raw.run_t_s[sel], raw.run_dir[sel], raw.run_phase[sel]

    def _pauses(self, flips: list[tuple[F64, np.ndarray, np.ndarray]]) -> tuple[F64, F64]:  # type: ignore[type-arg]
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

    def _axis(self, i: int, spec: AxisPulseSpec, raw: RawSteps, flip: tuple[F64, np.ndarray, np.ndarray],  # type: ignore[type-arg]
              warp: _Warp, end_ns: int, final: bool) -> AxisSteps:
        st = self.state[i]
        t_ns = np.rint(warp(raw.t_s) * 1e9).astype(np.int64)
        direction, phase = raw.direction, raw.phase
        backlash = np.zeros(t_ns.shape, dtype=np.bool_)
        burst, burst_len_s = self.burst[i]
        if (burst.size and flip[0].size) or st.pend_t.size:
            parts_t, parts_d, parts_p, parts_b = [t_ns, st.pend_t], [direction, st.pend_dir], [phase, st.pend_phase], \
                [backlash, np.ones(st.pend_t.shape, np.bool_)]
            starts = np.zeros(0)
            if burst.size and flip[0].size:
                starts = warp(flip[0], "left")
                bt = np.rint((starts[:, None] + burst[None, :]) * 1e9).astype(np.int64).ravel()
                parts_t.append(bt)
                parts_d.append(np.repeat(flip[1], burst.size))
                parts_p.append(np.repeat(flip[2], burst.size))
                parts_b.append(np.ones(bt.shape, np.bool_))
            t_ns, direction = np.concatenate(parts_t), np.concatenate(parts_d)
            phase, backlash = np.concatenate(parts_p), np.concatenate(parts_b)
            order = np.argsort(t_ns, kind="stable")
            t_ns, direction, phase, backlash = t_ns[order], direction[order], phase[order], backlash[order]
            for t0 in starts.tolist():
                superpose(t_ns, direction, backlash, round(t0 * 1e9), round((t0 + burst_len_s) * 1e9))
            carry = backlash & (t_ns >= end_ns) if not final else np.zeros(t_ns.shape, np.bool_)
            st.pend_t, st.pend_dir, st.pend_phase = t_ns[carry], direction[carry], phase[carry]
            if carry.any():
                keep = ~carry
                t_ns, direction, phase, backlash = t_ns[keep], direction[keep], phase[keep], backlash[keep]
        if t_ns.size == 0:
            return AxisSteps.empty()
        dir_idx = self._enforce(i, spec, t_ns, direction, phase)
        level = ((direction[dir_idx] > 0) ^ spec.direction_invert).astype(np.uint8)
        dir_t = t_ns[dir_idx] - spec.dir_setup_ns
        check_spacing(spec, t_ns, phase, st.last_t_ns, self.rep)
        st.last_t_ns = int(t_ns[-1])
        st.last_dir = int(direction[-1])
        return AxisSteps(t_ns, direction, phase, backlash, dir_t, level)

    def _enforce(self, i: int, spec: AxisPulseSpec, t_ns: I64, direction: np.ndarray,  # type: ignore[type-arg]
                 phase: np.ndarray) -> I64:  # type: ignore[type-arg]
        """Delay steps after direction changes, keep times strictly increasing; change indices."""
        st = self.state[i]
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
                self.rep.emit(diag.DIR_SETUP_DELAY, spec.name, int(phase[k]),
                              f"step delayed by {before + gap - int(t_ns[k])} ns for the direction set-up time")
                t_ns[k] = before + gap
        base = np.arange(t_ns.shape[0], dtype=np.int64)
        u = t_ns - base
        if st.last_t_ns is not None:
            u[0] = max(int(u[0]), st.last_t_ns + 1)
        t_ns[:] = np.maximum.accumulate(u) + base
        return idx


def superpose(t_ns: I64, direction: np.ndarray, backlash: np.ndarray, t0_ns: int, t1_ns: int) -> None:  # type: ignore[type-arg]
    """Re-time, in place, the backlash burst ``[t0_ns, t1_ns]`` and the commanded steps inside it.

    The drive sees the sum of two motions, the commanded one and the compensation, so
    its steps are where the *sum* of the two positions crosses the step boundaries,
    not the union of two step trains (which could put two pulses a nanosecond apart).
    Each train's position is taken as linear between its own crossings (step ``k`` at
    ``k - 1/2``); the combined steps are the crossings of the sum.  Labels (phase,
    backlash flag) stay with the steps in their merged order.
    """
    lo = int(np.searchsorted(t_ns, t0_ns, side="left"))
    hi = int(np.searchsorted(t_ns, t1_ns, side="right"))
    if hi - lo < 2:
        return
    seg_b = backlash[lo:hi]
    if seg_b.all() or not seg_b.any() or np.ptp(direction[lo:hi]) != 0:
        return  # nothing to combine, or a further reversal inside: keep the plain merge
    t = t_ns[lo:hi].astype(np.float64)
    knots_c = [float(t0_ns), *t[~seg_b].tolist()]
    n_c = int((~seg_b).sum())
    nxt = hi < t_ns.shape[0] and not backlash[hi] and direction[hi] == direction[lo]
    if nxt:
        knots_c.append(float(t_ns[hi]))
    levels_c = np.concatenate([[0.0], np.arange(n_c) + 0.5, [n_c + 0.5] if nxt else []])
    n_b = int(seg_b.sum())
    knots_b = np.array([float(t0_ns), *t[seg_b].tolist(), float(max(t1_ns, int(t[-1])))])
    levels_b = np.concatenate([[0.0], np.arange(n_b) + 0.5, [float(n_b)]])
    grid = np.unique(np.concatenate([knots_c, knots_b]))
    total = np.interp(grid, np.array(knots_c), levels_c) + np.interp(grid, knots_b, levels_b)
    total = np.maximum.accumulate(total)
    new = np.interp(np.arange(n_c + n_b) + 0.5, total, grid)
    t_ns[lo:hi] = np.rint(new).astype(np.int64)
