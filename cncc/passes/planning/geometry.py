"""Commands -> runs: the path between two stops, as a polyline with per-piece data.

Consumes IR commands in machine coordinates; yields runs, one at a time.  A run starts
and ends at rest.  A run is either a :class:`PathRun` (lines, interpolated rapids and
arcs as chords, in order) or an :class:`IndependentRapid` (a dog-leg G00 whose axes
each move at their own rate).  Runs are cut where a command ends in exact stop
(G09/G61/G60, ``rapid_ends_in_stop``), where a non-motion command forces a stop
(:func:`cncc.passes.blend.forces_stop`) and around independent rapids.

At -O2 (:data:`NATIVE_ARCS`) and -O1 (:data:`O1_NATIVE_ARCS`, not on SZGH speed-step
machines) an arc or helix is **one piece** whose exact shape is a row
of :class:`cncc.ir.trajectory.Geometry` (``PathRun.geo`` / ``PathRun.arcs``): the planner
plans it on its path coordinate with centripetal limits (``segments.py``).  Otherwise arcs
become chords whose sagitta is within ``min(arc_tolerance_mm, blend
tolerance)``; for -O3 the chords are also short enough that one chord takes about one
interpolation period at the centripetal speed (see ``blending.py``).
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field

import numpy as np

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink
from cncc.ir.commands import Arc, Command, Linear, PathMode, Rapid
from cncc.ir.machine import CornerRule, MachineModel, RapidMode
from cncc.ir.trajectory import FloatArray, Geometry
from cncc.passes.blend import forces_stop
from cncc.passes.planning.limits import AxisLimits

MIN_FEED_MM_MIN = 0.1
"""Smallest feed the planners take (mm/min): below it the times are absurd and the
floating-point error of hour-long phases reaches the verify tolerances."""

CHORD_SAFETY = 0.8
"""Share of the velocity-step budget a spaced arc chord's step may take."""

NORMAL_SHARE = 0.5
"""Share of each axis' acceleration that velocity steps at chord vertices may use."""

NATIVE_ARCS = True
"""-O2 plans arcs and helices as one piece on their exact geometry (False: chords, as -O3)."""

O1_NATIVE_ARCS = True
"""-O1 too plans arcs and helices as one piece on their path coordinate (with the centripetal
caps of ``segments.py``), except on SZGH speed-step machines, whose controller model steps
the speed at chord vertices (False: chords, grbl-style, for every -O1 plan)."""


def native_arcs(level: int, machine: MachineModel) -> bool:
    """Whether a plan at ``-O<level>`` on ``machine`` keeps arcs as one exact piece."""
    if level == 2:
        return NATIVE_ARCS
    return level == 1 and O1_NATIVE_ARCS and machine.corner_rule is not CornerRule.SPEED_STEP


@dataclass
class PathRun:
    """A polyline run. ``k`` pieces, ``k + 1`` points; arrays are numpy."""

    points: FloatArray  # (k+1, 6)
    cmd: np.ndarray  # (k,) int64, index of the command of each piece
    rapid: np.ndarray  # (k,) bool
    feed_mm_s: FloatArray  # (k,) programmed path feed (inf for rapids)
    tol_mm: FloatArray  # (k,) blend tolerance of the piece's command
    arc_vertex: np.ndarray  # (k+1,) bool, vertex strictly inside one arc
    stop_cmd: int = -1  # command whose stop ends the run (for reports)
    origin: np.ndarray | None = None  # (k+1,) index of the unrounded point each point comes from
    geo: np.ndarray | None = None  # (k,) int64, row of ``arcs`` of each arc piece, -1 for straight pieces
    arcs: Geometry | None = None  # exact shape of the arc pieces

    @property
    def straight(self) -> np.ndarray:
        """``(k,)`` bool: pieces that are straight lines (the others are native arcs)."""
        if self.geo is None:
            return np.ones(self.cmd.size, bool)
        out: np.ndarray = self.geo < 0
        return out


@dataclass
class IndependentRapid:
    start: FloatArray  # (6,)
    end: FloatArray  # (6,)
    cmd: int


Run = PathRun | IndependentRapid


@dataclass
class _Builder:
    """Collects the pieces of a run in plain lists (one row per piece end point)."""

    start: tuple[float, ...] | None = None
    points: list[tuple[float, ...]] = field(default_factory=list)
    cmd: list[int] = field(default_factory=list)
    rapid: list[bool] = field(default_factory=list)
    feed: list[float] = field(default_factory=list)
    tol: list[float] = field(default_factory=list)
    arcv: list[bool] = field(default_factory=list)  # the piece's end point is inside an arc
    geo: list[int] = field(default_factory=list)  # row of ``arcs`` (native arc pieces) or -1
    arcs: list[Geometry] = field(default_factory=list)
    native: bool = False  # -O2: the run keeps ``geo`` even without arcs (its corners become blend arcs)

    def add_line(self, start: tuple[float, ...], end: tuple[float, ...], cmd: int, rapid: bool, feed: float,
                 tol: float) -> None:
        if self.start is None:
            self.start = start
        self.points.append(end)
        self.cmd.append(cmd)
        self.rapid.append(rapid)
        self.feed.append(feed)
        self.tol.append(tol)
        self.arcv.append(False)
        self.geo.append(-1)

    def add_native_arc(self, start: tuple[float, ...], end: tuple[float, ...], shape: Geometry, cmd: int,
                       feed: float, tol: float) -> None:
        last = self.points[-1] if self.points else self.start
        if last is not None and max(abs(a - b) for a, b in zip(last, start, strict=True)) > 1e-9:
            self.add_line(last, start, cmd, False, feed, tol)  # reach the arc's start (chords do so too)
        self.add_line(start, end, cmd, False, feed, tol)
        self.geo[-1] = len(self.arcs)
        self.arcs.append(shape)

    def add_arc(self, start: tuple[float, ...], pts: FloatArray, cmd: int, feed: float, tol: float) -> None:
        if self.start is None:
            self.start = start
        q = pts.shape[0]
        self.points.extend(map(tuple, pts.tolist()))
        self.cmd.extend([cmd] * q)
        self.rapid.extend([False] * q)
        self.feed.extend([feed] * q)
        self.tol.extend([tol] * q)
        self.arcv.extend([True] * (q - 1) + [False])
        self.geo.extend([-1] * q)

    def finish(self) -> PathRun | None:
        if self.start is None:
            return None
        pts = np.array([self.start, *self.points], dtype=float)
        arcv = np.array([False, *self.arcv], dtype=bool)
        arcv[-1] = False
        geo = np.array(self.geo, dtype=np.int64) if self.arcs or self.native else None
        arcs = Geometry.concat(self.arcs, pts.shape[1]) if self.arcs or self.native else None
        return PathRun(pts, np.array(self.cmd, dtype=np.int64), np.array(self.rapid, dtype=bool),
                       np.array(self.feed, dtype=float), np.array(self.tol, dtype=float), arcv, geo=geo, arcs=arcs)


def build_runs(cmds: Sequence[Command], machine: MachineModel, limits: AxisLimits, level: int,
               sink: DiagnosticSink) -> Iterator[Run]:
    """Split the command list into runs (see the module docstring), each yielded as soon as
    it is closed (the planner holds one run at a time)."""
    native = level == 2 and NATIVE_ARCS
    exact_arcs = native_arcs(level, machine)
    b = _Builder(native=native)
    warned: set[str] = set()
    for index, cmd in enumerate(cmds):
        match cmd:
            case Rapid() | Linear() | Arc():
                _check_axes(cmd, limits, sink, warned)
                if isinstance(cmd, Rapid) and machine.rapid_mode is RapidMode.INDEPENDENT:
                    yield from _closed(b)
                    b = _Builder(native=native)
                    yield IndependentRapid(np.array(cmd.start, float), np.array(cmd.end, float), index)
                    continue
                _add_motion(b, cmd, index, machine, limits, level, sink, warned, exact_arcs)
                if cmd.motion.mode is PathMode.EXACT_STOP or (isinstance(cmd, Rapid) and machine.rapid_ends_in_stop):
                    yield from _closed(b)
                    b = _Builder(native=native)
            case _:
                if forces_stop(cmd, machine):
                    yield from _closed(b)
                    b = _Builder(native=native)
    yield from _closed(b)


def _closed(b: _Builder) -> Iterator[PathRun]:
    run = b.finish()
    if run is not None:
        yield run


def _add_motion(b: _Builder, cmd: Rapid | Linear | Arc, index: int, machine: MachineModel, limits: AxisLimits,
                level: int, sink: DiagnosticSink, warned: set[str], exact_arcs: bool) -> None:
    tol = cmd.motion.blend_tolerance_mm
    tol_mm = machine.blend_tolerance_mm if tol is None else max(tol, 0.0)
    if isinstance(cmd, Rapid):
        b.add_line(cmd.start, cmd.end, index, True, math.inf, tol_mm)
        return
    feed = _feed_mm_s(cmd, machine, sink, warned)
    if isinstance(cmd, Linear):
        b.add_line(cmd.start, cmd.end, index, False, feed, tol_mm)
        return
    if exact_arcs:
        shape = arc_geometry(cmd)
        if shape is not None:
            b.add_native_arc(cmd.start, cmd.end, shape, index, feed, tol_mm)
            return
    chord_max = _arc_chord_max(cmd, feed, machine, limits) if level >= 2 else math.inf
    sag = min(machine.arc_tolerance_mm, tol_mm) if tol_mm > 0 else machine.arc_tolerance_mm
    b.add_arc(cmd.start, arc_points(cmd, sag, chord_max)[1:], index, feed, tol_mm)


def _feed_mm_s(cmd: Linear | Arc, machine: MachineModel, sink: DiagnosticSink, warned: set[str]) -> float:
    feed = cmd.feed_mm_min
    if isinstance(cmd, Linear) and cmd.motion.css is not None:  # CSS: the slowest feed along the move
        css = cmd.motion.css
        feed = css.slowest_feed_mm_min(cmd.start, cmd.end, cmd.frame.total_offset_mm[css.axis])
    if not feed > 0:
        sink.emit(dg.BAD_FEED, cmd.span, f"feed {feed:g} mm/min is not positive; using the machine default "
                  f"{machine.default_feed_mm_min:g} mm/min")
        feed = machine.default_feed_mm_min
    if feed < MIN_FEED_MM_MIN:
        sink.emit(dg.FEED_TOO_SMALL, cmd.span, f"feed {feed:g} mm/min is below the smallest feed the planner "
                  f"handles; planned at {MIN_FEED_MM_MIN:g} mm/min")
        feed = MIN_FEED_MM_MIN
    if feed > machine.max_feed_mm_min and "feed" not in warned:
        warned.add("feed")
        sink.emit(dg.FEED_CLAMPED, cmd.span, f"feed {feed:g} mm/min is above the machine's cap "
                  f"{machine.max_feed_mm_min:g} mm/min (clamped; reported once)")
    return feed / 60.0


def _check_axes(cmd: Rapid | Linear | Arc, limits: AxisLimits, sink: DiagnosticSink, warned: set[str]) -> None:
    for i, (a, b) in enumerate(zip(cmd.start, cmd.end, strict=True)):
        if not limits.present[i] and abs(a - b) > 1e-9 and f"axis{i}" not in warned:
            warned.add(f"axis{i}")
            sink.emit(dg.AXIS_NOT_ON_MACHINE, cmd.span,
                      f"axis {'XYZABC'[i]} moves but the machine has no such axis "
                      "(planned with the first axis' limits)")


def _arc_chord_max(cmd: Arc, feed_mm_s: float, machine: MachineModel, limits: AxisLimits) -> float:
    """Chord length that one interpolation period covers at the arc's speed limit."""
    f, s = cmd.plane.first, cmd.plane.second
    radius = math.hypot(cmd.start[f] - cmd.center[f], cmd.start[s] - cmd.center[s])
    a_plane = float(min(limits.amax_mm_s2[f], limits.amax_mm_s2[s]))
    v = min(feed_mm_s, math.sqrt(NORMAL_SHARE * a_plane * max(radius, 1e-9)))
    t = machine.interpolation_period_s
    # below the centripetal speed a longer chord keeps its vertex step v c / r within the
    # velocity-step budget NORMAL_SHARE * a * T (the steps then no longer overlap): fewer
    # chords for the same caps (equal to v T at the centripetal speed)
    spaced = CHORD_SAFETY * NORMAL_SHARE * a_plane * t * max(radius, 1e-9) / max(v, 1e-9)
    return max(1.02 * v * t + 2.2 * t * t * a_plane, spaced, 1e-4)


def _sweep(cmd: Arc) -> tuple[float, float, float, float]:
    """Start radius, end radius, start angle and signed sweep (rad) of the arc in its plane."""
    f, s = cmd.plane.first, cmd.plane.second
    cf, cs = cmd.center[f], cmd.center[s]
    start, end = cmd.start, cmd.end
    r0 = math.hypot(start[f] - cf, start[s] - cs)
    r1 = math.hypot(end[f] - cf, end[s] - cs)
    a0 = math.atan2(start[s] - cs, start[f] - cf)
    a1 = math.atan2(end[s] - cs, end[f] - cf)
    turns = cmd.turns if cmd.turns != 0 else 1
    if turns > 0:
        sweep = (a1 - a0) % (2 * math.pi)
        sweep = sweep if sweep > 1e-9 else 2 * math.pi
        sweep += 2 * math.pi * (turns - 1)
    else:
        sweep = -((a0 - a1) % (2 * math.pi))
        sweep = sweep if sweep < -1e-9 else -2 * math.pi
        sweep -= 2 * math.pi * (-turns - 1)
    return r0, r1, a0, sweep


def arc_geometry(cmd: Arc) -> Geometry | None:
    """The exact shape of an arc or helix as one :class:`Geometry` row (None: degenerate).

    ``s`` runs over the helix length ``hypot(sweep * r, axial)``; the radius changes
    linearly from the start's to the end's (``dr``), so the end point is exact."""
    f, s = cmd.plane.first, cmd.plane.second
    r0, r1, a0, sweep = _sweep(cmd)
    if max(r0, r1) < 1e-9:
        return None
    start = np.array(cmd.start, float)
    end = np.array(cmd.end, float)
    axial = end - start
    axial[[f, s]] = 0.0
    c = start.copy()
    c[f], c[s] = cmd.center[f], cmd.center[s]
    circle = _exact_circle(start[[f, s]], end[[f, s]], np.array([c[f], c[s]]), sweep)
    if circle is not None:  # a circle through both ends: |p'| = 1, no radius change
        (c[f], c[s]), r0 = circle
        r1 = r0
        a0 = math.atan2(start[s] - c[s], start[f] - c[f])
    length = math.hypot(abs(sweep) * (r0 + r1) / 2, float(np.linalg.norm(axial)))
    if length < 1e-9:
        return None
    e1, e2 = np.zeros(6), np.zeros(6)
    e1[f], e2[s] = 1.0, 1.0
    one = np.ones(1)
    return Geometry(c[None, :], e1[None, :], e2[None, :], (axial / length)[None, :], one * r0,
                    one * ((r1 - r0) / length), one * a0, one * (sweep / length), one * length)


def _exact_circle(p0: FloatArray, p1: FloatArray, centre: FloatArray, sweep: float
                  ) -> tuple[tuple[float, float], float] | None:
    """Centre and radius of the circle through ``p0`` and ``p1`` (in the plane) that sweeps
    ``sweep`` between them, next to the programmed ``centre`` (whose two radii may differ a
    little, within arc-check's tolerance); None where the ends already share the radius or
    the chord is too short to tell."""
    if abs(float(np.linalg.norm(p0 - centre)) - float(np.linalg.norm(p1 - centre))) < 1e-12:
        return None
    chord = p1 - p0
    half = float(np.linalg.norm(chord)) / 2
    sin_half = abs(math.sin(sweep / 2))
    if half < 1e-9 or sin_half < 1e-6:
        return None
    radius = half / sin_half
    mid = (p0 + p1) / 2
    normal = np.array([-chord[1], chord[0]]) / (2 * half)
    h = math.sqrt(max(radius * radius - half * half, 0.0))
    best = min((mid + h * normal, mid - h * normal), key=lambda c: float(np.linalg.norm(c - centre)))
    return (float(best[0]), float(best[1])), radius


def arc_points(cmd: Arc, sag_mm: float, chord_max_mm: float = math.inf) -> FloatArray:
    """Points of the arc or helix from start to end (both included), shape ``(N+1, 6)``."""
    f, s = cmd.plane.first, cmd.plane.second
    start = np.array(cmd.start, float)
    end = np.array(cmd.end, float)
    cf, cs = cmd.center[f], cmd.center[s]
    r0, r1, a0, sweep = _sweep(cmd)
    r = max(r0, r1, 1e-9)
    dtheta = 2 * math.acos(max(1 - sag_mm / r, -1.0)) if sag_mm < r else math.pi / 2
    other = float(np.linalg.norm(np.delete(end - start, [f, s])))
    length = math.hypot(abs(sweep) * r, other)
    n = max(1, math.ceil(abs(sweep) / max(dtheta, 1e-9)), math.ceil(length / chord_max_mm))
    n = min(n, 2_000_000)
    frac = np.linspace(0.0, 1.0, n + 1)
    ang = a0 + sweep * frac
    rad = r0 + (r1 - r0) * frac
    pts = start[None, :] + (end - start)[None, :] * frac[:, None]
    pts[:, f] = cf + rad * np.cos(ang)
    pts[:, s] = cs + rad * np.sin(ang)
    pts[-1] = end
    out: FloatArray = pts
    return out
