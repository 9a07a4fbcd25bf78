"""Path-coordinate phases -> Trajectory rows on the exact segment geometry.

Consumes :class:`Segments` and :class:`Phases` on the run's path coordinate ``s``;
produces :class:`Rows` (the Trajectory arrays without the time offset).  Phases that
cross a vertex are split at the exact crossing time (the root of the phase's cubic,
found by vectorised bisection), so every row lies on one segment: its path law
(segment, ``s`` from the segment's start, speed, acceleration, jerk) with the segment's
:class:`~cncc.ir.trajectory.Geometry` is the motion, exact, not sampled; the per-axis
arrays hold the exact state at the row's start (on a line, ``u_k`` times the path
polynomial is the motion itself).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cncc.ir.trajectory import FloatArray, Geometry, Limit, PathLaw, Trajectory
from cncc.passes.planning.profile import Phases
from cncc.passes.planning.segments import Segments


@dataclass
class Rows:
    t0: FloatArray
    dur: FloatArray
    p0: FloatArray
    v0: FloatArray
    a0: FloatArray
    j: FloatArray
    cmd: np.ndarray
    limit: np.ndarray
    law: PathLaw | None = None  # the path phases (``seg`` indexes ``law.geometry``); None: axis rows

    @property
    def duration(self) -> float:
        return float(self.t0[-1] + self.dur[-1]) if self.t0.size else 0.0


def eval_phase(ph: Phases, idx: np.ndarray, tau: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    v0, a0, j = ph.v0[idx], ph.a0[idx], ph.j[idx]
    s = ph.s0[idx] + v0 * tau + a0 * tau**2 / 2 + j * tau**3 / 6
    return s, v0 + a0 * tau + j * tau**2 / 2, a0 + j * tau


def crossing_times(ph: Phases, cuts: FloatArray) -> tuple[np.ndarray, FloatArray]:
    """For each ``s`` in ``cuts`` (sorted, inside the profile): the phase and the local time
    at which the (monotone) path coordinate reaches it, by vectorised bisection."""
    s_end = ph.s0 + ph.v0 * ph.dur + ph.a0 * ph.dur**2 / 2 + ph.j * ph.dur**3 / 6
    idx = np.clip(np.searchsorted(s_end, cuts, side="left"), 0, max(ph.t0.size - 1, 0))
    lo, hi = np.zeros(idx.size), ph.dur[idx].copy()
    for _ in range(56):
        mid = (lo + hi) / 2
        s_mid, _, _ = eval_phase(ph, idx, mid)
        below = s_mid < cuts
        lo = np.where(below, mid, lo)
        hi = np.where(below, hi, mid)
    return idx, (lo + hi) / 2


def split_at(ph: Phases, cuts: FloatArray) -> Phases:
    """Split phases where ``s`` crosses each value of ``cuts`` (sorted)."""
    return split_owned(ph, cuts)[0]


def split_owned(ph: Phases, cuts: FloatArray) -> tuple[Phases, np.ndarray]:
    """:func:`split_at` and, for each new phase, the index of the phase it comes from."""
    if cuts.size == 0 or ph.t0.size == 0:
        return ph, np.arange(ph.t0.size)
    s_end = ph.s0 + ph.v0 * ph.dur + ph.a0 * ph.dur**2 / 2 + ph.j * ph.dur**3 / 6
    idx = np.clip(np.searchsorted(s_end, cuts, side="left"), 0, ph.t0.size - 1)
    inside = (cuts > ph.s0[idx] + 1e-12) & (cuts < s_end[idx] - 1e-12)
    idx, tau = crossing_times(ph, cuts[inside])
    t_cut = ph.t0[idx] + tau
    starts = np.unique(np.concatenate([ph.t0, t_cut]))
    owner = np.clip(np.searchsorted(ph.t0, starts, side="right") - 1, 0, ph.t0.size - 1)
    tau = starts - ph.t0[owner]
    s, v, a = eval_phase(ph, owner, tau)
    end = ph.t0[-1] + ph.dur[-1]
    dur = np.diff(np.concatenate([starts, [end]]))
    keep = dur > 1e-13
    return (Phases(starts[keep], dur[keep], s[keep], v[keep], a[keep], ph.j[owner][keep], ph.limit[owner][keep]),
            owner[keep])


def path_rows(seg: Segments, ph: Phases) -> Rows:
    """Rows of a run; ``ph.interval`` (if set) gives each phase's segment directly."""
    if ph.interval is not None and ph.interval.size == ph.t0.size:
        k = ph.interval
    else:
        bounds = ph.segments
        ph, owner = split_owned(ph, seg.s0[1:-1])
        s_mid, _, _ = eval_phase(ph, np.arange(ph.t0.size), ph.dur / 2)
        k = np.clip(np.searchsorted(seg.s0, s_mid, side="right") - 1, 0, seg.count - 1)
        if bounds is not None:  # rounding may carry a phase a hair past its block's end
            k = np.clip(k, bounds[0][owner], bounds[1][owner])
    limit = np.where(ph.limit == Limit.NONE, seg.vlim[k], ph.limit).astype(np.int8)
    s_local = np.clip(ph.s0 - seg.s0[k], 0.0, seg.length[k])
    law = PathLaw(k.astype(np.int64), s_local, ph.v0, ph.a0, ph.j, seg.shape())
    if seg.geo is None:
        u = seg.u[k]
        p0 = seg.p0[k] + u * s_local[:, None]
        return Rows(ph.t0, ph.dur, p0, u * ph.v0[:, None], u * ph.a0[:, None], u * ph.j[:, None], seg.cmd[k], limit,
                    law)
    p0, v0, a0, j = law.states(np.arange(k.size), np.zeros(k.size))
    return Rows(ph.t0, ph.dur, p0, v0, a0, j, seg.cmd[k], limit, law)


@dataclass
class AxisProfile:
    """A 1-D constant-jerk profile of one axis (times local to the move)."""

    t0: FloatArray
    dur: FloatArray
    p0: FloatArray
    v0: FloatArray
    a0: FloatArray
    j: FloatArray


def merge_axes(profiles: list[AxisProfile], start: FloatArray, cmd: int, limit: int) -> Rows:
    """Rows of an independent-axis move: time split at every axis' phase boundary."""
    total = max((p.t0[-1] + p.dur[-1] for p in profiles if p.t0.size), default=0.0)
    ends = [p.t0[-1:] + p.dur[-1:] for p in profiles if p.t0.size]
    knots = np.unique(np.concatenate([[0.0], *[p.t0 for p in profiles if p.t0.size], *ends]))
    knots = knots[knots < total - 1e-13]
    n = knots.size
    dur = np.diff(np.concatenate([knots, [total]]))
    p0 = np.tile(start, (n, 1))
    v0, a0, jj = np.zeros((n, 6)), np.zeros((n, 6)), np.zeros((n, 6))
    for i, prof in enumerate(profiles):
        if prof.t0.size == 0:
            continue
        end_t = prof.t0[-1] + prof.dur[-1]
        k = np.clip(np.searchsorted(prof.t0, knots, side="right") - 1, 0, prof.t0.size - 1)
        tau = np.minimum(knots, end_t) - prof.t0[k]
        active = knots < end_t - 1e-13
        p = prof.p0[k] + prof.v0[k] * tau + prof.a0[k] * tau**2 / 2 + prof.j[k] * tau**3 / 6
        p0[:, i] = p
        v0[:, i] = np.where(active, prof.v0[k] + prof.a0[k] * tau + prof.j[k] * tau**2 / 2, 0.0)
        a0[:, i] = np.where(active, prof.a0[k] + prof.j[k] * tau, 0.0)
        jj[:, i] = np.where(active, prof.j[k], 0.0)
    return Rows(knots, dur, p0, v0, a0, jj, np.full(n, cmd, dtype=np.int64), np.full(n, limit, dtype=np.int8))


def assemble(chunks: list[Rows]) -> Trajectory:
    chunks = [c for c in chunks if c.t0.size]
    if not chunks:
        return Trajectory.empty()
    offsets = np.cumsum([0.0] + [c.duration for c in chunks[:-1]])
    return Trajectory(
        np.concatenate([c.t0 + off for c, off in zip(chunks, offsets, strict=True)]),
        np.concatenate([c.dur for c in chunks]),
        np.concatenate([c.p0 for c in chunks]),
        np.concatenate([c.v0 for c in chunks]),
        np.concatenate([c.a0 for c in chunks]),
        np.concatenate([c.j for c in chunks]),
        np.concatenate([c.cmd for c in chunks]).astype(np.int64),
        np.concatenate([c.limit for c in chunks]).astype(np.int8),
        path=_joined_law(chunks),
    )


def _joined_law(chunks: list[Rows]) -> PathLaw | None:
    """One path law over the chunks (axis-row chunks get segment ``-1``); None without path phases."""
    if all(c.law is None for c in chunks):
        return None
    m = chunks[0].p0.shape[1]
    geos: list[Geometry] = []
    seg, s0, v, a, j = [], [], [], [], []
    base = 0
    for c in chunks:
        n = c.t0.size
        if c.law is None:
            seg.append(np.full(n, -1, np.int64))
            zero = np.zeros(n)
            s0.append(zero)
            v.append(zero)
            a.append(zero)
            j.append(zero)
            continue
        seg.append(c.law.seg + base)
        s0.append(c.law.s0_mm)
        v.append(c.law.v_mm_s)
        a.append(c.law.a_mm_s2)
        j.append(c.law.j_mm_s3)
        geos.append(c.law.geometry)
        base += c.law.geometry.count
    return PathLaw(np.concatenate(seg), np.concatenate(s0), np.concatenate(v), np.concatenate(a), np.concatenate(j),
                   Geometry.concat(geos, m))
