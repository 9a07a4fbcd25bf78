"""Nominal timing (``-O0``): length / feed, as CAM systems estimate.

Consumes IR commands and a machine model; produces either plain sums
(:func:`nominal_timing`) or a :class:`~cncc.ir.trajectory.Trajectory` of
constant-velocity phases (:func:`nominal_trajectory`) that the timing report reads
exactly like a planned one.

Rapids run at the machine's rapid rates (interpolated: the slowest axis sets the
time and all axes finish together; independent: each axis at its own rate, the
longest wins, a dog-leg path), feeds at the programmed feed along the path (arcs
along their helical length; a G95 line under constant surface speed integrates
1/feed along the move, :meth:`cncc.ir.css.Css.time_s`), with no acceleration at all: that is what the planner
levels add.  Non-motion commands (dwells, tool changes, spindle starts, stops) are
events; :mod:`cncc.backends.timing.events` gives their times.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from cncc.ir import Arc, Aux, Command, Dwell, Linear, Rapid, Spindle, SpindleState, Stop, StopKind, ToolChange
from cncc.ir.frame import Plane
from cncc.ir.machine import MachineModel, RapidMode

if TYPE_CHECKING:
    import numpy as np
    import numpy.typing as npt

    from cncc.ir.batch import MoveBatch
    from cncc.ir.trajectory import Trajectory

    F64 = npt.NDArray[np.float64]
    I64 = npt.NDArray[np.int64]

ARC_CHORD_MAX_RAD = math.radians(10.0)
"""Nominal trajectories draw arcs as chords of at most this sweep (for plots only:
the time is the helical length / feed either way)."""

ARCS_PER_CHUNK = 4096
"""Arcs chorded per numpy step in :func:`nominal_trajectory` (bounds its temporaries)."""


@dataclass(slots=True)
class NominalTiming:
    total_s: float = 0.0
    by_category_s: dict[str, float] = field(default_factory=dict)
    by_line_s: dict[tuple[int, int], float] = field(default_factory=dict)  # (source_id, span start) -> s
    by_command: list[tuple[Command, float, str]] = field(default_factory=list)


def arc_sweep_rad(c: Arc) -> float:
    """Signed sweep of an arc (positive counter-clockwise), full turns included."""
    return sweep_rad(c.start, c.end, c.center, c.turns, c.plane)


def sweep_rad(start: Sequence[float], end: Sequence[float], center: Sequence[float], turns: int, plane: Plane) -> float:
    """:func:`arc_sweep_rad` of an arc given by its parts (the rows of a batch use it too)."""
    i, j = plane.first, plane.second
    a0 = math.atan2(start[j] - center[j], start[i] - center[i])
    a1 = math.atan2(end[j] - center[j], end[i] - center[i])
    sweep = a1 - a0
    if turns > 0:
        while sweep <= 1e-12:
            sweep += 2 * math.pi
        return sweep + 2 * math.pi * (turns - 1)
    while sweep >= -1e-12:
        sweep -= 2 * math.pi
    return sweep - 2 * math.pi * (-turns - 1)


def arc_length_mm(c: Arc) -> float:
    return helix_length_mm(c.start, c.end, c.center, arc_sweep_rad(c), c.plane)


def helix_length_mm(start: Sequence[float], end: Sequence[float], center: Sequence[float], sweep: float,
                    plane: Plane) -> float:
    """Length of the helix from ``start`` to ``end`` around ``center`` over ``sweep`` radians."""
    i, j, n = plane.first, plane.second, plane.normal
    r = math.hypot(start[i] - center[i], start[j] - center[j])
    planar = abs(sweep) * r
    helix = end[n] - start[n]
    return math.hypot(planar, helix)


def arc_chords(sweep: float) -> int:
    """How many chords a nominal trajectory draws an arc of ``sweep`` radians with."""
    return max(1, math.ceil(abs(sweep) / ARC_CHORD_MAX_RAD))


def linear_length_mm(c: Linear) -> float:
    """Path length of a feed move: XYZ length, or the rotary length when only A/B/C move."""
    length = math.dist(c.start[:3], c.end[:3])
    return length if length > 0.0 else math.dist(c.start, c.end)


def rapid_time_s(start: Sequence[float], end: Sequence[float], machine: MachineModel) -> float:
    t = 0.0
    for k, axis in enumerate(machine.axes[: len(start)]):
        d = abs(end[k] - start[k])
        if d > 0:
            t = max(t, d / (axis.rapid_mm_min / 60.0))
    return t


def feed_time_s(length_mm: float, feed_mm_min: float) -> float:
    return length_mm / (feed_mm_min / 60.0) if feed_mm_min > 0 else 0.0


def linear_time_s(c: Linear) -> float:
    """Length / feed; under CSS (``motion.css``) the exact time with the spindle speed following the radius."""
    if c.motion.css is not None:
        css = c.motion.css
        return css.time_s(linear_length_mm(c), c.start, c.end, c.frame.total_offset_mm[css.axis])
    return feed_time_s(linear_length_mm(c), c.feed_mm_min)


def command_time_s(c: Command, machine: MachineModel) -> tuple[float, str]:
    match c:
        case Rapid():
            return rapid_time_s(c.start, c.end, machine), "rapid"
        case Linear():
            return linear_time_s(c), "feed"
        case Arc():
            return feed_time_s(arc_length_mm(c), c.feed_mm_min), "arc"
        case Dwell():
            return c.seconds, "dwell"
        case ToolChange():
            return machine.tool_change_s, "tool_change"
        case Spindle():
            if c.state in (SpindleState.CW, SpindleState.CCW):
                return machine.spindle_ramp_s, "spindle"
            return 0.0, "spindle"
        case Aux():
            whole, frac = divmod(c.code, 10)
            known = machine.m_code(f"M{whole:02d}" + (f".{frac}" if frac else ""))
            return (known.seconds, "wait") if known is not None else (0.0, "")
        case Stop():
            if c.kind is StopKind.OPTIONAL_STOP or c.kind is StopKind.PROGRAM_STOP:
                return machine.optional_stop_s, "wait"
            return 0.0, "wait"
    return 0.0, ""


def nominal_timing(cmds: Iterable[Command], machine: MachineModel) -> NominalTiming:
    """Sum the nominal times; ``by_line_s`` is keyed by (source id, span start)."""
    out = NominalTiming()
    for c in cmds:
        t, cat = command_time_s(c, machine)
        if not cat:
            continue
        out.total_s += t
        out.by_category_s[cat] = out.by_category_s.get(cat, 0.0) + t
        key = (c.span.source_id, c.span.start)
        out.by_line_s[key] = out.by_line_s.get(key, 0.0) + t
        out.by_command.append((c, t, cat))
    return out


# ---- constant-velocity trajectory ------------------------------------------------------
@dataclass(slots=True)
class _Rows:
    """Phases under construction (lists of plain floats; turned into arrays at the end)."""

    dur_s: list[float] = field(default_factory=list)
    p0_mm: list[Sequence[float]] = field(default_factory=list)
    v_mm_s: list[Sequence[float]] = field(default_factory=list)
    cmd: list[int] = field(default_factory=list)
    limit: list[int] = field(default_factory=list)

    def add(self, dur_s: float, p0: Sequence[float], p1: Sequence[float], cmd: int, limit: int) -> None:
        if dur_s <= 0.0:
            return
        self.dur_s.append(dur_s)
        self.p0_mm.append(tuple(p0))
        self.v_mm_s.append(tuple((b - a) / dur_s for a, b in zip(p0, p1, strict=True)))
        self.cmd.append(cmd)
        self.limit.append(limit)


def _rapid_rows(rows: _Rows, c: Rapid, i: int, machine: MachineModel, limit: int) -> None:
    if machine.rapid_mode is not RapidMode.INDEPENDENT:
        rows.add(rapid_time_s(c.start, c.end, machine), c.start, c.end, i, limit)
        return
    finish_s = axis_finish_s(c.start, c.end, machine)

    def at(t_s: float) -> list[float]:
        return [s + (e - s) * (min(t_s, f) / f if f > 0 else 1.0)
                for s, e, f in zip(c.start, c.end, finish_s, strict=True)]

    t_prev = 0.0
    for t in sorted(set(finish_s)):
        if t > t_prev:
            rows.add(t - t_prev, at(t_prev), at(t), i, limit)
            t_prev = t


def axis_finish_s(start: Sequence[float], end: Sequence[float], machine: MachineModel) -> list[float]:
    """Independent rapids: when each axis arrives (each at its own rate; the machine's unknown axes
    along the whole move)."""
    total_s = rapid_time_s(start, end, machine)
    finish_s = [0.0] * len(start)
    for k, axis in enumerate(machine.axes[: len(start)]):
        d = abs(end[k] - start[k])
        finish_s[k] = d / (axis.rapid_mm_min / 60.0) if d > 0 else 0.0
    for k in range(len(machine.axes), len(start)):
        finish_s[k] = total_s if end[k] != start[k] else 0.0
    return finish_s


def independent_rapid_phases_s(start: Sequence[float], end: Sequence[float], machine: MachineModel) -> list[float]:
    """The phase durations :func:`nominal_trajectory` gives an independent rapid (one per arrival)."""
    out: list[float] = []
    t_prev = 0.0
    for t in sorted(set(axis_finish_s(start, end, machine))):
        if t > t_prev:
            out.append(t - t_prev)
            t_prev = t
    return out


@dataclass(slots=True)
class _ArcRows:
    """The arcs of a nominal trajectory, chorded at the end in numpy (one row per chord).

    Per arc only its scalars are computed in Python (sweep, radii, start angle, time); the
    chord points are the same float operations per element as the per-chord formula
    ``r = r0 + (r1 - r0) u``, ``a = a0 + sweep u``, ``p = s + (e - s) u`` with ``u = k / n``
    (numpy element-wise, no fused operations) and ``math.cos`` / ``math.sin`` of every angle
    (numpy's may differ in the last bit), so the rows are bit for bit the scalar code's.
    """

    cmd: list[int] = field(default_factory=list)
    start: list[Sequence[float]] = field(default_factory=list)
    end: list[Sequence[float]] = field(default_factory=list)
    center: list[Sequence[float]] = field(default_factory=list)
    plane: list[tuple[int, int]] = field(default_factory=list)
    scal: list[tuple[float, float, float, float, float]] = field(default_factory=list)  # r0, r1, a0, sweep, dur
    chords: list[int] = field(default_factory=list)

    def add(self, c: Arc, i: int) -> None:
        total_s = feed_time_s(arc_length_mm(c), c.feed_mm_min)
        sweep = arc_sweep_rad(c)
        n = arc_chords(sweep)
        if total_s / n <= 0.0:  # _Rows.add drops phases without time
            return
        pi, pj = c.plane.first, c.plane.second
        self.cmd.append(i)
        self.start.append(c.start)
        self.end.append(c.end)
        self.center.append(c.center)
        self.plane.append((pi, pj))
        r0 = math.hypot(c.start[pi] - c.center[pi], c.start[pj] - c.center[pj])
        r1 = math.hypot(c.end[pi] - c.center[pi], c.end[pj] - c.center[pj])
        a0 = math.atan2(c.start[pj] - c.center[pj], c.start[pi] - c.center[pi])
        self.scal.append((r0, r1, a0, sweep, total_s / n))
        self.chords.append(n)

    def chord_counts(self) -> I64:
        import numpy as np

        return np.asarray(self.chords, dtype=np.int64)

    def chunks(self, arcs_per_chunk: int = 0) -> Iterator[tuple[int, F64, F64, F64]]:
        """(first chord row, durations, start points, velocities) of the chords of
        ``arcs_per_chunk`` arcs at a time, in order (bounded temporaries: 100k helices are
        3.4 M chords)."""
        import numpy as np

        arcs_per_chunk = arcs_per_chunk or ARCS_PER_CHUNK
        n_all = self.chord_counts()
        first_all = np.concatenate(([0], np.cumsum(n_all)[:-1]))
        for lo in range(0, len(n_all), arcs_per_chunk):
            hi = min(len(n_all), lo + arcs_per_chunk)
            n = n_all[lo:hi]
            arc = np.repeat(np.arange(hi - lo), n)  # the arc of every chord (within the chunk)
            first = np.concatenate(([0], np.cumsum(n)[:-1]))
            k = np.arange(len(arc)) - first[arc] + 1  # 1..n within each arc
            u = k.astype(np.float64) / n[arc].astype(np.float64)
            s0 = np.asarray(self.start[lo:hi], dtype=np.float64)[arc]
            e0 = np.asarray(self.end[lo:hi], dtype=np.float64)[arc]
            cen = np.asarray(self.center[lo:hi], dtype=np.float64)[arc]
            sc = np.asarray(self.scal[lo:hi], dtype=np.float64)[arc]
            r0, r1, a0, sweep, dur = sc[:, 0], sc[:, 1], sc[:, 2], sc[:, 3], sc[:, 4]
            r, a = r0 + (r1 - r0) * u, a0 + sweep * u
            pts = s0 + (e0 - s0) * u[:, None]
            plane = np.asarray(self.plane[lo:hi], dtype=np.int64)[arc]
            rows = np.arange(len(arc))
            al = a.tolist()
            pts[rows, plane[:, 0]] = cen[rows, plane[:, 0]] + r * np.fromiter(map(math.cos, al), np.float64, len(al))
            pts[rows, plane[:, 1]] = cen[rows, plane[:, 1]] + r * np.fromiter(map(math.sin, al), np.float64, len(al))
            last = first + n - 1
            pts[last] = e0[last]  # the last chord ends on the arc's end point exactly
            p0 = np.empty_like(pts)
            p0[1:] = pts[:-1]
            p0[first] = s0[first]  # the first chord starts on the arc's start point
            yield int(first_all[lo]), dur, p0, (pts - p0) / dur[:, None]


def nominal_trajectory(cmds: Sequence[Command], machine: MachineModel) -> Trajectory:
    """A Trajectory of constant-velocity phases with the nominal (-O0) times.

    One phase per rapid (interpolated) or per axis arrival (independent), one per
    linear move, one per chord of an arc.  ``cmd_index`` indexes ``cmds``; the limit
    is ``RAPID`` for rapids and ``FEED`` for feed moves.  Non-motion commands get no
    phase.  Arcs are chorded in numpy (:class:`_ArcRows`), then merged in command order.
    """
    import numpy as np

    from cncc.ir.frame import AXES
    from cncc.ir.trajectory import Limit, Trajectory

    rows = _Rows()
    arcs = _ArcRows()
    for i, c in enumerate(cmds):
        match c:
            case Rapid():
                _rapid_rows(rows, c, i, machine, int(Limit.RAPID))
            case Linear():
                rows.add(linear_time_s(c), c.start, c.end, i, int(Limit.FEED))
            case Arc():
                arcs.add(c, i)
    if not rows.dur_s and not arcs.cmd:
        return Trajectory.empty(AXES)
    width = len(AXES)
    n_lin = len(rows.dur_s)
    arc_cmd = np.repeat(np.asarray(arcs.cmd, dtype=np.int64), arcs.chord_counts())
    order = np.argsort(np.concatenate((np.asarray(rows.cmd, dtype=np.int64), arc_cmd)), kind="stable")
    total = len(order)  # one command is an arc or not: the stable sort keeps each command's rows in order
    dest = np.empty(total, dtype=np.int64)
    dest[order] = np.arange(total)  # where every row (the other moves', then the chords) goes
    dur, p0, v = np.empty(total), np.empty((total, width)), np.empty((total, width))
    cmd, limit = np.empty(total, dtype=np.int64), np.empty(total, dtype=np.int8)
    if n_lin:
        at = dest[:n_lin]
        dur[at] = rows.dur_s
        p0[at] = np.asarray(rows.p0_mm, dtype=np.float64).reshape(-1, width)
        v[at] = np.asarray(rows.v_mm_s, dtype=np.float64).reshape(-1, width)
        cmd[at] = rows.cmd
        limit[at] = rows.limit
    if arcs.cmd:
        at = dest[n_lin:]
        cmd[at] = arc_cmd
        limit[at] = int(Limit.FEED)
        for lo, c_dur, c_p0, c_v in arcs.chunks():
            part = at[lo:lo + len(c_dur)]
            dur[part], p0[part], v[part] = c_dur, c_p0, c_v
    t0 = np.concatenate(([0.0], np.cumsum(dur)[:-1]))
    # the acceleration and jerk rows are zero: two untouched zero arrays (pages the OS maps on write)
    return Trajectory(t0, dur, p0, v, np.zeros((total, width)), np.zeros((total, width)), cmd, limit, AXES)


# ---- batches of moves -------------------------------------------------------------------
def batch_phases_s(b: MoveBatch, machine: MachineModel) -> tuple[F64, I64] | None:
    """The phase durations :func:`nominal_trajectory` gives the moves of ``b``, from its arrays.

    ``(durations of the phases in order, phases of each move)``; bit for bit the values the
    per-command code gives each move (the same float operations: element-wise in numpy,
    ``math.dist`` for lengths and the scalar arc code per arc, whose libm calls numpy may not
    reproduce).  None when the batch needs the per-command code (constant surface speed).
    """
    import numpy as np

    from cncc.ir.batch import ARC, LINEAR, RAPID

    if b.motion.css is not None:
        return None
    n = len(b)
    starts = b.starts()
    row_s = np.zeros(n, dtype=np.float64)
    chords = np.ones(n, dtype=np.int64)
    lin = np.flatnonzero(b.kind == LINEAR)
    if len(lin):
        d = b.end[lin, :3] - starts[lin, :3]  # math.dist(p, q) is math.hypot of these differences, bit for bit
        length = np.fromiter(map(math.hypot, d[:, 0].tolist(), d[:, 1].tolist(), d[:, 2].tolist()), np.float64,
                             len(lin))
        for k in np.flatnonzero(~(length > 0.0)).tolist():  # only rotary axes move: their length
            length[k] = math.dist(starts[lin[k]].tolist(), b.end[lin[k]].tolist())
        feed = b.feed[lin]
        with np.errstate(divide="ignore", invalid="ignore"):
            row_s[lin] = np.where(feed > 0, length / (feed / 60.0), 0.0)
    rap = np.flatnonzero(b.kind == RAPID)
    independent = machine.rapid_mode is RapidMode.INDEPENDENT and len(rap) > 0
    n_axes = min(len(machine.axes), 6)
    if len(rap) and not independent and n_axes:
        d = np.abs(b.end[rap, :n_axes] - starts[rap, :n_axes])
        rate = np.asarray([a.rapid_mm_min / 60.0 for a in machine.axes[:n_axes]], dtype=np.float64)
        with np.errstate(divide="ignore", invalid="ignore"):
            row_s[rap] = np.where(d > 0, d / rate, 0.0).max(axis=1)
    arcs = np.flatnonzero(b.kind == ARC).tolist()
    if arcs:
        st, en, ce = starts[arcs].tolist(), b.end[arcs].tolist(), b.center[arcs].tolist()
        for k, r, turns, feed_mm_min in zip(range(len(arcs)), arcs, b.turns[arcs].tolist(), b.feed[arcs].tolist(),
                                            strict=True):
            sweep = sweep_rad(st[k], en[k], ce[k], turns, b.plane)
            chords[r] = m = arc_chords(sweep)
            row_s[r] = feed_time_s(helix_length_mm(st[k], en[k], ce[k], sweep, b.plane), feed_mm_min) / m
    counts = np.where(row_s > 0.0, chords, 0)
    if not independent:
        return np.repeat(row_s, counts), counts
    pieces: list[float] = []
    rapid_rows = set(rap.tolist())
    st_all, en_all = starts.tolist(), b.end.tolist()
    for r, (t, m) in enumerate(zip(row_s.tolist(), counts.tolist(), strict=True)):
        if r in rapid_rows:
            phases = independent_rapid_phases_s(st_all[r], en_all[r], machine)
            counts[r] = len(phases)
            pieces += phases
        else:
            pieces += [t] * m
    return np.asarray(pieces, dtype=np.float64), counts
