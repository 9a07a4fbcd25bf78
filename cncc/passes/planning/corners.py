"""-O2/-O3 on blending machines: round every corner, or stop where stopping is faster.

Consumes a :class:`PathRun`; produces the run's parts (rest to rest) as
``(Segments, Phases)`` pairs, each profiled by the caller's ``profile`` function.

A rounded corner that is nearly a stop (a sharp corner within a small tolerance) can
cost more than a real stop: the velocity-step rule takes acceleration from the chords
of the blend, and the jerk filter's window carries that smaller acceleration into the
braking before the corner, while a stop lets ruckig brake and start with the full
limits.  So, per corner:

1. *candidates*: corners between two straight commands whose rounded speed (the
   centripetal speed of the blend arc, an upper bound of what the velocity-step rule
   leaves) is below :data:`SLOW_CORNER` times the neighbouring speed caps;
2. for every candidate, the two commands around it are planned from rest to rest with
   the corner rounded — all candidates at once, as one chain of independent windows
   (one TOPP, no filter: a filtered part lasts its unfiltered time plus ``Tf``);
3. the corner stops when the two commands' rest-to-rest ruckig times (what a stop
   costs when the neighbouring corners stop too) are shorter;
4. the run is planned once, with those stops.

Both sides of the comparison start and end at rest, so the estimate isolates the
corner; it is exact for polygons whose corners all stop and a close estimate where a
neighbour is rounded.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import NamedTuple

import numpy as np

from cncc.ir.machine import MachineModel
from cncc.ir.trajectory import FloatArray, IntArray
from cncc.passes.planning.geometry import NORMAL_SHARE, PathRun
from cncc.passes.planning.limits import AxisLimits, path_limit
from cncc.passes.planning.profile import Phases
from cncc.passes.planning.segments import Segments

SLOW_CORNER = 0.7
"""A corner whose blend-arc speed is below this share of the neighbouring caps may stop."""

Part = tuple[Segments, Phases]


def plan_blended(run: PathRun, machine: MachineModel, limits: AxisLimits,
                 profile: Callable[[Segments], Phases], decide_stops: bool = True, whole: bool = False
                 ) -> list[Part]:
    """The run's parts, profiled; ``decide_stops`` runs the stop-or-round decision (for the
    filter planner of -O3; -O2 decides in closed form); ``whole`` keeps the run in one
    part, its stops as zero vertex caps (the S-curve planner plans them itself)."""
    if not decide_stops:
        from cncc.passes.planning.smoothing import snap_short_moves

        run = snap_short_moves(run)
    cand = candidates(run, limits, machine)
    if not cand.any():
        stop = None
    elif decide_stops:
        stop = faster_stops(run, cand, limits, machine)
    else:
        speeds, seg, caps = _blend_speeds(run, machine, limits)
        stop = closed_form_stops(run, cand, limits, machine, speeds)
        if whole and seg is not None and caps is not None and seg.vorigin is not None:
            # stops only where the rounding left the corner sharp: the same geometry
            rounded = np.bincount(seg.vorigin, minlength=run.points.shape[0]) > 1
            if not (stop & rounded).any():
                seg.vvert[1:-1] = np.minimum(seg.vvert[1:-1], np.where(stop[seg.vorigin[1:-1]], 0.0, caps))
                return [(seg, profile(seg))]
        del seg, caps, speeds  # the run is rounded again with its stops: not both at once in memory
    return [(part, profile(part)) for part in rounded_parts(run, stop, machine, limits, whole)]


def rounded_parts(run: PathRun, stop: np.ndarray | None, machine: MachineModel, limits: AxisLimits,
                  whole: bool = False) -> list[Segments]:
    """The run rounded except at ``stop`` (``(k+1,)`` bool), cut into parts at rest."""
    from cncc.passes.planning.blending import velocity_step_caps
    from cncc.passes.planning.segments import make_segments, split_at_stops

    if stop is not None and not stop.any():
        stop = None
    seg = make_segments(_rounded(run, limits, machine, stop), limits, machine)
    if seg is None:
        return []
    if seg.count >= 2:
        native = run.geo is not None
        caps = continuous_caps(seg, velocity_step_caps(seg, limits, machine.interpolation_period_s), native)
        if stop is not None and seg.vorigin is not None:
            caps = np.where(stop[seg.vorigin[1:-1]], 0.0, caps)
        seg.vvert[1:-1] = np.minimum(seg.vvert[1:-1], caps)
    return [seg] if whole else split_at_stops(seg)


def candidates(run: PathRun, limits: AxisLimits, machine: MachineModel) -> np.ndarray:
    """Interior points of the (unrounded) run that may become stops, ``(k+1,)`` bool."""

    k = run.cmd.size
    cand = np.zeros(k + 1, bool)
    if k < 2:
        return cand
    base = run.cmd - run.cmd.min()
    single = (np.bincount(base)[base] == 1) & run.straight  # the piece is its whole command (a line)
    v = 1 + np.flatnonzero((run.cmd[:-1] != run.cmd[1:]) & single[:-1] & single[1:] & ~run.arc_vertex[1:-1])
    if v.size == 0:
        return cand
    g = _corner_geometry(run, v, limits, machine)
    len_in, v_in, len_out, v_out, half = g.len_in, g.v_in, g.len_out, g.v_out, g.half
    radius = np.nan_to_num(g.radius_mm, nan=np.inf, posinf=np.inf)
    with np.errstate(invalid="ignore"):  # 0 * inf: no normal acceleration on a straight-through corner
        v_arc = np.nan_to_num(np.sqrt(NORMAL_SHARE * g.a_normal * radius), nan=np.inf)
    v_arc = np.where(half > np.pi / 2 - 5e-4, 0.0, v_arc)  # a reversal is never rounded
    turning = half > 5e-4
    cand[v] = turning & (len_in > 1e-9) & (len_out > 1e-9) & (v_arc < SLOW_CORNER * np.minimum(v_in, v_out))
    return cand



class _Corner(NamedTuple):
    """The two pieces meeting at vertices ``v`` and the blend arc the tolerance allows there."""

    len_in: FloatArray
    v_in: FloatArray
    a_in: FloatArray
    j_in: FloatArray
    len_out: FloatArray
    v_out: FloatArray
    a_out: FloatArray
    j_out: FloatArray
    half: FloatArray  # half the deflection angle, rad
    d_t_mm: FloatArray  # tangent-point distance from the vertex
    radius_mm: FloatArray  # blend radius (NaN / inf where there is no turn: the caller decides)
    a_normal: FloatArray  # path acceleration limit across the corner, mm/s^2


def _corner_geometry(run: PathRun, v: IntArray, limits: AxisLimits, machine: MachineModel) -> _Corner:
    from cncc.passes.planning.segments import piece_caps

    len_in, v_in, a_in, j_in = piece_caps(run, v - 1, limits, machine)
    len_out, v_out, a_out, j_out = piece_caps(run, v, limits, machine)
    u_in = (run.points[v] - run.points[v - 1]) / np.maximum(len_in, 1e-300)[:, None]
    u_out = (run.points[v + 1] - run.points[v]) / np.maximum(len_out, 1e-300)[:, None]
    cos_t = np.clip(np.einsum("ij,ij->i", u_in, u_out), -1.0, 1.0)
    half = np.arccos(cos_t) / 2
    tol = run.tol_mm[v - 1]
    with np.errstate(divide="ignore", invalid="ignore"):
        d_tol = tol * np.tan(half) / (1.0 / np.cos(half) - 1.0)
        d_t = np.minimum.reduce([np.nan_to_num(d_tol, nan=0.0, posinf=np.inf), len_in / 2, len_out / 2])
        radius = d_t / np.tan(half)
    e2 = u_out - cos_t[:, None] * u_in
    e2 /= np.maximum(np.linalg.norm(e2, axis=1), 1e-300)[:, None]
    a_normal = path_limit(limits.amax_mm_s2, np.abs(u_in) + np.abs(e2))
    return _Corner(len_in, v_in, a_in, j_in, len_out, v_out, a_out, j_out, half, d_t, radius, a_normal)

def _reach_from_rest(length: FloatArray, a_max: FloatArray, j_max: FloatArray) -> FloatArray:
    """Largest speed a ramp from rest (zero acceleration at both ends) reaches within ``length``."""
    tj = a_max / j_max
    short = length < a_max * tj * tj
    dv_short = (length * np.sqrt(j_max)) ** (2 / 3)
    b = tj / 2
    dv_long = -2 * (-length) / (b + np.sqrt(b * b + 2 * length / a_max))
    out: FloatArray = np.where(short, dv_short, dv_long)
    return out


def _blend_speeds(run: PathRun, machine: MachineModel, limits: AxisLimits
                  ) -> tuple[FloatArray, Segments | None, FloatArray | None]:
    """Per run point: the lowest vertex cap of its blend arc with every corner rounded
    (the velocity-step rule on the actual chords), ``inf`` where there is none; and the
    rounded segments with their vertex caps (reused when no rounded corner stops)."""
    from cncc.passes.planning.blending import velocity_step_caps
    from cncc.passes.planning.segments import make_segments

    out = np.full(run.points.shape[0], np.inf)
    seg = make_segments(_rounded(run, limits, machine), limits, machine)
    if seg is None or seg.count < 2 or seg.vorigin is None:
        return out, None, None
    caps = continuous_caps(seg, velocity_step_caps(seg, limits, machine.interpolation_period_s), run.geo is not None)
    np.minimum.at(out, seg.vorigin[1:-1], caps)
    if seg.geo is not None:  # native blend arcs: crossed at most at their own speed cap
        blend = seg.vorigin[:-1] == seg.vorigin[1:]
        np.minimum.at(out, seg.vorigin[:-1][blend], seg.vcap[blend])
    return out, seg, caps


STEP_SLACK_MM_S = 1e-7
"""On native -O2 runs a corner left sharp (a reversal, a corner too tight to blend) keeps
every axis' velocity step within this: practically a stop, so the velocity is continuous
wherever the machine declares no step (blend machines)."""


def continuous_caps(seg: Segments, caps: FloatArray, native: bool) -> FloatArray:
    """``caps`` of the interior vertices, on native runs also ``STEP_SLACK_MM_S / |du_i|``."""
    if not native or caps.size == 0:
        return caps
    du = seg.turn().max(axis=1)
    with np.errstate(divide="ignore"):
        out: FloatArray = np.minimum(caps, np.where(du > 0, STEP_SLACK_MM_S / np.maximum(du, 1e-300), np.inf))
    return out


def _rounded(run: PathRun, limits: AxisLimits, machine: MachineModel, sharp: np.ndarray | None = None) -> PathRun:
    """The run with its corners rounded: one exact blend arc per corner on native runs
    (-O2, ``fillets.py``), blend chords otherwise (``blending.py``)."""
    if run.geo is not None:
        from cncc.passes.planning.fillets import round_native

        return round_native(run, sharp)
    from cncc.passes.planning.blending import round_corners

    return round_corners(run, limits, machine, sharp)


def closed_form_stops(run: PathRun, cand: np.ndarray, limits: AxisLimits, machine: MachineModel,
                      blend_speed: FloatArray | None = None) -> np.ndarray:
    """The candidates where a stop beats passing the blend arc, by the S-curve ramps of -O2.

    Per side of the corner, over the half of the neighbouring piece: cruise at the speed
    ``V`` that the half reaches from rest, then ramp to 0 at the corner (stop), or ramp to
    the blend arc's speed ``w`` at the tangent point and cross half of the arc at ``w``
    (round).  The times of both sides are compared (zero acceleration at the ramps'
    ends, as :mod:`scurve` plans them)."""
    from cncc.passes.planning.scurve import ramp_distance, ramp_time

    v = np.flatnonzero(cand)
    g = _corner_geometry(run, v, limits, machine)
    len_in, v_in, a_in, j_in = g.len_in, g.v_in, g.a_in, g.j_in
    len_out, v_out, a_out, j_out = g.len_out, g.v_out, g.a_out, g.j_out
    half, d_t = g.half, g.d_t_mm
    radius = np.nan_to_num(g.radius_mm, nan=0.0, posinf=0.0)
    w = np.sqrt(NORMAL_SHARE * g.a_normal * radius)
    if blend_speed is not None:
        w = np.minimum(w, blend_speed[v])
    arc_half = radius * half  # half of the arc (deflection 2 * half)
    t_stop = np.zeros(v.size)
    t_round = np.zeros(v.size)
    for length, vcap, a_max, j_max in ((len_in, v_in, a_in, j_in), (len_out, v_out, a_out, j_out)):
        x = length / 2
        top = np.maximum(np.minimum(vcap, _reach_from_rest(x, a_max, j_max)), 1e-9)
        wc = np.minimum(w, top)
        t_stop += np.maximum(x - ramp_distance(top, 0 * top, a_max, j_max), 0.0) / top + ramp_time(top, 0 * top,
                                                                                                   a_max, j_max)
        straight = np.maximum(x - d_t - ramp_distance(top, wc, a_max, j_max), 0.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            t_round += straight / top + ramp_time(top, wc, a_max, j_max) + np.where(wc > 0, arc_half / wc, np.inf)
    out = np.zeros(cand.size, bool)
    out[v] = t_stop < t_round
    return out


def faster_stops(run: PathRun, cand: np.ndarray, limits: AxisLimits, machine: MachineModel) -> np.ndarray:
    """The candidates where stopping beats rounding (see the module docstring)."""
    from cncc.passes.planning.segments import piece_caps

    k = run.cmd.size
    v = np.flatnonzero(cand)
    rest = np.full(k, np.nan)  # ruckig rest-to-rest time of the pieces next to candidates
    pieces = np.unique(np.concatenate([v - 1, v]))
    rest[pieces] = _rest_times(*piece_caps(run, pieces, limits, machine))
    pair = rest[v - 1] + rest[v] < _window_times(run, v - 1, v + 1, limits, machine) * (1 - 1e-9)
    v = v[pair]
    if v.size == 0:
        return np.zeros_like(cand)
    # blocks of consecutive stops; each is kept only if it beats rounding the whole block
    brk = np.flatnonzero(np.diff(v) != 1)
    first = v[np.concatenate([[0], brk + 1])]
    last = v[np.concatenate([brk, [v.size - 1]])]
    lo, hi = first - 1, last + 1  # pieces [lo, hi) around each block
    open_lo, open_hi = lo > 0, hi < k  # boundary piece inside a rounded part (else at a run end)
    singles = np.concatenate([lo[open_lo], hi[open_hi] - 1])
    t = _window_times(run, np.concatenate([lo, singles]), np.concatenate([hi, singles + 1]), limits, machine)
    t_round, t_single = t[:lo.size], t[lo.size:]
    t_edge = np.zeros(lo.size)
    t_edge[open_lo] += t_single[:int(open_lo.sum())]
    t_edge[open_hi] += t_single[int(open_lo.sum()):]
    inner = np.concatenate([[0.0], np.cumsum(np.nan_to_num(rest))])  # prefix sums of ruckig times
    t_stop = t_edge + (inner[np.where(open_hi, hi - 1, hi)] - inner[np.where(open_lo, lo + 1, lo)])
    keep = t_stop < t_round * (1 - 1e-9)
    stop = np.zeros_like(cand)
    for a, b in zip(first[keep].tolist(), last[keep].tolist(), strict=True):
        stop[a:b + 1] = True
    return stop


def _window_times(run: PathRun, lo: np.ndarray, hi: np.ndarray, limits: AxisLimits, machine: MachineModel
                  ) -> FloatArray:
    """Rest-to-rest -O2 time of the pieces ``[lo, hi)`` of each window, inner corners rounded.

    All windows are planned at once: chained end to end (translated) with a stop at each
    junction, one unfiltered TOPP; a part from rest to rest lasts that time plus ``Tf``.
    """
    from cncc.passes.planning.blending import reduce_accel
    from cncc.passes.planning.fir import unfiltered_profile

    m = lo.size
    count = hi - lo
    piece = np.repeat(lo - np.concatenate([[0], np.cumsum(count)[:-1]]), count) + np.arange(int(count.sum()))
    d = run.points[piece + 1] - run.points[piece]
    pts = np.vstack([np.zeros((1, 6)), np.cumsum(d, axis=0)])
    junction = np.zeros(piece.size + 1, bool)
    junction[np.cumsum(count)] = True
    chain = PathRun(pts, run.cmd[piece], run.rapid[piece], run.feed_mm_s[piece], run.tol_mm[piece],
                    np.zeros(piece.size + 1, bool))
    seg = _joined(chain, junction, machine, limits)
    seg.acap = reduce_accel(seg, limits, machine.interpolation_period_s)
    ph, tf = unfiltered_profile(seg)
    assert seg.vorigin is not None
    ends = seg.s0[np.flatnonzero(junction[seg.vorigin])]  # the end of each window
    s_mid = ph.s0 + ph.v0 * ph.dur / 2 + ph.a0 * ph.dur**2 / 8
    owner = np.minimum(np.searchsorted(ends[:-1], s_mid, side="right"), m - 1)
    out: FloatArray = np.bincount(owner, weights=ph.dur, minlength=m).astype(float) + tf
    return out


def _joined(run: PathRun, stop: np.ndarray, machine: MachineModel, limits: AxisLimits) -> Segments:
    """Like :func:`rounded_parts` but one Segments with zero caps at the stops (not cut)."""
    from cncc.passes.planning.blending import round_corners, velocity_step_caps
    from cncc.passes.planning.segments import make_segments

    seg = make_segments(round_corners(run, limits, machine, stop), limits, machine)
    assert seg is not None and seg.vorigin is not None
    caps = velocity_step_caps(seg, limits, machine.interpolation_period_s)
    seg.vvert[1:-1] = np.minimum(seg.vvert[1:-1], np.where(stop[seg.vorigin[1:-1]], 0.0, caps))
    return seg


def _rest_times(length: FloatArray, vcap: FloatArray, acap: FloatArray, jcap: FloatArray) -> list[float]:
    """ruckig's rest-to-rest time per piece (cached: CAM paths repeat their pieces)."""
    from cncc.ir.trajectory import Limit
    from cncc.passes.planning.onedim import jerk_limited_move

    cache: dict[tuple[float, float, float, float], float] = {}
    out = []
    for key in zip(length.tolist(), vcap.tolist(), acap.tolist(), jcap.tolist(), strict=True):
        if key not in cache:
            cache[key] = jerk_limited_move(*key, int(Limit.FEED)).end_time
        out.append(cache[key])
    return out
