"""Limit checks on trajectories and pulse trains; diagnostics that name the command.

* E0701: consecutive steps of an axis closer than ``1 / max_step_rate_hz`` (with the
  1 ns tolerance of integer-nanosecond times);
* E0702: closer than the minimum spacing ``2 * pulse_width_ns``;
* E0703: a phase takes an axis beyond its soft limits (checked on the polynomial's
  extremes, so a crossing between samples is not missed);
* W0705: a step delayed to respect the direction set-up time.

Each (code, axis, command) is reported once, with the worst value seen in the first
window that shows it; at most :data:`MAX_PER_CODE` per code.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from cncc import diagnostics as diag
from cncc.backends.pulses.blocks import blockwise
from cncc.backends.pulses.spec import AxisPulseSpec
from cncc.diagnostics import DiagnosticSink
from cncc.ir.trajectory import Trajectory, position_bounds
from cncc.source import NO_SPAN, Span

MAX_PER_CODE = 100
SOFT_LIMIT_TOL_MM = 1e-9


class Reporter:
    """Turns violations found on phases into deduplicated diagnostics."""

    def __init__(self, traj: Trajectory, spans: Sequence[Span] | None, sink: DiagnosticSink | None) -> None:
        self.cmd_index = traj.cmd_index
        self.spans = spans
        self.sink = sink
        self.seen: set[tuple[str, str, int]] = set()
        self.per_code: dict[str, int] = {}

    def span_of(self, cmd: int) -> Span:
        if self.spans is not None and 0 <= cmd < len(self.spans):
            return self.spans[cmd]
        return NO_SPAN

    def cmd_of_phase(self, phase: int) -> int:
        if 0 <= phase < self.cmd_index.shape[0]:
            return int(self.cmd_index[phase])
        return -1

    def emit(self, code: str, axis: str, phase: int, message: str) -> None:
        if self.sink is None:
            return
        cmd = self.cmd_of_phase(phase)
        key = (code, axis, cmd)
        if key in self.seen or self.per_code.get(code, 0) >= MAX_PER_CODE:
            return
        self.seen.add(key)
        self.per_code[code] = self.per_code.get(code, 0) + 1
        self.sink.emit(code, self.span_of(cmd), f"axis {axis}, command #{cmd}: {message}")

    def emit_each_command(self, code: str, axis: str, phases: npt.NDArray[np.int32],
                          values: npt.NDArray[np.float64], worst_is_min: bool, describe: str) -> None:
        """One diagnostic per command among ``phases``; ``describe`` is formatted with the worst value."""
        if self.sink is None or phases.size == 0:
            return
        last = max(self.cmd_index.shape[0] - 1, 0)
        cmds = self.cmd_index[np.clip(phases, 0, last)] if self.cmd_index.size else phases
        for cmd in np.unique(cmds).tolist():
            sel = cmds == cmd
            worst = float(values[sel].min() if worst_is_min else values[sel].max())
            first_phase = int(phases[np.argmax(sel)])
            self.emit(code, axis, first_phase, describe.format(worst))


def check_soft_limits(traj: Trajectory, specs: tuple[AxisPulseSpec, ...], cols: tuple[int, ...],
                      rep: Reporter) -> None:
    """E0703 for every command whose motion leaves an axis' soft-limit range."""
    if traj.phase_count == 0:
        return
    if all(spec.soft_min_mm is None and spec.soft_max_mm is None for spec in specs):
        return
    box_lo, box_hi = blockwise(position_bounds, traj)  # exact extremes, arcs included
    for spec, i in zip(specs, cols, strict=True):
        if spec.soft_min_mm is None and spec.soft_max_mm is None:
            continue
        lo, hi = box_lo[:, i], box_hi[:, i]
        if spec.soft_min_mm is not None:
            bad = np.flatnonzero(lo < spec.soft_min_mm - SOFT_LIMIT_TOL_MM).astype(np.int32)
            rep.emit_each_command(diag.SOFT_LIMIT, spec.name, bad, lo[bad], True,
                                  "reaches {:.4f}, below the soft limit " + f"{spec.soft_min_mm:.4f}")
        if spec.soft_max_mm is not None:
            bad = np.flatnonzero(hi > spec.soft_max_mm + SOFT_LIMIT_TOL_MM).astype(np.int32)
            rep.emit_each_command(diag.SOFT_LIMIT, spec.name, bad, hi[bad], False,
                                  "reaches {:.4f}, above the soft limit " + f"{spec.soft_max_mm:.4f}")


def check_spacing(spec: AxisPulseSpec, t_ns: npt.NDArray[np.int64], dt_ns: npt.NDArray[np.int64],
                  phase: npt.NDArray[np.int32], last_t_ns: int | None, rep: Reporter) -> None:
    """E0701 and E0702 on the final step times of one axis in one window (``dt_ns = diff(t_ns)``)."""
    if t_ns.size == 0:
        return
    rate_dt_ns = 1e9 / spec.max_step_rate_hz - 1.0 if spec.max_step_rate_hz > 0 else 0.0
    least = max(rate_dt_ns, float(spec.min_spacing_ns))
    first_ok = last_t_ns is None or int(t_ns[0]) - last_t_ns >= least
    if first_ok and (dt_ns.size == 0 or int(dt_ns.min()) >= least):
        return
    if last_t_ns is None:
        dt = dt_ns
        ph = phase[1:]
    else:
        dt = np.concatenate([[int(t_ns[0]) - last_t_ns], dt_ns])
        ph = phase
    fast = np.flatnonzero(dt < rate_dt_ns)
    if fast.size:
        rates = 1e9 / np.maximum(dt[fast], 1).astype(np.float64)
        rep.emit_each_command(diag.STEP_RATE, spec.name, ph[fast], rates, False,
                              "step rate {:.0f} Hz above the maximum " + f"{spec.max_step_rate_hz:.0f} Hz")
    close = np.flatnonzero(dt < spec.min_spacing_ns)
    if close.size:
        rep.emit_each_command(diag.PULSE_SPACING, spec.name, ph[close], dt[close].astype(np.float64), True,
                              "pulses {:.0f} ns apart, minimum spacing " + f"{spec.min_spacing_ns} ns")
