"""Pauses in the pulse time line: reversal delays and program events.

The planner's trajectory time ``t`` (seconds) becomes machine time (integer ns) as ::

    T(t, phase) = rint(t * 1e9) + R(t) + E(phase)

* ``R(t)``: the reversal delays (SZGH Axis P68) at instants up to ``t``.  An axis
  reverses where a stretch of motion that makes steps goes the other way than the
  axis' last one (the start of that stretch, ``t_r``); the pause is the axis'
  ``reversal_delay_s``, and reversals of several axes at the same nanosecond pause
  once, for the longest delay.  :class:`ReversalPauses` lists them for a whole
  trajectory (:func:`exact_reversals`, :func:`interp_reversals`), so the timing report
  can count the same pauses the pulses have (the driver passes them to both).
* ``E(phase)``: the pauses of commands without motion (dwells, tool changes, spindle
  ramps, stops, waits; the driver takes their times from the timing backend's event
  rules).  A pause of command ``c`` is inserted before the first phase of a later
  command, so every event of a later phase, on every axis, moves by it; a pause after
  the last phase only moves the end of the stream.  Phases, not instants, decide, so
  a step exactly at the boundary stays with its own command.

Both are integers, so a step time minus its pause offset is the rounded trajectory
time exactly.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np
import numpy.typing as npt

from cncc.backends.pulses.interp import period_count, period_runs
from cncc.backends.pulses.solve import F64, I8, I32, I64, Segments, axis_runs
from cncc.backends.pulses.spec import AxisPulseSpec
from cncc.ir.trajectory import Trajectory

ReversalKey = tuple[str, float, int]
"""What reversal instants depend on besides the trajectory and the axes: (mode, period_s, budget)."""

Side = Literal["left", "right"]


@dataclass(frozen=True, slots=True)
class ReversalPauses:
    """The reversal pauses of a trajectory on a machine; arrays of shape ``(r,)``, by time.

    ``t_s`` are distinct instants (trajectory time), ``ns`` the pause at each,
    ``phase`` the phase it falls in, ``axis`` the axis whose delay it is.
    """

    t_s: F64
    ns: I64
    phase: I32
    axis: tuple[str, ...]
    key: ReversalKey

    @property
    def total_ns(self) -> int:
        return int(self.ns.sum())

    def by_command(self, cmd_index: I64) -> list[tuple[int, int, str]]:
        """``(command index, ns, "reversal X Y")`` per command with reversal pauses, in order."""
        if self.ns.size == 0:
            return []
        cmds = cmd_index[np.clip(self.phase, 0, max(cmd_index.shape[0] - 1, 0))].tolist()
        out: dict[int, tuple[int, list[str]]] = {}
        for cmd, ns, axis in zip(cmds, self.ns.tolist(), self.axis, strict=True):
            total, axes = out.get(cmd, (0, []))
            if axis not in axes:
                axes.append(axis)
            out[cmd] = (total + ns, axes)
        return [(cmd, ns, "reversal " + " ".join(axes)) for cmd, (ns, axes) in sorted(out.items())]

    @staticmethod
    def none(key: ReversalKey) -> ReversalPauses:
        return ReversalPauses(np.zeros(0), np.zeros(0, np.int64), np.zeros(0, np.int32), (), key)


def delay_ns(spec: AxisPulseSpec) -> int:
    return round(spec.reversal_delay_s * 1e9) if spec.reversal_delay_s > 0 else 0


def flips(run_t_s: F64, run_dir: I8, run_phase: I32, last_motion: int) -> tuple[F64, I8, I32]:
    """The runs whose direction differs from the one before (the first compared with ``last_motion``)."""
    if run_dir.size == 0:
        return np.zeros(0), np.zeros(0, np.int8), np.zeros(0, np.int32)
    prev = np.empty_like(run_dir)
    prev[0] = last_motion
    prev[1:] = run_dir[:-1]
    sel = run_dir != prev
    return run_t_s[sel], run_dir[sel], run_phase[sel]


def merge_reversals(found: Sequence[tuple[str, int, F64, I32]], key: ReversalKey) -> ReversalPauses:
    """One pause per distinct nanosecond, the longest delay of the axes reversing there.

    ``found``: per axis ``(name, delay ns, reversal instants, their phases)``.
    """
    found = [f for f in found if f[1] > 0 and f[2].size]
    if not found:
        return ReversalPauses.none(key)
    t_all = np.concatenate([f[2] for f in found])
    ph_all = np.concatenate([f[3] for f in found]).astype(np.int32)
    d_all = np.concatenate([np.full(f[2].shape, f[1], np.int64) for f in found])
    ax_all = np.concatenate([np.full(f[2].shape, k, np.int64) for k, f in enumerate(found)])
    order = np.argsort(t_all, kind="stable")
    t_all, ph_all, d_all, ax_all = t_all[order], ph_all[order], d_all[order], ax_all[order]
    group = np.cumsum(np.diff(np.rint(t_all * 1e9), prepend=np.nan) != 0) - 1
    starts = np.flatnonzero(np.diff(group, prepend=-1))
    longest = np.lexsort((-d_all, group))[starts]  # the longest delay of each group first
    names = tuple(found[int(k)][0] for k in ax_all[longest].tolist())
    return ReversalPauses(t_all[starts], d_all[longest], ph_all[longest], names, key)


def exact_reversals(traj: Trajectory, seg: Segments, wins: Sequence[tuple[int, int]],
                    specs: Sequence[AxisPulseSpec], cols: Sequence[int], key: ReversalKey) -> ReversalPauses:
    """Reversal pauses of the exact mode: the runs of :func:`~.solve.axis_runs` over all windows."""
    found: list[tuple[str, int, F64, I32]] = []
    for spec, i in zip(specs, cols, strict=True):
        d = delay_ns(spec)
        if d <= 0:
            continue
        parts = [axis_runs(traj, seg, lo, hi, i, spec) for lo, hi in wins]
        if not parts:
            continue
        t, _, ph = flips(np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts]),
                         np.concatenate([p[2] for p in parts]), 1)
        found.append((spec.name, d, t, ph))
    return merge_reversals(found, key)


INTERP_WINDOW_PERIODS = 1 << 16


def interp_reversals(traj: Trajectory, specs: Sequence[AxisPulseSpec], cols: Sequence[int], period_s: float,
                     key: ReversalKey) -> ReversalPauses:
    """Reversal pauses of the interpolation mode: periods whose net count changes sign."""
    sel = [(spec, i) for spec, i in zip(specs, cols, strict=True) if delay_ns(spec) > 0]
    if not sel or traj.phase_count == 0:
        return ReversalPauses.none(key)
    cs = [i for _, i in sel]
    sub = traj.select_axes(cs)
    sub_specs = tuple(spec for spec, _ in sel)
    runs: list[list[tuple[F64, I8, I32]]] = [[] for _ in sel]
    total = period_count(traj, period_s)
    for k0 in range(0, total, INTERP_WINDOW_PERIODS):
        t, mid, per_axis = period_runs(sub, sub_specs, k0, min(k0 + INTERP_WINDOW_PERIODS, total), period_s)
        for acc, (mv, _, direction) in zip(runs, per_axis, strict=True):
            acc.append((t[mv], direction, mid[mv]))
    found: list[tuple[str, int, F64, I32]] = []
    for (spec, _), acc in zip(sel, runs, strict=True):
        if not acc:
            continue
        t_f, _, ph = flips(np.concatenate([a[0] for a in acc]), np.concatenate([a[1] for a in acc]),
                           np.concatenate([a[2] for a in acc]), 1)
        found.append((spec.name, delay_ns(spec), t_f, ph))
    return merge_reversals(found, key)


@dataclass(frozen=True, slots=True)
class TimeLine:
    """Trajectory time and phase -> machine time in ns (module docstring)."""

    rev_t_s: F64  # (r,) reversal instants, sorted
    rev_cum_ns: I64  # (r + 1,) reversal pause before each position
    ev_phase: I64  # (e,) phase each event pause goes before, sorted
    ev_cum_ns: I64  # (e + 1,)

    @staticmethod
    def of(rev: ReversalPauses, cmd_index: I64, pauses: Sequence[tuple[int, int]]) -> TimeLine:
        """``pauses``: ``(command index, ns)`` of the events; ``cmd_index`` the trajectory's."""
        rev_cum = np.concatenate([[0], np.cumsum(rev.ns)]).astype(np.int64)
        kept = [(c, ns) for c, ns in pauses if ns > 0]
        if not kept:
            return TimeLine(rev.t_s, rev_cum, np.zeros(0, np.int64), np.zeros(1, np.int64))
        cmd = np.array([c for c, _ in kept], np.int64)
        ns = np.array([n for _, n in kept], np.int64)
        running = np.maximum.accumulate(cmd_index) if cmd_index.size else cmd_index
        before = np.searchsorted(running, cmd, side="right").astype(np.int64)  # first phase of a later command
        order = np.argsort(before, kind="stable")
        return TimeLine(rev.t_s, rev_cum, before[order], np.concatenate([[0], np.cumsum(ns[order])]).astype(np.int64))

    def reversal_ns(self, t_s: F64, side: Side = "right") -> I64 | int:
        """Reversal pause up to each of the sorted ``t_s`` (``side="left"``: strictly before)."""
        return _cumulative(self.rev_t_s, self.rev_cum_ns, t_s, side)

    def event_ns(self, phase: I32 | I64) -> I64 | int:
        """Event pause before each of the non-decreasing ``phase``."""
        return _cumulative(self.ev_phase, self.ev_cum_ns, phase, "right")

    def to_ns(self, t_s: F64, phase: I32) -> I64:
        """Machine times of steps at sorted trajectory times ``t_s`` in phases ``phase``."""
        t = t_s * 1e9
        out = np.rint(t, out=t).astype(np.int64)
        if t_s.size == 0:
            return out
        off_r, off_e = self.reversal_ns(t_s), self.event_ns(phase)
        if isinstance(off_r, int) and isinstance(off_e, int):
            if off_r + off_e:
                out += off_r + off_e
            return out
        out += off_r
        out += off_e
        return out

    def to_s(self, t_s: F64, phase: I32) -> F64:
        """Machine times (float s) of reversal instants, before their own pause (backlash bursts start there)."""
        off = np.asarray(self.reversal_ns(t_s, "left") + self.event_ns(phase), dtype=np.float64)
        return t_s + off / 1e9

    def window_end(self, t_end_s: float, phase_end: int, final: bool) -> tuple[int, int, int]:
        """(machine time of a window's end, reversal pause and event pause up to it).

        A window's steps lie before ``t_end_s`` in phases up to ``phase_end``; the next
        window's at or after it in phases from ``phase_end`` on, so the end separates them.
        The last window's end takes every pause (``phase_end`` = the phase count).
        """
        t = np.array([t_end_s])
        rev = int(np.asarray(self.reversal_ns(t, "right" if final else "left")).reshape(-1)[0])
        ev = int(self.ev_cum_ns[-1]) if final else int(np.asarray(self.event_ns(np.array([phase_end]))).reshape(-1)[0])
        return int(np.rint(t_end_s * 1e9)) + rev + ev, rev, ev


def _cumulative(at: npt.NDArray[np.float64] | I64, cum: I64, x: npt.NDArray[np.generic], side: Side) -> I64 | int:
    """``cum[#(at <= x)]`` (``side="left"``: ``at < x``) for sorted ``x``; an int when constant over ``x``."""
    if at.size == 0 or x.size == 0:
        return int(cum[0])
    lo = int(np.searchsorted(at, x[0], side="left"))
    hi = int(np.searchsorted(at, x[-1], side=side))
    if lo >= hi:
        return int(cum[lo])
    idx = np.searchsorted(at[lo:hi], x, side=side)
    idx += lo
    res: I64 = cum[idx]
    return res
