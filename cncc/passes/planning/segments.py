"""A run's polyline as straight segments with speed, acceleration and jerk caps.

Consumes a :class:`PathRun` polyline; produces :class:`Segments` (all arrays, ``k``
segments):

* ``vcap`` path speed cap (programmed feed, machine feed cap, per-axis velocity and
  step rate, or the per-axis rapid rates), ``vlim`` the :class:`Limit` that set it;
* ``acap`` / ``jcap`` path acceleration / jerk caps from the per-axis limits;
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
from cncc.ir.trajectory import FloatArray, Limit
from cncc.passes.planning.geometry import PathRun
from cncc.passes.planning.limits import AxisLimits, path_limit


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

    @property
    def count(self) -> int:
        return int(self.length.shape[0])

    def end_point(self) -> FloatArray:
        out: FloatArray = self.p0[-1] + self.u[-1] * self.length[-1]
        return out


def make_segments(run: PathRun, limits: AxisLimits, machine: MachineModel) -> Segments | None:
    pts = run.points
    d = np.diff(pts, axis=0)
    length = np.linalg.norm(d, axis=1)
    keep = length > 1e-9
    if not keep.any():
        return None
    idx = np.flatnonzero(keep)
    d, length = d[idx], length[idx]
    p0 = pts[idx]
    u = d / length[:, None]
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
    u_in, u_out = seg.u[:-1], seg.u[1:]
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
    u_in, u_out = seg.u[:-1], seg.u[1:]
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
    first = min(path, float(path_limit(limits.start_mm_s, seg.u[:1])[0]), float(seg.vcap[0]))
    last = min(path, float(path_limit(limits.start_mm_s, seg.u[-1:])[0]), float(seg.vcap[-1]))
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
                             smooth=None if seg.smooth is None else seg.smooth[a:b + 1]))
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
