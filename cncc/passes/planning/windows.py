"""-O2 local re-planning: each segment's piece of the filtered profile re-timed by ruckig.

Consumes the :class:`Segments` of a part (rest to rest) and its filtered
:class:`Phases` (``fir.py``); produces phases that are never slower.

The moving-average filter uses one width ``Tf`` for the whole part, while the best width
for a speed change ``dv`` is about ``sqrt(dv / J)``: where the path is short segments
with a speed minimum at every corner, the filter forces cruises and slow ramps.  Here the
filtered profile is cut where it crosses the vertices; between two crossings the path is
one straight segment, so its caps are the segment's own (speed ``vcap``, acceleration
``acap``, jerk ``jcap``).  ruckig gives the time-optimal jerk-limited profile between the
filtered states at both crossings (position, speed *and* acceleration, so the joins stay
continuous in acceleration), with the speed kept in ``[0, vcap]``.  It replaces the
filtered piece when it is faster.

Then, on parts of at most :data:`MAX_SEARCH` segments that spend most of their time
below a tenth of their speed caps (short moves, where the jerk limit governs), the
vertex states themselves are searched: a pattern search moves the speed and the
acceleration of one vertex, or of a run of 2 or 4 consecutive vertices together (the
chords of a slow blend arc only gain together), along the axes and diagonals of the
(v, a) plane, with halving steps, and keeps a move when the ruckig times of the pieces
it bounds add up to less.  The speed stays within the vertex cap and the acceleration
within both segments' caps, so the vertex caps and the velocity-step rule still hold.

Safety: every ruckig piece is checked against its caps by the exact extremes of its
phases and against the end state, and the joined profile for continuity of s, v and a;
if anything fails, the filtered profile is returned unchanged.

Cost: ruckig solves in ~5 µs with a reused instance (building one costs 20 times
that), the per-segment pass about 18 µs per segment in all; it runs on parts of at most
:data:`MAX_PLAIN` segments, or :data:`MAX_SEGMENTS` when they are jerk-bound, so long
CAM parts keep the filter's throughput, and the search makes a few hundred
thousand solves on a part of a few hundred segments (seconds).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache
from typing import Any

import numpy as np

from cncc.ir.trajectory import FloatArray, Limit
from cncc.passes.planning.emit import eval_phase, split_at
from cncc.passes.planning.profile import Phases
from cncc.passes.planning.segments import Segments

MAX_SEGMENTS = 4096  # jerk-bound parts up to this size are re-timed
MAX_PLAIN = 512  # other parts up to this size too
MAX_SEARCH = 512  # parts up to this size also get the vertex-state search
SLOW_SHARE = 0.1
SWEEPS = 3
WIDTHS = (1, 2, 4)
STEPS = 12
GAIN = 1e-9  # a re-planned piece must be faster by this share
TOL = 1e-9  # relative tolerance on the caps and on the reached state


def replan_segments(seg: Segments, ph: Phases) -> Phases:
    """``ph`` with every segment's piece replaced by ruckig's where that is faster."""
    if seg.count < 2 or seg.count > MAX_SEGMENTS or ph.t0.size == 0:
        return ph
    jerk_bound = _jerk_bound(ph, seg)
    if seg.count > MAX_PLAIN and not jerk_bound:
        return ph
    ph = split_at(ph, seg.s0[1:-1])
    n = ph.t0.size
    s_mid, _, _ = eval_phase(ph, np.arange(n), ph.dur / 2)
    k = np.clip(np.searchsorted(seg.s0, s_mid, side="right") - 1, 0, seg.count - 1)
    if np.any(np.diff(k) < 0):
        return ph
    lo = np.searchsorted(k, np.arange(seg.count), side="left")
    hi = np.searchsorted(k, np.arange(seg.count), side="right")
    if np.any(lo == hi):
        return ph
    s_end, v_end, a_end = eval_phase(ph, np.arange(n), ph.dur)
    pieces: list[Piece] = [_slice(ph, int(a), int(b)) for a, b in zip(lo, hi, strict=True)]
    states: list[State] = [(float(ph.s0[a]), float(ph.v0[a]), float(ph.a0[a])) for a in lo]
    states.append((float(s_end[-1]), float(v_end[-1]), float(a_end[-1])))
    caps = [(float(seg.vcap[i]), float(seg.acap[i]), float(seg.jcap[i])) for i in range(seg.count)]
    changed = False
    for i in range(seg.count):
        new = _ruckig(states[i], states[i + 1], caps[i])
        if new is not None and new.time < pieces[i].time * (1 - GAIN):
            pieces[i], changed = new, True
    if seg.count <= MAX_SEARCH and jerk_bound:
        changed = _search_vertices(seg, caps, states, pieces) or changed
    if not changed:
        return ph
    out = _join([p.phases(seg, i) for i, p in enumerate(pieces)])
    checks = (p.ok(states[i + 1], caps[i]) for i, p in enumerate(pieces))
    return out if all(checks) and _continuous(out) else ph


def _jerk_bound(ph: Phases, seg: Segments) -> bool:
    """The part spends most of its time below a tenth of its speed caps: a regime of
    short moves governed by the jerk limit, where the vertex search pays."""
    k = np.clip(np.searchsorted(seg.s0, ph.s0, side="right") - 1, 0, seg.count - 1)
    slow = ph.v0 < SLOW_SHARE * seg.vcap[k]
    return bool(ph.dur[slow].sum() > 0.5 * ph.dur.sum())


def _join(parts: list[Phases]) -> Phases:
    dur = np.concatenate([p.dur for p in parts])
    t0 = np.concatenate([[0.0], np.cumsum(dur)[:-1]])
    return Phases(t0, dur, np.concatenate([p.s0 for p in parts]), np.concatenate([p.v0 for p in parts]),
                  np.concatenate([p.a0 for p in parts]), np.concatenate([p.j for p in parts]),
                  np.concatenate([p.limit for p in parts]).astype(np.int8))


def _continuous(ph: Phases) -> bool:
    """Position, speed and acceleration continuous at every join (the planners' own
    profiles may step the speed at vertices, e.g. the SZGH emulation: such parts are
    left alone)."""
    s1, v1, a1 = eval_phase(ph, np.arange(ph.t0.size), ph.dur)
    scale_v = max(float(np.abs(ph.v0).max()), 1.0)
    scale_a = max(float(np.abs(ph.a0).max()), 1.0)
    return bool(np.all(np.abs(s1[:-1] - ph.s0[1:]) <= 1e-9 * max(float(s1[-1]), 1.0))
                and np.all(np.abs(v1[:-1] - ph.v0[1:]) <= 1e-7 * scale_v)
                and np.all(np.abs(a1[:-1] - ph.a0[1:]) <= 1e-6 * scale_a))


State = tuple[float, float, float]
Caps = tuple[float, float, float]


@dataclass
class Piece:
    """A segment's piece: the filtered phases, or a ruckig profile (lists, per phase)."""

    time: float
    kept: Phases | None = None
    raw: tuple[list[float], list[float], list[float], list[float], list[float]] | None = None

    def phases(self, seg: Segments, i: int) -> Phases:
        if self.kept is not None:
            return self.kept
        assert self.raw is not None
        t, p, v, a, j = (np.array(x, float) for x in self.raw)
        keep = t > 1e-13
        t, p, v, a, j = t[keep], p[keep], v[keep], a[keep], j[keep]
        lim = np.where(np.abs(a) + np.abs(j) > 0, int(Limit.JERK), int(seg.vlim[i])).astype(np.int8)
        return Phases(np.concatenate([[0.0], np.cumsum(t)[:-1]]), t, p, v, a, j, lim)

    def ok(self, end: State, caps: Caps) -> bool:
        if self.kept is not None:
            return True
        return _within(self.phases_plain(), end, *caps)

    def phases_plain(self) -> Phases:
        assert self.raw is not None
        t, p, v, a, j = (np.array(x, float) for x in self.raw)
        return Phases(np.concatenate([[0.0], np.cumsum(t)[:-1]]), t, p, v, a, j, np.zeros(t.size, np.int8))


def _slice(ph: Phases, a: int, b: int) -> Piece:
    part = Phases(ph.t0[a:b], ph.dur[a:b], ph.s0[a:b], ph.v0[a:b], ph.a0[a:b], ph.j[a:b], ph.limit[a:b])
    return Piece(float(part.dur.sum()), kept=part)


def _search_vertices(seg: Segments, caps: list[Caps], states: list[State], pieces: list[Piece]) -> bool:
    """Pattern search on the interior vertex states (speed <= vertex cap, acceleration
    within both segments' caps), minimising the ruckig times of the pieces they bound.
    Runs of ``w`` consecutive vertices also move together (a slow blend arc is several
    chords whose vertices only gain together)."""
    v_cap = [float(min(seg.vvert[i], seg.vcap[i - 1], seg.vcap[i])) for i in range(1, seg.count)]
    a_cap = [float(min(seg.acap[i - 1], seg.acap[i])) for i in range(1, seg.count)]
    bounds = [(0.0, 0.0), *zip(v_cap, a_cap, strict=True)]
    changed = False
    for _ in range(SWEEPS):
        for w in WIDTHS:
            for m in range(1, seg.count - w + 1):
                changed = _search_run(caps, bounds, states, pieces, m, w) or changed
    return changed


def _search_run(caps: list[Caps], bounds: list[tuple[float, float]], states: list[State], pieces: list[Piece],
                m: int, w: int) -> bool:
    idx = range(m, m + w)
    best = sum(pieces[i].time for i in range(m - 1, m + w))
    dv = 0.1 * max(max(states[i][1] for i in idx), 1e-3)
    da = 0.25 * min(bounds[i][1] for i in idx)
    changed = False
    for _ in range(STEPS):
        moved = False
        for sv, sa in MOVES(dv, da):
            cand = [(states[i][0], states[i][1] + sv, states[i][2] + sa) for i in idx]
            if not all(0.0 < c[1] <= bounds[i][0] and abs(c[2]) <= bounds[i][1]
                       for c, i in zip(cand, idx, strict=True)):
                continue
            ends = [states[m - 1], *cand, states[m + w]]
            total = 0.0
            for i in range(m - 1, m + w):
                total += _time(ends[i - m + 1], ends[i - m + 2], caps[i])
                if total >= best:
                    break
            if total >= best * (1 - GAIN):
                continue
            new = [_ruckig(ends[i - m + 1], ends[i - m + 2], caps[i]) for i in range(m - 1, m + w)]
            if any(p is None for p in new):
                continue
            best, moved, changed = total, True, True
            pieces[m - 1:m + w] = [p for p in new if p is not None]
            states[m:m + w] = cand
            break
        if not moved:
            dv, da = dv / 2, da / 2
    return changed


@cache
def _solver() -> tuple[Any, Any, Any, tuple[Any, ...], type[Exception]]:
    """One ruckig instance, input and trajectory, reused (building them costs ~20x a solve)."""
    from ruckig import InputParameter, Result, Ruckig, RuckigError, Trajectory

    return Ruckig(1), InputParameter(1), Trajectory(1), (Result.Working, Result.Finished), RuckigError


def _solve(start: State, end: State, caps: Caps) -> Any:
    """ruckig's time-optimal jerk-limited trajectory from ``start`` to ``end`` (s, v, a), or None."""
    v_max, a_max, j_max = caps
    if not (0.0 < v_max < math.inf and 0.0 < a_max < math.inf and 0.0 < j_max < math.inf) or end[0] <= start[0]:
        return None
    if max(abs(start[2]), abs(end[2])) > a_max or max(start[1], end[1]) > v_max or min(start[1], end[1]) < 0:
        return None
    otg, inp, traj, good, error = _solver()
    inp.current_position, inp.current_velocity, inp.current_acceleration = [start[0]], [start[1]], [start[2]]
    inp.target_position, inp.target_velocity, inp.target_acceleration = [end[0]], [end[1]], [end[2]]
    inp.max_velocity, inp.min_velocity = [v_max], [0.0]
    inp.max_acceleration, inp.max_jerk = [a_max], [j_max]
    try:
        result = otg.calculate(inp, traj)
    except (error, RuntimeError):
        return None
    return traj if result in good else None


def _time(start: State, end: State, caps: Caps) -> float:
    traj = _solve(start, end, caps)
    return math.inf if traj is None else float(traj.duration)


def _ruckig(start: State, end: State, caps: Caps) -> Piece | None:
    """The piece of ruckig's profile from ``start`` to ``end``, or None."""
    traj = _solve(start, end, caps)
    if traj is None:
        return None
    prof = traj.profiles[0][0]
    raw = (list(prof.t), list(prof.p[:-1]), list(prof.v[:-1]), list(prof.a[:-1]), list(prof.j))
    return Piece(float(sum(raw[0])), raw=raw)


def _within(ph: Phases, end: State, v_max: float, a_max: float, j_max: float) -> bool:
    """Exact extremes of every phase within the caps, the end state reached."""
    s1, v1, a1 = eval_phase(ph, np.arange(ph.t0.size), ph.dur)
    scale = max(v_max, 1.0)
    if abs(float(s1[-1]) - end[0]) > 1e-9 * max(abs(end[0]), 1.0) or abs(float(v1[-1]) - end[1]) > TOL * scale:
        return False
    if abs(float(a1[-1]) - end[2]) > TOL * a_max or np.any(np.abs(ph.j) > j_max * (1 + TOL)):
        return False
    if np.any(np.maximum(np.abs(ph.a0), np.abs(a1)) > a_max * (1 + TOL)):
        return False
    # speed extremes: the ends of each phase and the stationary point of its quadratic
    with np.errstate(divide="ignore", invalid="ignore"):
        tau = np.where(ph.j != 0.0, -ph.a0 / ph.j, 0.0)
    tau = np.where((tau > 0) & (tau < ph.dur), tau, 0.0)
    _, v_st, _ = eval_phase(ph, np.arange(ph.t0.size), tau)
    speeds: FloatArray = np.concatenate([ph.v0, v1, v_st])
    return bool(speeds.min() >= -TOL * scale and speeds.max() <= v_max * (1 + TOL))


def _moves_axes(dv: float, da: float) -> tuple[tuple[float, float], ...]:
    return (dv, 0.0), (-dv, 0.0), (0.0, da), (0.0, -da)


def _moves_diag(dv: float, da: float) -> tuple[tuple[float, float], ...]:
    return (dv, 0.0), (-dv, 0.0), (0.0, da), (0.0, -da), (dv, da), (dv, -da), (-dv, da), (-dv, -da)


MOVES = _moves_diag
