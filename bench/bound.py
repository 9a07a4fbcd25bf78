"""An independent, jerk-aware lower bound of a program's motion time (no planner code).

Run: ``python bench/bound.py FILE [MACHINE]`` prints ``jerk-aware-bound accel-only-bound``
in seconds.  :func:`lower_bounds_s` works on the commands the planner receives (machine
coordinates).  It imports nothing from ``cncc.passes.planning`` or ``plan``; from the
passes only ``blend.forces_stop`` (which commands the path stops at).

The class of trajectories bounded
---------------------------------
A trajectory ``x(t)`` (XYZ) is *admissible* when

(A1) it is continuous in position and velocity, and on each axis ``|v_i| <= V_i``,
     ``|a_i| <= A_i`` and ``|j_i| <= J_i`` almost everywhere (``V_i`` the axis or rapid
     rate, both capped by the step rate; with ``J = inf`` for the acceleration-only
     bound);
(A2) its path speed is at most the (machine-capped) feed of the command it executes
     (rapids: ``|V|``, the norm of the rapid rates): between its visits of two points of
     one command that lie farther than ``2 d`` from that command's ends, that command's
     cap; between any other two points, the largest cap of the commands passed with one
     neighbour either side (a blend at a junction may run under either command);
(A3) it passes within ``d`` of every point of the programmed path, in program order, with
     ``d`` the larger blend tolerance (programmed G64 P or the machine's) of the
     neighbouring commands plus the arc tolerance;
(A4) it is at rest (all axes, ``v = 0``) at the start, the end, at exact stops (G61/G09,
     an exact-stop machine, rapids on machines whose rapids end in a stop) and where a
     non-motion command forces a stop (dwell, tool change, M0, ... : ``forces_stop``);
(A5) between its visits of the first and the last point of a group of consecutive arcs
     with one centre and radius ``r > d`` it stays in the annulus ``r +- d`` of the plane.

This is what ``verify`` accepts with ``strict_continuity`` on a machine that declares no
velocity steps, *except* that verify's E0618 lets the acceleration step by up to
``J_i T`` at a phase boundary (the controller averages over one period ``T``): such a
plan may beat the bound by about one period per such step.  On machines that declare
velocity steps (speed-step corners, take-off speed) (A1) fails; there only the cruise
and length terms are used (steps do not shorten a distance at a capped speed).

Every step below drops constraints (relaxations only), so the minimum over the
admissible class is at least the bound.

Runs.  (A4) cuts the program into runs, rest to rest; the runs occupy disjoint time
intervals, so their bounds add.  Inside a run every term below bounds the run's time;
their maximum does.

(1) Reversal chains, per direction.  For a unit direction ``w`` (the 3 axes and the 6
    diagonals of the coordinate planes) the projection ``y = w.x`` has, by (A1) and
    ``|sum w_i a_i| <= sum |w_i| A_i``, ``|y'| <= V_w = min(sum |w_i| V_i, path cap)``,
    ``|y''| <= A_w``, ``|y'''| <= J_w``.  By (A3) ``y`` visits the intervals ``[c_k - d,
    c_k + d]`` of the projected points ``c_k`` in order.  Pick alternate checkpoints
    ``k_1 < k_2 < ...`` (high, low, high, ...) whose intervals are separated
    (``c_hi - d > c_lo + d``).  Then ``y`` has a maximum between the visits of the
    neighbouring lows -- interior, so ``y' = 0`` there -- and a minimum between the
    neighbouring highs; taking each extreme over the interval that starts at the previous
    extreme keeps them in order.  Between consecutive extremes (and the rests of the run's
    ends) ``y`` moves from rest to rest over at least ``D = (c_hi - d) - (c_lo + d)``.
    Its time is at least ``T(D)``: the least ``T`` with ``E(T) >= D``, where
    ``E(T) = int_0^T min(V, A t, A (T - t), J t (T - t) / 2) dt`` bounds the distance of
    any such motion of duration ``T`` (``v(0) = v(T) = 0`` and ``|v'| <= A`` give the
    two lines; ``v'' >= -J`` makes ``v - J t (T - t) / 2`` convex and zero at both ends,
    hence ``<= 0``).  The accelerations at the extremes are left free (a relaxation of
    their continuity), which is why ``E`` uses ``A t`` and not the rest-to-rest S-curve.
    The legs are disjoint in time: the run takes at least their sum.  The greedy choice of
    the checkpoints (hysteresis ``2 d``) is one admissible choice; any gives a bound.
(2) Length at the feed.  Between the visits of checkpoints ``p`` and ``q`` the path is at
    least ``|P_q - P_p| - 2 d`` long; over a chain of checkpoints the lengths add (disjoint
    intervals), each at most at its cap (A2): time ``>= sum L / cap``.  The chain that
    maximises the sum of ``L / cap`` over a window of 64 predecessors is found by dynamic
    programming (again any chain is valid).
(3) Length with acceleration: the same total length ``S``, from rest to rest at the run's
    largest cap, with the path acceleration ``|x''| <= |A|`` (norm of the axis limits):
    ``T >= T_acc(S)`` (trapezoid or triangle).
(4) Circles (A5).  In polar coordinates about the centre, ``rho theta'^2 = rho'' - a_r``,
    ``|a_r| <= A_pl = |(A_f, A_s)|``, ``|rho'| <= V``; integrating over the interval
    ``dt`` between the visits, with Cauchy-Schwarz ``int theta'^2 >= Phi^2 / dt`` and
    ``rho >= r - d``: ``(r - d) Phi^2 <= 2 V dt + A_pl dt^2``, so ``dt >= (-V + sqrt(V^2
    + A_pl (r - d) Phi^2)) / A_pl``; ``Phi`` is the swept angle less ``2 asin(d / r)``
    (the visits may sit that far from the ends).  This replaces the feed term (2) of the
    group's pieces when larger.
(5) Corners.  With the chains of (2) forced through the middle ``M`` of every command, the
    interval between the visits of ``M_c`` and ``M_{c+1}`` contains the visit of the corner
    ``P`` (the end of ``c``).  Along ``w``, the unit bisector of ``P - M_c`` and ``P -
    M_{c+1}``, the projection has an interior maximum (``y' = 0``) when ``w.P - d`` exceeds
    both ``w.M + d``: the motion from the first visit to it ends at rest after at least
    ``D1 = w.(P - M_c) - 2 d``, the motion from it to the second visit starts at rest, over
    ``D2``.  In time ``T`` such a motion covers at most ``int_0^T min(V_w, A_w t) dt``, so
    the interval takes at least the two braking times (acceleration only: the jerk needs a
    second rest).  This replaces the piece's feed term when larger.

(6) Jerk-coupled corners (jerk-aware bound only).  In (5) let ``t*`` be the time of the
    extreme of ``y = w_c . x`` between the visits ``t_c`` of ``M_c`` and ``t_c+1`` of
    ``M_c+1``.  Since ``|y'''| <= J_w``, ``y''`` stays within ``J_w |t - t_m|`` of its value
    ``gamma`` at a middle's visit ``t_m``; so on the half from ``t*`` (``y' = 0``) to ``t_m``
    the speed away from the extreme is at most ``f(s) = int_0^s min(A_w, J_w (tau - u) -
    gamma) du`` (``gamma`` signed towards the extreme, ``tau = |t_m - t*|``), and the half
    covers at most ``E(tau, gamma) = int_0^tau min(V_w, f)`` (closed form,
    :func:`half_reach_mm`): it takes at least ``tau(D, gamma)``, increasing in ``gamma``.
    The interval ``[t_c, t_c+1]`` thus takes at least ``max(feed_c, tau(D1, beta_c) +
    tau(D2, alpha_c))`` with ``beta_c = a(t_c) . w_c`` and ``alpha_c = a(t_c+1) . w_c``.  At a
    middle between two corners one acceleration ``a`` gives both: ``alpha = a . w_(c-1)``,
    ``beta = a . w_c``, and with ``|a_i| <= A_i``: ``alpha >= -A_w(c-1)``, ``beta >= -A_w(c)``,
    ``alpha + beta >= -S``, ``S = sum_i |w_(c-1),i + w_c,i| A_i``.  Cutting ``alpha`` into
    cells ``[alpha_k, alpha_k+1]``, any motion has in its cell ``tau(D2, alpha) >=
    tau(D2, alpha_k)`` and ``tau(D1, beta) >= tau(D1, max(-A_w, -S - alpha_k+1))``; the
    least sum over all cell sequences (dynamic programming along each chain of consecutive
    corners) bounds the chain's intervals, which are those of (5), from below.  A chain's
    first ``beta`` and last ``alpha`` are free (``-A_w``).  This is where sharp corners a
    few millimetres apart cost jerk: braking into one corner and pushing away from the
    previous one need opposite accelerations at the middle.

Limitations (it is a bound, not an estimate): the jerk of a centripetal turn and the
accelerations at the extremes are dropped, and (6) couples the corners only through the
middles' accelerations, so it is loose on short sharp-cornered paths; it is tight on
feed-limited long moves.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from cncc.ir.commands import Arc, Command, Linear, Rapid
from cncc.ir.machine import CornerRule, MachineModel
from cncc.ir.pathmode import PathMode
from cncc.passes.blend import forces_stop

DIRECTIONS = np.array([[1, 0, 0], [0, 1, 0], [0, 0, 1],
                       [1, 1, 0], [1, -1, 0], [1, 0, 1], [1, 0, -1], [0, 1, 1], [0, 1, -1]], float)
DIRECTIONS /= np.linalg.norm(DIRECTIONS, axis=1)[:, None]
DP_WINDOW = 64
ARC_STEP_RAD = math.radians(5.0)
MIN_FEED_MM_MIN = 0.1


@dataclass
class _Run:
    pts: list[np.ndarray] = field(default_factory=list)  # XYZ checkpoints
    tol: list[float] = field(default_factory=list)  # d at each checkpoint
    cmd: list[int] = field(default_factory=list)  # index into the run's command caps
    inner: list[bool] = field(default_factory=list)  # farther than 2 d from its command's ends
    mids: dict[int, int] = field(default_factory=dict)  # command -> the checkpoint at its middle
    caps: list[float] = field(default_factory=list)  # path speed cap per command
    axis_caps: list[np.ndarray] = field(default_factory=list)  # (3,) per command
    circles: list[tuple[int, int, float, float, int, int]] = field(default_factory=list)
    # (first checkpoint, last checkpoint, radius, swept angle, plane axes f, s)


@dataclass(frozen=True)
class _Limits:
    v_axis: np.ndarray  # (3,) feed moves
    v_rapid: np.ndarray  # (3,) rapids
    a: np.ndarray
    j: np.ndarray
    steps: bool  # the machine declares velocity steps


def _limits(machine: MachineModel) -> _Limits:
    by = {a.name: a for a in machine.axes}
    v, r, a, j = (np.full(3, np.inf) for _ in range(4))
    declares = machine.corner_rule is CornerRule.SPEED_STEP
    for i, name in enumerate("XYZ"):
        ax = by.get(name)
        if ax is None:
            continue
        step = ax.step.max_step_rate_hz * max(ax.step.gear_cmd, 1) / (ax.step.steps_per_mm * ax.step.gear_cmr)
        v[i] = min(ax.max_velocity_mm_min / 60, step)
        r[i] = min(ax.rapid_mm_min / 60, step)
        a[i], j[i] = ax.max_accel_mm_s2, ax.max_jerk_mm_s3
        declares = declares or ax.start_speed_mm_min > 0
    return _Limits(v, r, a, j, declares)


def _arc_points(cmd: Arc) -> tuple[np.ndarray, float, float, int, int]:
    """Points on the arc (every 5 degrees and at every multiple of 45 degrees), radius, sweep."""
    f, s = cmd.plane.first, cmd.plane.second
    start, end = np.array(cmd.start[:3], float), np.array(cmd.end[:3], float)
    cf, cs = cmd.center[f], cmd.center[s]
    a0 = math.atan2(start[s] - cs, start[f] - cf)
    a1 = math.atan2(end[s] - cs, end[f] - cf)
    r0, r1 = math.hypot(start[f] - cf, start[s] - cs), math.hypot(end[f] - cf, end[s] - cs)
    turns = cmd.turns or 1
    if turns > 0:
        sweep = (a1 - a0) % (2 * math.pi) or 2 * math.pi
        sweep += 2 * math.pi * (turns - 1)
    else:
        sweep = -((a0 - a1) % (2 * math.pi) or 2 * math.pi)
        sweep -= 2 * math.pi * (-turns - 1)
    n = max(2, math.ceil(abs(sweep) / ARC_STEP_RAD))
    frac = list(np.linspace(0, 1, n + 1))
    q = math.pi / 4  # the axis and diagonal extremes lie at multiples of 45 degrees
    lo_k, hi_k = sorted((a0 / q, (a0 + sweep) / q))
    frac += [(k * q - a0) / sweep for k in range(math.ceil(lo_k), math.floor(hi_k) + 1)]
    fr = np.unique(np.clip(np.array(frac), 0.0, 1.0))
    pts = start + (end - start) * fr[:, None]
    rad = r0 + (r1 - r0) * fr
    pts[:, f] = cf + rad * np.cos(a0 + sweep * fr)
    pts[:, s] = cs + rad * np.sin(a0 + sweep * fr)
    return pts, min(r0, r1), abs(sweep), f, s


def _add_line(cur: _Run, cmd: Linear | Rapid, d: float, ci: int) -> None:
    a, b = np.array(cmd.start[:3], float), np.array(cmd.end[:3], float)
    span = float(np.linalg.norm(b - a))
    if span > 6 * d:  # inner points 2 d (and a bit) from the ends, and the middle
        for x in (2.5 * d / span, 0.5, 1 - 2.5 * d / span):
            if x == 0.5:
                cur.mids[ci] = len(cur.pts)
            cur.pts.append(a + (b - a) * x)
            cur.tol.append(d)
            cur.cmd.append(ci)
            cur.inner.append(True)
    cur.pts.append(b)
    cur.tol.append(d)
    cur.cmd.append(ci)
    cur.inner.append(False)


def _runs(cmds: Sequence[Command], machine: MachineModel, lim: _Limits) -> list[_Run]:
    runs: list[_Run] = []
    cur = _Run()
    arc_key: tuple[float, ...] | None = None

    def close() -> None:
        nonlocal cur, arc_key
        if len(cur.pts) > 1:
            runs.append(cur)
        last = (cur.pts[-1], cur.tol[-1]) if cur.pts else None
        cur, arc_key = _Run(), None
        if last is not None:  # the next run starts at rest where this one ended
            cur.pts.append(last[0])
            cur.tol.append(last[1])
            cur.cmd.append(0)
            cur.inner.append(False)
            cur.caps.append(0.0)
            cur.axis_caps.append(np.zeros(3))

    for cmd in cmds:
        if not isinstance(cmd, Rapid | Linear | Arc):
            if forces_stop(cmd, machine):
                close()
            continue
        tol = cmd.motion.blend_tolerance_mm
        d = (machine.blend_tolerance_mm if tol is None else tol) + machine.arc_tolerance_mm
        if isinstance(cmd, Rapid):
            axis_caps = lim.v_rapid
            cap = float(np.linalg.norm(lim.v_rapid))
        else:
            feed = cmd.feed_mm_min if cmd.feed_mm_min > 0 else machine.default_feed_mm_min
            axis_caps = lim.v_axis
            cap = min(max(feed, MIN_FEED_MM_MIN), machine.max_feed_mm_min) / 60
        if not cur.pts:
            cur.pts.append(np.array(cmd.start[:3], float))
            cur.tol.append(d)
            cur.cmd.append(0)
            cur.inner.append(False)
            cur.caps.append(0.0)
            cur.axis_caps.append(np.zeros(3))
        cur.caps.append(cap)
        cur.axis_caps.append(axis_caps)
        ci = len(cur.caps) - 1
        cur.tol[-1] = max(cur.tol[-1], d)
        if isinstance(cmd, Arc):
            pts, radius, sweep, f, s = _arc_points(cmd)
            key = (cmd.center[f], cmd.center[s], round(radius, 9), float(f), float(s))
            first = len(cur.pts) - 1
            along = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
            cur.pts.extend(pts[1:])
            cur.tol.extend([d] * (len(pts) - 1))
            cur.cmd.extend([ci] * (len(pts) - 1))
            cur.inner.extend(bool(x) for x in (along[1:] > 2 * d) & (along[1:] < along[-1] - 2 * d))
            if along[-1] > 6 * d:
                cur.mids[ci] = first + int(np.argmin(np.abs(along - along[-1] / 2)))
            if arc_key == key and cur.circles and cur.circles[-1][1] == first:
                g = cur.circles[-1]
                cur.circles[-1] = (g[0], len(cur.pts) - 1, min(g[2], radius), g[3] + sweep, f, s)
            else:
                cur.circles.append((first, len(cur.pts) - 1, radius, sweep, f, s))
            arc_key = key
        else:
            _add_line(cur, cmd, d, ci)
            arc_key = None
        stop = cmd.motion.mode is PathMode.EXACT_STOP or machine.corner_rule is CornerRule.EXACT_STOP
        if stop or (isinstance(cmd, Rapid) and machine.rapid_ends_in_stop):
            close()
    close()
    return runs


# ---- one-dimensional rest-to-rest legs --------------------------------------------------
def reach_mm(t: np.ndarray, v: np.ndarray, a: np.ndarray, j: np.ndarray) -> np.ndarray:
    """``E(T)``: the largest distance of a motion of duration ``T`` with ``v = 0`` at both
    ends, ``|v| <= V``, ``|v'| <= A``, ``v'' >= -J`` (an upper bound; see the docstring)."""
    h = t / 2  # by symmetry E = 2 int_0^{T/2} min(V, A t, J t (T - t) / 2)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        tc = np.clip(np.where(np.isfinite(j), t - 2 * a / j, h), 0.0, h)  # the line is lower before tc

        def prim(x: np.ndarray) -> np.ndarray:  # int_0^x J t (T - t) / 2 dt
            out: np.ndarray = j / 2 * (t * x * x / 2 - x**3 / 3)
            return out

        def parabola_int(x0: np.ndarray, x1: np.ndarray) -> np.ndarray:
            out: np.ndarray = np.where(np.isfinite(j), prim(x1) - prim(x0), 0.0)
            return out

        # where g(t) = min(A t, parabola) reaches V on [0, T/2]
        tv_line = v / a
        disc = t * t - 8 * v / np.where(np.isfinite(j), j, 1.0)
        tv_par = np.where(disc >= 0, (t - np.sqrt(np.maximum(disc, 0.0))) / 2, np.inf)
        tv = np.where(a * tc >= v, tv_line, np.where(np.isfinite(j), np.maximum(tv_par, tc), np.inf))
        tv = np.minimum(tv, h)
        line_end = np.minimum(tc, tv)
        area = a * line_end**2 / 2 + parabola_int(line_end, np.maximum(tv, line_end)) + v * (h - tv)
    out: np.ndarray = 2 * area
    return out


def leg_time_s(dist: np.ndarray, v: np.ndarray, a: np.ndarray, j: np.ndarray) -> np.ndarray:
    """Least ``T`` with ``E(T) >= dist`` (0 for ``dist <= 0``), by bisection."""
    dist = np.maximum(dist, 0.0)
    jj = np.where(np.isfinite(j), j, 1e300)
    hi = 2 * (dist / v + v / a + a / np.where(np.isfinite(j), j, np.inf)) + 4 * np.cbrt(dist / jj) + 1e-12
    lo = np.zeros_like(dist)
    for _ in range(60):
        mid = (lo + hi) / 2
        ok = reach_mm(mid, v, a, j) >= dist
        hi, lo = np.where(ok, mid, hi), np.where(ok, lo, mid)
    out: np.ndarray = np.where(dist > 0, lo, 0.0)
    return out


def _chain_dists(c: Sequence[float], d: Sequence[float]) -> list[float]:
    """Distances of the legs between alternate separated extremes (hysteresis ``2 d``),
    the run's rests at both ends included."""
    n = len(c)
    legs: list[float] = []
    base_hi, base_lo = c[0] + d[0], c[0] - d[0]  # the last committed element's interval
    cand, kind = -1, 0  # candidate extreme and its type (+1 high, -1 low)
    for k in range(1, n):
        lo, hi = c[k] - d[k], c[k] + d[k]
        if kind == 0:
            if lo > base_hi:
                cand, kind = k, 1
            elif hi < base_lo:
                cand, kind = k, -1
            continue
        if kind == 1:
            if lo > c[cand] - d[cand]:
                cand = k  # a higher high
            elif hi < c[cand] - d[cand]:  # separated below: commit the high
                legs.append((c[cand] - d[cand]) - base_hi)
                base_hi, base_lo = c[cand] + d[cand], c[cand] - d[cand]
                cand, kind = k, -1
        else:
            if hi < c[cand] + d[cand]:
                cand = k
            elif lo > c[cand] + d[cand]:
                legs.append(base_lo - (c[cand] + d[cand]))
                base_hi, base_lo = c[cand] + d[cand], c[cand] - d[cand]
                cand, kind = k, 1
    if kind == 1:  # the last extreme, then the rest at the end
        legs.append((c[cand] - d[cand]) - base_hi)
        legs.append((c[cand] - d[cand]) - (c[-1] + d[-1]))
    elif kind == -1:
        legs.append(base_lo - (c[cand] + d[cand]))
        legs.append((c[-1] - d[-1]) - (c[cand] + d[cand]))
    return [x for x in legs if x > 0]


Leg = tuple[int, float, float, float, float]


def _chain_legs(run: _Run, pts: np.ndarray, tol: np.ndarray, lim: _Limits) -> list[Leg]:
    """(direction, distance, V_w, A_w, J_w) of every leg of (1), all directions."""
    caps = np.array(run.caps[1:])
    axis_caps = np.array(run.axis_caps[1:])
    out: list[Leg] = []
    for di, w in enumerate(DIRECTIONS):
        aw = np.abs(w)
        v = min(float(np.max(axis_caps @ aw)), float(caps.max()))
        a, j = float(np.sum(aw * lim.a)), float(np.sum(aw * lim.j))
        out.extend((di, x, v, a, j) for x in _chain_dists(list(pts @ w), list(tol)))
    return out


LAGS = (1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64)  # predecessors the chain may jump back to


def _range_max(values: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """``max(values[lo:hi + 1])`` elementwise (a sparse table; ``lo <= hi``)."""
    table = [values]
    while (1 << len(table)) <= values.size:
        prev, half = table[-1], 1 << (len(table) - 1)
        table.append(np.maximum(prev[:-half], prev[half:]))
    span = hi - lo + 1
    level = np.floor(np.log2(span)).astype(int)
    out = np.empty(lo.size)
    for lv in np.unique(level):
        sel = level == lv
        t = table[lv]
        out[sel] = np.maximum(t[lo[sel]], t[hi[sel] - (1 << lv) + 1])
    return out


def _length_bounds(run: _Run, pts: np.ndarray, tol: np.ndarray, lim: _Limits, corners: bool = False,
                   pieces: dict[int, tuple[float, float]] | None = None) -> tuple[float, float]:
    """(2) with (4), and (3) of the docstring; with ``corners``, (5): the chains are forced
    through the middle of every command and each corner's term replaces its piece's;
    ``pieces`` (if given) receives per corner ``c`` its feed term and the piece used."""
    n = len(pts)
    cap_of_cmd = np.array(run.caps)
    cmd = np.array(run.cmd)
    inner = np.array(run.inner, bool)
    ncmd = cap_of_cmd.size
    weight, gaps = [], []
    for lag in LAGS:  # the feed term and length of the piece from k - lag to k, for every k
        w, g = np.full(n, -1.0), np.zeros(n)
        if lag < n:
            ks = np.arange(lag, n)
            gap = np.maximum(np.linalg.norm(pts[ks] - pts[ks - lag], axis=1) - tol[ks] - tol[ks - lag], 0.0)
            cap = _range_max(cap_of_cmd, np.maximum(cmd[ks - lag] - 1, 0), np.minimum(cmd[ks] + 1, ncmd - 1))
            own = inner[ks] & inner[ks - lag] & (cmd[ks] == cmd[ks - lag])  # (A2): inside one command
            cap = np.where(own, cap_of_cmd[cmd[ks]], cap)
            w[lag:], g[lag:] = gap / cap, gap
        weight.append(w.tolist())
        gaps.append(g.tolist())
    # chains are forced through the ends of every circle group, (4) replaces their feed term
    cuts = sorted({0, n - 1, *(c[0] for c in run.circles), *(c[1] for c in run.circles),
                   *(run.mids.values() if corners else ())})
    circle_of = {} if corners else {(c[0], c[1]): c for c in run.circles}
    corner_of = {}
    if corners:
        for c, mid in run.mids.items():
            nxt = run.mids.get(c + 1)
            if nxt is not None:
                corner_of[mid, nxt] = int(np.flatnonzero(cmd == c)[-1])  # the end of command c
    cruise, s_total = 0.0, 0.0
    for i0, i1 in itertools.pairwise(cuts):
        best, length = {i0: 0.0}, {i0: 0.0}
        for k in range(i0 + 1, i1 + 1):
            b, ln = -1.0, 0.0
            for li, lag in enumerate(LAGS):
                p = k - lag
                if p < i0:
                    break
                sc = best[p] + weight[li][k]
                if sc > b:
                    b, ln = sc, length[p] + gaps[li][k]
            best[k], length[k] = b, ln
        piece = best[i1]
        group = circle_of.get((i0, i1))
        if group is not None and not lim.steps:
            piece = max(piece, _circle_time_s(group, tol, cap_of_cmd, cmd, lim))
        vertex = corner_of.get((i0, i1))
        if vertex is not None and not lim.steps:
            cap_here = float(cap_of_cmd[max(int(cmd[i0]) - 1, 1):min(int(cmd[i1]) + 2, ncmd)].max())
            feed_piece = piece
            piece = max(piece, _corner_time_s(pts[i0], pts[vertex], pts[i1], float(tol[i0:i1 + 1].max()),
                                              cap_here, lim))
            if pieces is not None:
                pieces[int(cmd[vertex])] = (feed_piece, piece)
        cruise += piece
        s_total += length[i1]
    a_path = float(np.linalg.norm(lim.a))
    v_run = float(cap_of_cmd[1:].max())
    ramp = v_run * v_run / a_path
    t_acc = 2 * math.sqrt(s_total / a_path) if s_total < ramp else s_total / v_run + v_run / a_path
    return cruise, t_acc


def _brake_s(dist: float, v: float, a: float) -> float:
    """Least time to cover ``dist`` ending at rest from any start with ``|v| <= V``,
    ``|v'| <= A``: the distance in time ``T`` is at most ``int_0^T min(V, A t) dt``."""
    if dist <= 0:
        return 0.0
    return math.sqrt(2 * dist / a) if dist <= v * v / (2 * a) else dist / v + v / (2 * a)


def _corner_time_s(p_a: np.ndarray, p: np.ndarray, p_b: np.ndarray, d: float, cap: float, lim: _Limits) -> float:
    """(5): the least time between the visits of ``p_a`` and ``p_b`` with the corner ``p``
    visited between them."""
    e1, e2 = p - p_a, p - p_b
    n1, n2 = float(np.linalg.norm(e1)), float(np.linalg.norm(e2))
    if n1 <= 2 * d or n2 <= 2 * d:
        return 0.0
    w = e1 / n1 + e2 / n2
    nw = float(np.linalg.norm(w))
    if nw < 1e-12:
        return 0.0
    w /= nw
    d1, d2 = float(w @ e1) - 2 * d, float(w @ e2) - 2 * d
    if d1 <= 0 or d2 <= 0:
        return 0.0
    aw = np.abs(w)
    v_w = min(float(aw @ np.maximum(lim.v_axis, lim.v_rapid)), cap)
    a_w = float(aw @ lim.a)
    return _brake_s(d1, v_w, a_w) + _brake_s(d2, v_w, a_w)


def half_reach_mm(tau: np.ndarray, gam: np.ndarray, v: np.ndarray, a: np.ndarray, j: np.ndarray) -> np.ndarray:
    """(6) ``E(tau, gamma)``: the largest distance of a projection ``y`` in time ``tau`` from
    an extreme (``y' = 0``) to a point where ``y'' = gamma`` (signed towards the extreme),
    with ``|y'| <= V``, ``|y''| <= A``, ``|y'''| <= J``: ``y''`` stays within ``J |t - t_m|``
    of its value at the end, so the speed away from the extreme is at most ``f(s) =
    int_0^s min(A, J (tau - u) - gamma) du`` and ``E = int_0^tau min(V, f)`` (closed form;
    ``f`` is concave: ``A s`` up to ``u0``, then a parabola)."""
    c = j * tau - gam
    u0 = np.clip((c - a) / j, 0.0, tau)
    g0 = np.minimum(a, c)

    def prim(x: np.ndarray) -> np.ndarray:  # int_0^x f
        sig = np.maximum(x - u0, 0.0)
        lin = np.minimum(x, u0)
        out: np.ndarray = a * lin * lin / 2 + a * u0 * sig + g0 * sig * sig / 2 - j * sig**3 / 6
        return out

    with np.errstate(invalid="ignore", divide="ignore"):
        disc = g0 * g0 - 2 * j * (v - a * u0)
        root = np.sqrt(np.maximum(disc, 0.0))
        on_line = a * u0 >= v
        s1 = np.where(on_line, v / a, u0 + (g0 - root) / j)
        s2 = np.minimum(u0 + (g0 + root) / j, tau)
        over = (on_line | ((disc > 0) & (g0 > 0))) & (s1 < s2)
        cut = np.where(over, prim(s2) - prim(s1) - v * (s2 - s1), 0.0)
    out: np.ndarray = prim(tau) - np.maximum(cut, 0.0)
    return out


def half_leg_s(dist: np.ndarray, gam: np.ndarray, v: np.ndarray, a: np.ndarray, j: np.ndarray) -> np.ndarray:
    """Least ``tau`` with ``E(tau, gamma) >= dist`` (0 for ``dist <= 0``), by bisection."""
    dist = np.maximum(dist, 0.0)
    gam = np.clip(gam, -a, a)
    hi = np.sqrt(2 * dist / a) + dist / v + 4 * a / j + 2 * np.cbrt(6 * dist / j) + 1e-9
    for _ in range(60):  # make sure hi is feasible
        short = half_reach_mm(hi, gam, v, a, j) < dist
        if not short.any():
            break
        hi = np.where(short, 2 * hi, hi)
    lo = np.zeros_like(dist)
    for _ in range(44):
        mid = (lo + hi) / 2
        ok = half_reach_mm(mid, gam, v, a, j) >= dist
        hi, lo = np.where(ok, mid, hi), np.where(ok, lo, mid)
    out: np.ndarray = np.where(dist > 0, lo, 0.0)
    return out


PAIR_CELLS = 24

Corner = tuple[np.ndarray, float, float, float, float, float]


def _corner_halves(run: _Run, pts: np.ndarray, tol: np.ndarray, lim: _Limits) -> dict[int, Corner]:
    """Per corner ``c`` (the end of command ``c``) with an interior extreme along its bisector
    ``w`` between the middles of ``c`` and ``c + 1`` (as in (5)): ``(w, D1, D2, V_w, A_w, J_w)``."""
    cap_of_cmd = np.array(run.caps)
    cmd = np.array(run.cmd)
    ncmd = cap_of_cmd.size
    corners: dict[int, Corner] = {}
    for c, mid in run.mids.items():
        nxt = run.mids.get(c + 1)
        if nxt is None:
            continue
        vertex = int(np.flatnonzero(cmd == c)[-1])
        e1, e2 = pts[vertex] - pts[mid], pts[vertex] - pts[nxt]
        d = float(tol[mid:nxt + 1].max())
        n1, n2 = float(np.linalg.norm(e1)), float(np.linalg.norm(e2))
        if n1 <= 2 * d or n2 <= 2 * d:
            continue
        w = e1 / n1 + e2 / n2
        nw = float(np.linalg.norm(w))
        if nw < 1e-12:
            continue
        w /= nw
        d1, d2 = float(w @ e1) - 2 * d, float(w @ e2) - 2 * d
        if d1 <= 0 or d2 <= 0:
            continue
        aw = np.abs(w)
        cap_here = float(cap_of_cmd[max(c - 1, 1):min(c + 2, ncmd)].max())
        v_w = min(float(aw @ np.maximum(lim.v_axis, lim.v_rapid)), cap_here)
        corners[c] = (w, d1, d2, v_w, float(aw @ lim.a), float(aw @ lim.j))
    return corners


def _corner_chain_s(run: _Run, pts: np.ndarray, tol: np.ndarray, lim: _Limits,
                    pieces: dict[int, tuple[float, float]]) -> float:
    """(6): what the jerk adds to (5), see the module docstring; ``pieces[c] = (feed, used)``
    are corner ``c``'s feed term and the (5) piece the length bound used for it."""
    corners = _corner_halves(run, pts, tol, lim)
    chain = sorted(c for c in corners if c in pieces)
    if not chain:
        return 0.0
    n, cells = len(chain), PAIR_CELLS
    grid = np.linspace(0.0, 1.0, cells + 1)
    prev_in_chain = np.array([i > 0 and chain[i - 1] == chain[i] - 1 for i in range(n)])
    next_in_chain = np.append(prev_in_chain[1:], False)
    w = np.array([corners[c][0] for c in chain])
    d1, d2, v_w, a_w, j_w = (np.array([corners[c][i] for c in chain]) for i in range(1, 6))
    # in-half of corner c: beta at M_c, cell k's right end of the previous corner's alpha cells
    s_sum = np.zeros(n)
    s_sum[1:] = (np.abs(w[1:] + w[:-1]) @ lim.a)
    a_prev = np.concatenate([[0.0], a_w[:-1]])
    alpha_prev = -a_prev[:, None] + 2 * a_prev[:, None] * grid[None, 1:]
    beta = np.where(prev_in_chain[:, None], np.maximum(-a_w[:, None], -s_sum[:, None] - alpha_prev), -a_w[:, None])
    # out-half of corner c: alpha at M_(c+1), cell l's left end
    alpha = np.where(next_in_chain[:, None], -a_w[:, None] + 2 * a_w[:, None] * grid[None, :-1], -a_w[:, None])
    shape = (n, cells)

    def flat(x: np.ndarray) -> np.ndarray:
        return np.broadcast_to(x[:, None], shape).ravel()

    t_in = half_leg_s(flat(d1), beta.ravel(), flat(v_w), flat(a_w), flat(j_w)).reshape(shape)
    t_out = half_leg_s(flat(d2), alpha.ravel(), flat(v_w), flat(a_w), flat(j_w)).reshape(shape)
    excess = 0.0
    best = np.zeros(1)
    for i, c in enumerate(chain):
        feed, used = pieces[c]
        tin = t_in[i] if prev_in_chain[i] else t_in[i, :1]
        tout = t_out[i] if next_in_chain[i] else t_out[i, :1]
        cost = np.maximum(np.maximum(feed, tin[:, None] + tout[None, :]), used) - used
        best = (best[:, None] + cost).min(axis=0)
        if not next_in_chain[i]:  # the chain ends: one state left
            excess += float(best.min())
            best = np.zeros(1)
    return excess


def _circle_time_s(group: tuple[int, int, float, float, int, int], tol: np.ndarray, cap_of_cmd: np.ndarray,
                   cmd: np.ndarray, lim: _Limits) -> float:
    """(4): the least time between the visits of a circle group's first and last points."""
    first, last, radius, sweep, f, s = group
    d = float(tol[first:last + 1].max())
    if radius <= d or max(f, s) > 2:
        return 0.0
    phi = sweep - 2 * math.asin(d / radius)
    if phi <= 0:
        return 0.0
    a_pl = math.hypot(lim.a[f], lim.a[s])
    lo, hi = max(int(cmd[first + 1]) - 1, 1), min(int(cmd[last]) + 1, cap_of_cmd.size - 1)
    v_pl = float(cap_of_cmd[lo:hi + 1].max())
    return (-v_pl + math.sqrt(v_pl * v_pl + a_pl * (radius - d) * phi * phi)) / a_pl


def lower_bounds_s(cmds: Sequence[Command], machine: MachineModel) -> tuple[float, float]:
    """(jerk-aware bound, acceleration-only bound) in seconds of motion."""
    lim = _limits(machine)
    runs = _runs(cmds, machine, lim)
    length_terms = np.zeros(len(runs))
    jerk_terms = np.zeros(len(runs))  # (6): the jerk-aware bound only
    legs: list[tuple[int, int, float, float, float, float]] = []
    for r, run in enumerate(runs):
        pts, tol = np.array(run.pts), np.array(run.tol)
        cruise, t_acc = _length_bounds(run, pts, tol, lim)
        length_terms[r] = cruise if lim.steps else max(cruise, t_acc, _length_bounds(run, pts, tol, lim, True)[0])
        if not lim.steps:
            pieces: dict[int, tuple[float, float]] = {}
            with_corners = _length_bounds(run, pts, tol, lim, True, pieces)[0]
            jerk_terms[r] = with_corners + _corner_chain_s(run, pts, tol, lim, pieces)
        # (velocity steps: only the feed term)
        if not lim.steps:
            legs.extend((r, *leg) for leg in _chain_legs(run, pts, tol, lim))
    if not legs:
        total = float(length_terms.sum())
        return float(np.maximum(length_terms, jerk_terms).sum()), total
    arr = np.array(legs)
    run_i, dir_i = arr[:, 0].astype(int), arr[:, 1].astype(int)
    out = []
    for jerk, extra in ((arr[:, 5], jerk_terms), (np.full(arr.shape[0], np.inf), np.zeros(len(runs)))):
        t = leg_time_s(arr[:, 2], arr[:, 3], arr[:, 4], jerk)
        per = np.zeros((len(runs), DIRECTIONS.shape[0]))
        np.add.at(per, (run_i, dir_i), t)
        out.append(float(np.maximum(np.maximum(length_terms, extra), per.max(axis=1)).sum()))
    return out[0], out[1]


def lower_bound_s(cmds: Sequence[Command], machine: MachineModel) -> float:
    """The jerk-aware bound (seconds)."""
    return lower_bounds_s(cmds, machine)[0]


def program_bounds_s(path: str, machine_name: str = "generic-mill") -> tuple[float, float]:
    """Compile ``path`` as ``--emit=timing`` does, capture the planner's input, bound it."""
    import os

    from cncc.cli import main
    from cncc.machines import load_machine
    from cncc.passes import plan

    captured: list[list[Command]] = []
    real = plan.plan_commands

    def spy(cmds: Sequence[Command], machine: MachineModel, *args: object, **kw: object) -> object:
        captured.append(list(cmds))
        return real(cmds, machine, *args, **kw)  # type: ignore[arg-type]

    plan.plan_commands = spy  # type: ignore[assignment]
    try:
        main([path, "-m", machine_name, "--emit=timing", "-O1", "-fno-verify", "-q", "-o", os.devnull])
    finally:
        plan.plan_commands = real
    if not captured:
        return math.nan, math.nan
    return lower_bounds_s(captured[0], load_machine(machine_name))


if __name__ == "__main__":
    import sys

    jb, ab = program_bounds_s(sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else "generic-mill")
    print(f"{jb:.9g} {ab:.9g}")
