"""Backlash compensation pulses combined with the commanded steps of one axis.

Consumes, per window, an axis' commanded steps (warped, integer ns) and the reversal
instants found in them; produces the combined step train.

* **Exact mode** (:class:`BurstMerger`): a burst of ``backlash_steps`` pulses starts at
  each reversal and is *superposed* on the commanded motion (:func:`superpose`): the
  drive sees the sum of the two motions, so the combined steps are where the sum of
  the two positions crosses the step boundaries.  A burst still running at the end
  of a window is not cut: every event of the axis from the burst's start on is held
  back and combined with the next window's steps, so the result does not depend on
  where windows end.  :attr:`BurstMerger.hold_ns` tells the generator how far the
  chunk's horizon may go.
* **Interpolation mode** (:func:`add_period_counts`): the compensation is counted per
  interpolation period, as the controller's interpolator outputs it, and *added* to
  the commanded count of each period before the pulses are spread evenly.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

F64 = npt.NDArray[np.float64]
I64 = npt.NDArray[np.int64]
I8 = npt.NDArray[np.int8]
I32 = npt.NDArray[np.int32]
B = npt.NDArray[np.bool_]


@dataclass(slots=True)
class Train:
    """Steps of one axis: times (ns), motor direction, phase, backlash flag; shape ``(c,)`` each."""

    t_ns: I64
    direction: I8
    phase: I32
    backlash: B

    @staticmethod
    def empty() -> Train:
        return Train(np.zeros(0, np.int64), np.zeros(0, np.int8), np.zeros(0, np.int32), np.zeros(0, np.bool_))

    @staticmethod
    def concat(parts: list[Train]) -> Train:
        return Train(np.concatenate([p.t_ns for p in parts]), np.concatenate([p.direction for p in parts]),
                     np.concatenate([p.phase for p in parts]), np.concatenate([p.backlash for p in parts]))

    def take(self, idx: npt.NDArray[np.intp] | B) -> Train:
        return Train(self.t_ns[idx], self.direction[idx], self.phase[idx], self.backlash[idx])


@dataclass(slots=True)
class BurstMerger:
    """Exact-mode backlash of one axis, with the events held back while a burst is open."""

    offsets_s: F64  # pulse times from the reversal
    length_s: float
    held: Train = field(default_factory=Train.empty)
    open_bursts: list[tuple[int, int]] = field(default_factory=list)  # (start, end) in ns
    hold_ns: int | None = None  # earliest held-back event, if any

    @property
    def idle(self) -> bool:
        return not self.open_bursts and self.held.t_ns.size == 0

    def merge(self, steps: Train, starts_ns: F64, dirs: I8, phases: I32, end_ns: int, final: bool) -> Train:
        """Commanded ``steps`` plus bursts starting at ``starts_ns``; returns what can be emitted now."""
        b = self.offsets_s.size
        parts = [self.held, steps]
        bursts = list(self.open_bursts)
        if b and starts_ns.size:
            bt = np.rint((starts_ns[:, None] + self.offsets_s[None, :]) * 1e9).astype(np.int64).ravel()
            parts.append(Train(bt, np.repeat(dirs, b), np.repeat(phases, b), np.ones(bt.shape, np.bool_)))
            bursts += [(round(t0 * 1e9), round((t0 + self.length_s) * 1e9)) for t0 in starts_ns.tolist()]
        train = Train.concat(parts)
        train = train.take(np.argsort(train.t_ns, kind="stable"))
        still_open = [t0 for t0, t1 in bursts if t1 >= end_ns and not final]
        cut = min(still_open) if still_open else None
        self.open_bursts = [(t0, t1) for t0, t1 in bursts if cut is not None and (t0 >= cut or t1 >= end_ns)]
        for t0, t1 in bursts:
            if (t0, t1) not in self.open_bursts:
                superpose(train.t_ns, train.direction, train.backlash, t0, t1)
        if cut is None:
            self.held, self.hold_ns = Train.empty(), None
            return train
        k = int(np.searchsorted(train.t_ns, cut, side="left"))
        self.held, self.hold_ns = train.take(slice(k, None)), cut  # type: ignore[arg-type]
        return train.take(slice(0, k))  # type: ignore[arg-type]


def superpose(t_ns: I64, direction: I8, backlash: B, t0_ns: int, t1_ns: int) -> None:
    """Re-time, in place, the backlash burst ``[t0_ns, t1_ns]`` and the commanded steps inside it.

    Each train's position is taken as linear between its own crossings (step ``k`` at
    ``k - 1/2``); the combined steps are the crossings of the sum, so a compensation
    pulse never lands a nanosecond from a commanded one.  Labels (phase, backlash
    flag) stay with the steps in their merged order.
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


@dataclass(slots=True)
class PeriodBacklash:
    """Interpolation-mode backlash of one axis: signed pulse counts owed to future periods."""

    per_period: I64  # pulses of one burst in its 1st, 2nd, ... period (from the reversal period on)
    pending: dict[int, tuple[int, int]] = field(default_factory=dict)  # period -> (signed count, phase)

    @staticmethod
    def of(offsets_s: F64, period_s: float) -> PeriodBacklash:
        if offsets_s.size == 0:
            return PeriodBacklash(np.zeros(0, np.int64))
        return PeriodBacklash(np.bincount(np.floor(offsets_s / period_s).astype(np.int64)).astype(np.int64))

    def add(self, first_periods: I64, dirs: I8, phases: I32) -> None:
        for k0, d, ph in zip(first_periods.tolist(), dirs.tolist(), phases.tolist(), strict=True):
            for i, c in enumerate(self.per_period.tolist()):
                if c:
                    old, old_ph = self.pending.get(k0 + i, (0, ph))
                    self.pending[k0 + i] = (old + d * c, old_ph)

    def take(self, k1: int | None) -> tuple[I64, I64, I32]:
        """Periods before ``k1`` (all when None) with their signed counts and phases; removed from pending."""
        keys = sorted(k for k in self.pending if k1 is None or k < k1)
        counts = [self.pending[k][0] for k in keys]
        phases = [self.pending.pop(k)[1] for k in keys]
        return np.array(keys, np.int64), np.array(counts, np.int64), np.array(phases, np.int32)


def add_period_counts(periods: I64, counts: I64, phases: I32, bl_periods: I64, bl_counts: I64, bl_phases: I32,
                      period_s: float) -> tuple[F64, I8, I32, B, I64, I8, I32, I64]:
    """Per-period signed counts (commanded + backlash), spread evenly in each period.

    Returns step times (s), directions, phases, backlash flags and, per period with
    pulses, its index, direction, phase and the index of its first step.  In a period
    where both add up in one direction, ``min(|backlash|, |net|)`` pulses are flagged.
    """
    keys = np.union1d(periods, bl_periods)
    cmd = np.zeros(keys.shape, np.int64)
    cmd[np.searchsorted(keys, periods)] = counts
    blc = np.zeros(keys.shape, np.int64)
    blc[np.searchsorted(keys, bl_periods)] = bl_counts
    ph = np.zeros(keys.shape, np.int32)
    ph[np.searchsorted(keys, bl_periods)] = bl_phases
    ph[np.searchsorted(keys, periods)] = phases
    net = cmd + blc
    mv = np.flatnonzero(net)
    keys, net, blc, ph = keys[mv], net[mv], blc[mv], ph[mv]
    n = np.abs(net)
    direction = np.sign(net).astype(np.int8)
    flagged = np.where(np.sign(blc) == direction, np.minimum(np.abs(blc), n), 0)
    pidx = np.repeat(np.arange(keys.shape[0]), n)
    first = np.cumsum(n) - n
    off = np.arange(pidx.shape[0], dtype=np.int64) - first[pidx]
    t_s = (keys[pidx] + (off + 0.5) / n[pidx]) * period_s
    return (t_s, direction[pidx], ph[pidx], off < flagged[pidx], keys, direction, ph, first)
