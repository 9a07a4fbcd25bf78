"""A run's polyline as straight segments with speed, acceleration and jerk caps.

Consumes a :class:`PathRun` polyline; produces :class:`Segments` (all arrays, ``k``
segments):

* ``vcap`` path speed cap (programmed feed, machine feed cap, per-axis velocity and
  step rate, or the per-axis rapid rates), ``vlim`` the :class:`Limit` that set it;
* ``acap`` / ``jcap`` path acceleration / jerk caps from the per-axis limits;
* native arc segments (-O2, :data:`geometry.NATIVE_ARCS`) are planned on their path
  coordinate: ``u`` is then the componentwise bound of ``|p'(s)|`` over the sweep (what
  the per-axis caps divide by), ``u_in`` / ``u_out`` the tangents at both ends, ``geo``
  the exact shape.  Their caps keep every axis within its limits at every instant: on a
  circle of radius ``r`` a plane axis of amplitude ``A`` has (tangential and normal parts
  are ``-A sin`` and ``A cos`` of one angle) ``|a_i| <= A sqrt(s''^2 + (v^2/r)^2)`` and
  ``|j_i| <= A sqrt((s''' + v^3/r^2)^2 + (3 v s''/r)^2)``, an axial axis ``|w_i| s''`` and
  ``|w_i| s'''``.  The speed cap keeps ``v^2 / r`` within ``NORMAL_SHARE`` of the plane
  axes' acceleration and ``v^3 / r^2`` within ``JERK_SHARES[0]`` of their jerk, the path
  jerk gets ``JERK_SHARES[1]`` of its straight cap, and the path acceleration is the
  largest that both bounds leave (``arc_caps``);
* ``vvert`` (``k + 1``) speed caps at the vertices, filled by a corner rule:
  :func:`junction_deviation` (grbl/Klipper), :func:`speed_step` (SZGH) or the
  velocity-step rule of ``blending.py``; ``vvert[0]`` and ``vvert[k]`` are the start
  and end speeds (0, or the SZGH take-off speed).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, replace

import numpy as np

from cncc.ir.machine import MachineModel
from cncc.ir.trajectory import FloatArray, Geometry, Limit
from cncc.passes.planning.geometry import NORMAL_SHARE, PathRun
from cncc.passes.planning.limits import AxisLimits, path_limit

JERK_SHARES = (0.25, 0.5)
"""Shares of the plane axes' jerk an arc leaves to ``v^3/r^2`` and to the path jerk (``3 v a / r``
takes what their sum leaves, orthogonally)."""

DR_MARGIN = 4.0
"""Arcs whose end radius differs (``dr != 0``) are capped ``1 / (1 + DR_MARGIN eps)`` lower,
``eps = |dr| / (rho kappa)``: the radius change's own terms in ``p', p'', p'''``."""


@dataclass
class Segments:
    p0: FloatArray  # (k, 6) start point
    u: FloatArray  # (k, 6) unit direction
    length: FloatArray  # (k,)
    s0: FloatArray  # (k+1,) arc length at the vertices
    cmd: np.ndarray  # (k,)
    vcap: FloatArray  # (k,) mm/s
    vlim: np.ndarray  # (k,) int8 Limit
    acap: FloatArray  # (k,) mm/s^2
    jcap: FloatArray  # (k,) mm/s^3
    vvert: FloatArray  # (k+1,)
    vorigin: np.ndarray | None = None  # (k+1,) unrounded run point of each vertex
    smooth: np.ndarray | None = None  # (k+1,) bool, vertex inside an arc or a blend (chords of one curve)
    u_in: FloatArray | None = None  # (k, 6) tangent at the start (None: ``u``, all straight)
    u_out: FloatArray | None = None  # (k, 6) tangent at the end
    geo: Geometry | None = None  # (k rows) exact shape of every segment (None: the lines p0 + u s)
    a_normal: FloatArray | None = None  # (k, 6) per-axis centripetal acceleration bound at vcap

    @property
    def count(self) -> int:
        return int(self.length.shape[0])

    @property
    def t_in(self) -> FloatArray:
        return self.u if self.u_in is None else self.u_in

    @property
    def t_out(self) -> FloatArray:
        return self.u if self.u_out is None else self.u_out

    def turn(self) -> FloatArray:
        """``|u_in[m] - u_out[m - 1]|`` per axis at the interior vertices, ``(k - 1, 6)``."""
        out: FloatArray = np.abs(self.t_in[1:] - self.t_out[:-1])
        return out

    def shape(self) -> Geometry:
        return Geometry.lines(self.p0, self.u, self.length) if self.geo is None else self.geo

    def end_point(self) -> FloatArray:
        if self.geo is not None:
            p, _, _, _ = self.geo.derivatives(np.array([self.count - 1]), self.length[-1:])
            return np.asarray(p[0], np.float64)
        out: FloatArray = self.p0[-1] + self.u[-1] * self.length[-1]
        return out


def make_segments(run: PathRun, limits: AxisLimits, machine: MachineModel) -> Segments | None:
    if run.geo is not None and run.arcs is not None and (run.geo >= 0).any():
        return _with_arcs(run, limits, machine)
    pts = run.points
    d = np.diff(pts, axis=0)
    length = np.linalg.norm(d, axis=1)
    keep = length > 1e-9
    if not keep.any():
        return None
    idx = np.flatnonzero(keep)
    d, length = d[idx], length[idx]
    return _line_segments(run, idx, pts[idx], d / length[:, None], length, limits, machine)


def _sin_bound(theta0: FloatArray, sweep: FloatArray, phase: float) -> FloatArray:
    """Largest ``|sin(theta + phase)|`` for theta between theta0 and theta0 + sweep."""
    lo = np.minimum(theta0, theta0 + sweep) + phase
    hi = np.maximum(theta0, theta0 + sweep) + phase
    out = np.maximum(np.abs(np.sin(lo)), np.abs(np.sin(hi)))
    k = np.ceil((lo - np.pi / 2) / np.pi)  # the first peak pi/2 + k pi at or after lo
    inside = np.pi / 2 + k * np.pi <= hi
    res: FloatArray = np.where(inside | (hi - lo >= np.pi), 1.0, out)
    return res


def arc_bounds(geo: Geometry) -> tuple[FloatArray, FloatArray]:
    """Per segment and axis: bounds of ``|p'(s)|`` and of the unit normal's components
    ``|n(s)|`` (``p'' = -rho kappa^2 n`` on a circle) over the whole segment, ``(g, 6)`` each."""
    sweep = (geo.kappa * geo.length)[:, None]
    amp, phi = geo.amplitude(np.arange(geo.count))
    start = geo.theta0[:, None] - phi
    t_b = amp * _sin_bound(start, sweep, 0.0)  # tangent component -A sin(th - phi)
    n_b = amp * _sin_bound(start, sweep, np.pi / 2)  # normal component A cos(th - phi)
    rho = np.maximum(geo.r0, geo.r0 + geo.dr * geo.length)[:, None]
    speed = rho * np.abs(geo.kappa)[:, None] * t_b + np.abs(geo.w) + np.abs(geo.dr)[:, None] * n_b
    return speed, np.minimum(n_b, 1.0)


def _with_arcs(run: PathRun, limits: AxisLimits, machine: MachineModel) -> Segments | None:
    """:func:`make_segments` of a run with native arc pieces (see the module docstring).

    The arc quantities are computed on the arc rows only and scattered (a run of lines with
    blend arcs between them has as many lines as arcs: half the temporaries)."""
    assert run.geo is not None and run.arcs is not None
    pts = run.points
    d = np.diff(pts, axis=0)
    chord = np.linalg.norm(d, axis=1)
    is_arc = run.geo >= 0
    length = np.where(is_arc, run.arcs.length[np.maximum(run.geo, 0)], chord)
    keep = length > 1e-9
    if not keep.any():
        return None
    idx = np.flatnonzero(keep)
    is_arc, length = is_arc[idx], length[idx]
    ai = np.flatnonzero(is_arc)  # rows (of idx) that are arcs
    arcs = run.arcs.take(run.geo[idx[ai]])
    u_line = d[idx] / np.maximum(chord[idx], 1e-300)[:, None]
    ub, nb = arc_bounds(arcs)
    rows = np.arange(ai.size)
    _, t0, _, _ = arcs.derivatives(rows, np.zeros(ai.size))
    _, t1, _, _ = arcs.derivatives(rows, arcs.length)
    u = u_line.copy()
    u[ai] = ub
    u_in, u_out = u_line.copy(), u_line.copy()
    u_in[ai], u_out[ai] = t0, t1
    line_geo = Geometry.lines(pts[idx], u_line, length)
    for f in Geometry.__slots__:
        getattr(line_geo, f)[ai] = getattr(arcs, f)
    seg = replace(_line_segments(run, idx, pts[idx], u, length, limits, machine), u_in=u_in, u_out=u_out,
                  geo=line_geo)
    del u_line, u_in, u_out, t0, t1, ub
    # arcs: centripetal caps; the plane axes are those the normal reaches
    r = np.maximum(np.minimum(arcs.r0, arcs.r0 + arcs.dr * arcs.length), 1e-9)
    plane = nb > 1e-12
    a_plane = np.where(plane, limits.amax_mm_s2[None, :], np.inf).min(axis=1)
    j_plane = np.where(plane, limits.jmax_mm_s3[None, :], np.inf).min(axis=1)
    v_cent = np.minimum(np.sqrt(NORMAL_SHARE * a_plane * r), np.cbrt(JERK_SHARES[0] * j_plane * r * r))
    # |p'| slightly above 1 where the end radius differs (dr != 0): the feed is a path speed
    rho_max = np.maximum(arcs.r0, arcs.r0 + arcs.dr * arcs.length)
    stretch = np.sqrt(arcs.dr**2 + (rho_max * arcs.kappa) ** 2 + np.einsum("ij,ij->i", arcs.w, arcs.w))
    feed = np.minimum(run.feed_mm_s[idx[ai]], machine.max_feed_mm_min / 60.0)
    eps = np.abs(arcs.dr) / np.maximum(rho_max * np.abs(arcs.kappa), 1e-12)
    shrink = 1.0 / (1.0 + DR_MARGIN * eps)
    v_arc = np.minimum(np.minimum(seg.vcap[ai], v_cent), feed / np.maximum(stretch, 1.0)) * shrink
    j_arc = JERK_SHARES[1] * seg.jcap[ai] * shrink
    a_arc, a_norm = arc_caps(arcs, v_arc, j_arc, limits, shrink)
    vlim = seg.vlim.copy()
    vlim[ai] = np.where(v_cent < seg.vcap[ai], int(Limit.CENTRIPETAL), vlim[ai])
    seg.vlim = vlim.astype(np.int8)
    seg.vcap = seg.vcap.copy()
    seg.vcap[ai] = v_arc
    seg.acap = seg.acap.copy()
    seg.acap[ai] = a_arc
    seg.jcap = seg.jcap.copy()
    seg.jcap[ai] = j_arc
    a_normal = np.zeros_like(seg.u)
    a_normal[ai] = a_norm
    seg.a_normal = a_normal
    return seg


def arc_caps(arcs: Geometry, v: FloatArray, jerk: FloatArray, limits: AxisLimits, share: FloatArray
             ) -> tuple[FloatArray, FloatArray]:
    """Largest path acceleration of each arc at speeds up to ``v`` and path jerk ``jerk``
    that keeps every axis within ``share`` of its limits (the module docstring's bounds),
    and the per-axis centripetal acceleration bound at ``v``, ``(g, 6)``."""
    amp, _ = arcs.amplitude(np.arange(arcs.count))
    rho = np.maximum(arcs.r0, arcs.r0 + arcs.dr * arcs.length)[:, None]
    kap = np.abs(arcs.kappa)[:, None]
    p1, p2, p3 = rho * kap, rho * kap**2, rho * kap**3
    vv, jj = v[:, None], jerk[:, None]
    amax, jmax = limits.amax_mm_s2[None, :] * share[:, None], limits.jmax_mm_s3[None, :] * share[:, None]
    plane = amp > 1e-12
    with np.errstate(divide="ignore", invalid="ignore"):
        a_room = np.sqrt(np.maximum((amax / np.where(plane, amp, 1.0)) ** 2 - (p2 * vv * vv) ** 2, 0.0))
        a_acc = np.where(plane, a_room / np.maximum(p1, 1e-300), np.inf)
        j_room = np.sqrt(np.maximum((jmax / np.where(plane, amp, 1.0)) ** 2 - (p1 * jj + p3 * vv**3) ** 2, 0.0))
        a_jerk = np.where(plane, j_room / np.maximum(3 * p2 * vv, 1e-300), np.inf)
        axial = np.abs(arcs.w)
        a_axial = np.where(axial > 1e-12, amax / np.maximum(axial, 1e-300), np.inf)
    acap = np.minimum(np.minimum(a_acc, a_jerk), a_axial).min(axis=1)
    a_norm = np.where(plane, amp * p2 * vv * vv, 0.0)
    return np.maximum(acap, 1e-9), a_norm


def _line_segments(run: PathRun, idx: np.ndarray, p0: FloatArray, u: FloatArray, length: FloatArray,
                   limits: AxisLimits, machine: MachineModel) -> Segments:
    """Segments of the pieces ``idx`` with direction (cap) vectors ``u`` and lengths ``length``."""
    feed = np.minimum(run.feed_mm_s[idx], machine.max_feed_mm_min / 60.0)
    rapid = run.rapid[idx]
    v_axis = path_limit(limits.vmax_mm_s, u)
    v_step = path_limit(limits.step_rate_mm_s, u)
    v_rapid = path_limit(limits.rapid_mm_s, u)
    vcap = np.where(rapid, v_rapid, np.minimum(feed, v_axis))
    vlim = np.where(rapid, Limit.RAPID, np.where(feed <= v_axis, Limit.FEED, Limit.AXIS_VELOCITY))
    vlim = np.where(~rapid & (v_step <= vcap * (1 + 1e-12)) & (v_step < limits.vmax_mm_s.max()), Limit.STEP_RATE, vlim)
    s0 = np.concatenate([[0.0], np.cumsum(length)])
    vvert = np.full(idx.size + 1, np.inf)
    vvert[0] = vvert[-1] = 0.0
    vpoint = np.concatenate([idx, idx[-1:] + 1])
    vorigin = vpoint if run.origin is None else run.origin[vpoint]
    return Segments(p0, u, length, s0, run.cmd[idx], vcap, vlim.astype(np.int8),
                    path_limit(limits.amax_mm_s2, u), path_limit(limits.jmax_mm_s3, u), vvert, vorigin,
                    run.arc_vertex[vpoint])


def junction_deviation(seg: Segments, limits: AxisLimits, deviation_mm: float) -> FloatArray:
    """grbl's junction speed at the interior vertices, shape ``(k - 1,)``."""
    u_in, u_out = seg.t_out[:-1], seg.t_in[1:]
    cos_theta = -np.einsum("ij,ij->i", u_in, u_out)
    junction = u_out - u_in
    norm = np.linalg.norm(junction, axis=1)
    unit = junction / np.maximum(norm, 1e-300)[:, None]
    a_j = path_limit(limits.amax_mm_s2, unit)
    sin_half = np.sqrt(np.clip(0.5 * (1.0 - cos_theta), 0.0, 1.0))
    with np.errstate(divide="ignore", invalid="ignore"):
        v2 = a_j * deviation_mm * sin_half / (1.0 - sin_half)
    v = np.sqrt(np.maximum(v2, 0.0))
    v = np.where(cos_theta < -0.999999, np.inf, v)
    return np.where(cos_theta > 0.999999, 0.0, v)


def speed_step(seg: Segments, limits: AxisLimits) -> FloatArray:
    """SZGH corner rule: each axis' velocity may jump by at most its speed step.

    Also brings the speed down to the reversal speed where an axis reverses.
    """
    u_in, u_out = seg.t_out[:-1], seg.t_in[1:]
    du = np.abs(u_out - u_in)
    steps = np.where(limits.step_mm_s > 0, limits.step_mm_s, 0.0)
    with np.errstate(divide="ignore"):
        v = np.where(du > 1e-12, steps[None, :] / np.maximum(du, 1e-300), np.inf).min(axis=1)
    reverses = (u_in * u_out < -1e-12)
    rev_speed = np.where(reverses, np.where(limits.reversal_mm_s > 0, limits.reversal_mm_s, np.inf)[None, :], np.inf)
    out: FloatArray = np.minimum(v, rev_speed.min(axis=1))
    return out


def take_off_speed(seg: Segments, limits: AxisLimits, machine: MachineModel) -> tuple[float, float]:
    """SZGH start/stop speed of the first and last segment (no ramp below it)."""
    path = machine.start_speed_mm_min / 60.0
    if path <= 0 or not (limits.start_mm_s > 0).any():
        return 0.0, 0.0
    first = min(path, float(path_limit(limits.start_mm_s, seg.t_in[:1])[0]), float(seg.vcap[0]))
    last = min(path, float(path_limit(limits.start_mm_s, seg.t_out[-1:])[0]), float(seg.vcap[-1]))
    return first, last


def split_at_stops(seg: Segments) -> list[Segments]:
    """Cut at interior vertices whose cap is zero; each part starts and ends at rest."""
    zero = np.flatnonzero(seg.vvert[1:-1] <= 0.0) + 1
    if zero.size == 0:
        return [seg]
    bounds = [0, *zero.tolist(), seg.count]
    parts = []
    for a, b in itertools.pairwise(bounds):
        vv = seg.vvert[a:b + 1].copy()
        vv[0] = vv[-1] = 0.0
        parts.append(replace(seg, p0=seg.p0[a:b], u=seg.u[a:b], length=seg.length[a:b],
                             s0=seg.s0[a:b + 1] - seg.s0[a], cmd=seg.cmd[a:b], vcap=seg.vcap[a:b],
                             vlim=seg.vlim[a:b], acap=seg.acap[a:b], jcap=seg.jcap[a:b], vvert=vv,
                             vorigin=None if seg.vorigin is None else seg.vorigin[a:b + 1],
                             smooth=None if seg.smooth is None else seg.smooth[a:b + 1],
                             u_in=None if seg.u_in is None else seg.u_in[a:b],
                             u_out=None if seg.u_out is None else seg.u_out[a:b],
                             geo=None if seg.geo is None else seg.geo.take(np.arange(a, b)),
                             a_normal=None if seg.a_normal is None else seg.a_normal[a:b]))
    return parts


def piece_caps(run: PathRun, pieces: np.ndarray, limits: AxisLimits, machine: MachineModel
               ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """Length and speed, acceleration, jerk caps of single pieces of ``run`` (as make_segments)."""
    d = run.points[pieces + 1] - run.points[pieces]
    length = np.linalg.norm(d, axis=1)
    u = d / np.maximum(length, 1e-300)[:, None]
    feed = np.minimum(run.feed_mm_s[pieces], machine.max_feed_mm_min / 60.0)
    vcap = np.where(run.rapid[pieces], path_limit(limits.rapid_mm_s, u),
                    np.minimum(feed, path_limit(limits.vmax_mm_s, u)))
    return length, vcap, path_limit(limits.amax_mm_s2, u), path_limit(limits.jmax_mm_s3, u)
