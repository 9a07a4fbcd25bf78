"""Trajectory: the planner's output, phases of constant jerk on exact path geometry.

Every phase ``k`` covers ``[t0_s[k], t0_s[k] + duration_s[k])``.  Two kinds of phase:

* **path phases** (``path.seg[k] >= 0``): the machine moves along segment ``g =
  path.seg[k]`` of :class:`Geometry` (a line, an arc, a helix or a blend arc, exactly),
  and its path coordinate is a cubic of the local time ``tau``::

      s(tau) = s0 + v tau + a tau^2 / 2 + j tau^3 / 6        (path.s0_mm ... path.j_mm_s3)

  so positions, per-axis velocities, accelerations and jerks (with the centripetal
  terms on arcs) and step times follow exactly from the geometry and ``s(t)``;
* **axis rows** (``path`` is None, or ``path.seg[k] == -1``): each axis ``i`` moves as
  its own cubic (independent-axis dog-leg rapids, the -O0 estimate)::

      p_i(tau) = p0_mm[k, i] + v0[k, i] tau + a0[k, i] tau^2 / 2 + j[k, i] tau^3 / 6

For every phase ``p0_mm``, ``v0_mm_s``, ``a0_mm_s2``, ``j_mm_s3`` hold the exact state
at the phase start.  On straight phases (lines, and the axis rows) the cubic above is
then the motion itself; on **curved** phases (``curved[k]``) it is only the Taylor
start of it: read curved phases through :meth:`Trajectory.sample`,
:meth:`Trajectory.end_states` and :class:`Geometry`.

Array shapes (``n`` phases, ``m`` axes, ``g`` geometry segments):

* ``t0_s``, ``duration_s``: ``(n,)`` float64, seconds
* ``p0_mm``, ``v0_mm_s``, ``a0_mm_s2``, ``j_mm_s3``: ``(n, m)`` float64
  (degrees for rotary axes)
* ``cmd_index``: ``(n,)`` int64, index of the IR command responsible
* ``limit``: ``(n,)`` int8, what limited the phase (:class:`Limit` value)

numpy is imported here only; nothing on the CLI or LSP start-up path imports this
module.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from cncc.ir.frame import AXES

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]
State = tuple[FloatArray, FloatArray, FloatArray, FloatArray]


class Limit(enum.IntEnum):
    """The constraint that bounded a phase (for timing reports)."""

    NONE = 0
    FEED = 1  # programmed feed
    ACCEL = 2
    JERK = 3
    CORNER = 4
    AXIS_VELOCITY = 5
    STEP_RATE = 6
    RAPID = 7
    CENTRIPETAL = 8


@dataclass(frozen=True, slots=True)
class Geometry:
    """Exact path segments (``g`` of them, ``m`` axes), each parameterised by its arc length ``s``::

        p(s) = c + rho(s) (cos th(s) e1 + sin th(s) e2) + w s,   rho = r0 + dr s,   th = theta0 + kappa s

    for ``0 <= s <= length``.  A line is ``c`` = its start, ``w`` = its unit direction,
    ``r0 = dr = kappa = 0``; an arc or helix has centre ``c`` (at the start's axial
    position), orthonormal plane basis ``e1, e2``, radius ``r0`` (``dr``: the radius
    change per mm of an arc whose end radius differs a little), start angle ``theta0``,
    ``kappa = sweep / length`` (rad/mm, signed) and axial rate ``w`` (mm per mm of path).
    ``|p'(s)| = 1`` exactly for lines, circles and helices (``dr = 0``).

    Per axis ``i`` the circle part is ``rho A_i cos(th - phi_i)`` with ``A_i = hypot(e1_i,
    e2_i)`` and ``phi_i = atan2(e2_i, e1_i)`` (:meth:`amplitude`): the plane may be any
    (blend arcs lie in the plane of their corner).  An axis has either a circle part or
    an axial rate, never both (``A_i w_i = 0``), which keeps every axis' turning points at
    ``th = phi_i + k pi``.
    """

    c: FloatArray  # (g, m)
    e1: FloatArray  # (g, m)
    e2: FloatArray  # (g, m)
    w: FloatArray  # (g, m)
    r0: FloatArray  # (g,)
    dr: FloatArray  # (g,)
    theta0: FloatArray  # (g,)
    kappa: FloatArray  # (g,)
    length: FloatArray  # (g,)

    @property
    def count(self) -> int:
        return int(self.r0.shape[0])

    @property
    def curved(self) -> npt.NDArray[np.bool_]:
        out: npt.NDArray[np.bool_] = (self.kappa != 0) & (self.r0 + np.abs(self.dr) > 0)
        return out

    def derivatives(self, g: IntArray, s: FloatArray) -> State:
        """``p(s), p'(s), p''(s), p'''(s)`` of segments ``g`` at ``s`` (shape ``(q,)`` each) -> ``(q, m)``."""
        g = np.asarray(g, np.int64)
        s = np.asarray(s, np.float64)
        bent = (self.r0[g] != 0) | (self.dr[g] != 0)  # lines (no circle part): p = c + w s, w, 0, 0
        if bent.all():
            return self._circle_derivatives(g, s)
        w = self.w[g]
        p = self.c[g] + w * s[:, None]
        d1 = np.array(w, copy=True)
        d2 = np.zeros_like(p)
        d3 = np.zeros_like(p)
        if bent.any():
            for dst, src in zip((p, d1, d2, d3), self._circle_derivatives(g[bent], s[bent]), strict=True):
                dst[bent] = src
        return p, d1, d2, d3

    def _circle_derivatives(self, g: IntArray, s: FloatArray) -> State:
        """The general formula of :meth:`derivatives` (circle part and axial rate)."""
        th = self.theta0[g] + self.kappa[g] * s
        cos, sin = np.cos(th)[:, None], np.sin(th)[:, None]
        e1, e2 = self.e1[g], self.e2[g]
        nrm = cos * e1 + sin * e2
        tan = cos * e2 - sin * e1
        k = self.kappa[g][:, None]
        dr = self.dr[g][:, None]
        rho = self.r0[g][:, None] + dr * s[:, None]
        w = self.w[g]
        p = self.c[g] + rho * nrm + w * s[:, None]
        d1 = dr * nrm + rho * k * tan + w
        d2 = 2 * dr * k * tan - rho * k * k * nrm
        d3 = -3 * dr * k * k * nrm - rho * k**3 * tan
        return p, d1, d2, d3

    def amplitude(self, g: IntArray) -> tuple[FloatArray, FloatArray]:
        """``A`` and ``phi`` of rows ``g``, ``(q, m)`` each (see the class docstring)."""
        e1, e2 = self.e1[g], self.e2[g]
        return np.hypot(e1, e2), np.arctan2(e2, e1)

    def take(self, g: IntArray) -> Geometry:
        return Geometry(self.c[g], self.e1[g], self.e2[g], self.w[g], self.r0[g], self.dr[g], self.theta0[g],
                        self.kappa[g], self.length[g])

    def axes_subset(self, cols: list[int]) -> Geometry:
        return Geometry(self.c[:, cols], self.e1[:, cols], self.e2[:, cols], self.w[:, cols], self.r0, self.dr,
                        self.theta0, self.kappa, self.length)

    @staticmethod
    def lines(p0: FloatArray, u: FloatArray, length: FloatArray) -> Geometry:
        g, m = p0.shape
        z = np.zeros(g)
        return Geometry(p0, np.zeros((g, m)), np.zeros((g, m)), u, z, z.copy(), z.copy(), z.copy(), length)

    @staticmethod
    def concat(parts: list[Geometry], m: int) -> Geometry:
        if not parts:
            z, zm = np.zeros(0), np.zeros((0, m))
            return Geometry(zm, zm.copy(), zm.copy(), zm.copy(), z, z.copy(), z.copy(), z.copy(), z.copy())
        return Geometry(*(np.concatenate([getattr(p, f) for p in parts]) for f in Geometry.__slots__))


@dataclass(frozen=True, slots=True)
class PathLaw:
    """The path coordinate of every phase: its segment (``-1``: an axis row) and ``s(tau)``."""

    seg: IntArray  # (n,)
    s0_mm: FloatArray  # (n,) from the segment's start
    v_mm_s: FloatArray  # (n,) path speed at the phase start
    a_mm_s2: FloatArray  # (n,)
    j_mm_s3: FloatArray  # (n,)
    geometry: Geometry

    def s_at(self, k: IntArray, tau: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        v, a, j = self.v_mm_s[k], self.a_mm_s2[k], self.j_mm_s3[k]
        s = self.s0_mm[k] + tau * (v + tau * (a / 2 + tau * j / 6))
        return s, v + tau * (a + tau * j / 2), a + j * tau, j

    def states(self, k: IntArray, tau: FloatArray) -> State:
        """Exact per-axis position, velocity, acceleration, jerk of path phases ``k`` at local ``tau``."""
        s, sd, sdd, sddd = self.s_at(k, tau)
        g = np.maximum(self.seg[k], 0)
        geo = self.geometry
        sd, sdd, sddd = sd[:, None], sdd[:, None], sddd[:, None]
        if not ((geo.r0[g] != 0) | (geo.dr[g] != 0)).any():  # lines only: p = c + w s
            w = geo.w[g]
            return geo.c[g] + w * s[:, None], w * sd, w * sdd, w * sddd
        p, d1, d2, d3 = geo.derivatives(g, s)
        v = d1 * sd
        a = d2 * sd * sd + d1 * sdd
        j = d3 * sd**3 + 3 * d2 * sd * sdd + d1 * sddd
        return p, v, a, j


def _cubic(p0: FloatArray, v0: FloatArray, a0: FloatArray, j: FloatArray, tau: FloatArray) -> State:
    p = p0 + tau * (v0 + tau * (a0 / 2 + tau * j / 6))
    return p, v0 + tau * (a0 + tau * j / 2), a0 + j * tau, j


@dataclass(frozen=True, slots=True)
class Trajectory:
    t0_s: FloatArray
    duration_s: FloatArray
    p0_mm: FloatArray
    v0_mm_s: FloatArray
    a0_mm_s2: FloatArray
    j_mm_s3: FloatArray
    cmd_index: IntArray
    limit: npt.NDArray[np.int8]
    axes: tuple[str, ...] = AXES
    path: PathLaw | None = None

    def __post_init__(self) -> None:
        n = self.t0_s.shape[0]
        m = len(self.axes)
        for name in ("duration_s", "cmd_index", "limit"):
            if getattr(self, name).shape != (n,):
                raise ValueError(f"Trajectory.{name} must have shape ({n},)")
        for name in ("p0_mm", "v0_mm_s", "a0_mm_s2", "j_mm_s3"):
            if getattr(self, name).shape != (n, m):
                raise ValueError(f"Trajectory.{name} must have shape ({n}, {m})")
        if self.path is not None and self.path.seg.shape != (n,):
            raise ValueError(f"Trajectory.path.seg must have shape ({n},)")

    @property
    def phase_count(self) -> int:
        return int(self.t0_s.shape[0])

    @property
    def duration_total_s(self) -> float:
        if self.phase_count == 0:
            return 0.0
        return float(self.t0_s[-1] + self.duration_s[-1])

    @property
    def curved(self) -> npt.NDArray[np.bool_]:
        """``(n,)`` bool: phases on an arc, helix or blend arc (their per-axis cubics are only
        the Taylor start of the motion; see the module docstring)."""
        if self.path is None:
            return np.zeros(self.phase_count, bool)
        seg = self.path.seg
        out: npt.NDArray[np.bool_] = (seg >= 0) & self.path.geometry.curved[np.maximum(seg, 0)]
        return out

    def states(self, k: IntArray, tau: FloatArray) -> State:
        """Exact position, velocity, acceleration, jerk of phases ``k`` at local times ``tau`` -> ``(q, m)``."""
        k = np.asarray(k, np.int64)
        tau = np.asarray(tau, np.float64)
        out = _cubic(self.p0_mm[k], self.v0_mm_s[k], self.a0_mm_s2[k], self.j_mm_s3[k], tau[:, None])
        if self.path is None:
            return out
        bent = self.curved[k]
        if not bent.any():
            return out
        exact = self.path.states(k[bent], tau[bent])
        for dst, src in zip(out, exact, strict=True):  # fresh arrays (fancy-indexed rows): no copy
            dst[bent] = src
        return out

    def end_state(self, k: int) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Position, velocity, acceleration at the end of phase ``k``."""
        p, v, a, _ = self.states(np.array([k]), self.duration_s[k:k + 1])
        return p[0], v[0], a[0]

    def end_states(self) -> State:
        """Exact position, velocity, acceleration, jerk at the end of every phase, ``(n, m)`` each."""
        return self.states(np.arange(self.phase_count), self.duration_s)

    def end_positions(self) -> FloatArray:
        """Exact position at the end of every phase, ``(n, m)``: the first of :meth:`end_states`,
        without the derivatives (arcs: the geometry's position part only)."""
        dur = self.duration_s
        p: FloatArray = self.p0_mm + dur[:, None] * (self.v0_mm_s + dur[:, None] * (
            self.a0_mm_s2 / 2 + dur[:, None] * self.j_mm_s3 / 6))
        bent = np.flatnonzero(self.curved)
        if bent.size and self.path is not None:
            law, geo = self.path, self.path.geometry
            s, _, _, _ = law.s_at(bent, dur[bent])
            g = law.seg[bent]
            th = geo.theta0[g] + geo.kappa[g] * s
            nrm = np.cos(th)[:, None] * geo.e1[g] + np.sin(th)[:, None] * geo.e2[g]
            rho = geo.r0[g][:, None] + geo.dr[g][:, None] * s[:, None]
            p[bent] = geo.c[g] + rho * nrm + geo.w[g] * s[:, None]
        return p

    def sample(self, t_s: FloatArray) -> State:
        """Position, velocity, acceleration, jerk at times ``t_s`` (shape ``(q,)``) -> ``(q, m)``."""
        if self.phase_count == 0:  # no motion: at rest at the origin
            z = np.zeros((np.shape(t_s)[0], len(self.axes)))
            return z, z.copy(), z.copy(), z.copy()
        k = self.phase_at(t_s)
        return self.states(k, np.asarray(t_s, np.float64) - self.t0_s[k])

    def phase_at(self, t_s: FloatArray) -> IntArray:
        """Index of the phase that covers each time of ``t_s`` (clipped to the first/last phase)."""
        out: IntArray = np.clip(np.searchsorted(self.t0_s, t_s, side="right") - 1, 0,
                                max(self.phase_count - 1, 0)).astype(np.int64)
        return out

    def phase_info(self, t_s: FloatArray) -> tuple[IntArray, npt.NDArray[np.int8]]:
        """``cmd_index`` and ``limit`` of the phase at each time of ``t_s`` (shape ``(q,)`` each)."""
        if self.phase_count == 0:
            return np.zeros(np.shape(t_s), np.int64), np.zeros(np.shape(t_s), np.int8)
        k = self.phase_at(t_s)
        return self.cmd_index[k], self.limit[k]

    def select_axes(self, cols: list[int]) -> Trajectory:
        """The same motion restricted to the axes ``cols`` (in that order)."""
        path = self.path
        if path is not None:
            path = PathLaw(path.seg, path.s0_mm, path.v_mm_s, path.a_mm_s2, path.j_mm_s3,
                           path.geometry.axes_subset(cols))
        return Trajectory(self.t0_s, self.duration_s, self.p0_mm[:, cols], self.v0_mm_s[:, cols],
                          self.a0_mm_s2[:, cols], self.j_mm_s3[:, cols], self.cmd_index, self.limit,
                          tuple(self.axes[i] for i in cols), path)

    @staticmethod
    def on_path(t0_s: FloatArray, duration_s: FloatArray, cmd_index: IntArray, limit: npt.NDArray[np.int8],
                law: PathLaw, rows: State | None = None, axes: tuple[str, ...] = AXES) -> Trajectory:
        """A trajectory of path phases (and axis rows where ``law.seg == -1``, whose cubics
        ``rows`` gives); the per-axis start states are computed from the geometry."""
        n, m = t0_s.shape[0], len(axes)
        p0, v0, a0, j = (np.zeros((n, m)) for _ in range(4))
        on = law.seg >= 0
        if on.any():
            k = np.flatnonzero(on)
            for dst, src in zip((p0, v0, a0, j), law.states(k, np.zeros(k.size)), strict=True):
                dst[k] = src
        if rows is not None and (~on).any():
            for dst, src in zip((p0, v0, a0, j), rows, strict=True):
                dst[~on] = src[~on]
        return Trajectory(t0_s, duration_s, p0, v0, a0, j, cmd_index, limit, axes, law)

    @staticmethod
    def empty(axes: tuple[str, ...] = AXES) -> Trajectory:
        m = len(axes)
        z = np.zeros(0)
        zm = np.zeros((0, m))
        return Trajectory(z, z.copy(), zm, zm.copy(), zm.copy(), zm.copy(),
                          np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int8), axes)


def _abs_sin_max(lo: FloatArray, hi: FloatArray) -> FloatArray:
    """Largest ``|sin x|`` over ``[lo, hi]`` (elementwise, ``lo <= hi``)."""
    edge = np.maximum(np.abs(np.sin(lo)), np.abs(np.sin(hi)))
    peak = np.pi / 2 + np.ceil((lo - np.pi / 2) / np.pi) * np.pi  # first pi/2 + k pi at or after lo
    out: FloatArray = np.where((peak <= hi) | (hi - lo >= np.pi), 1.0, edge)
    return out


def _abs_quad_max(c0: FloatArray, c1: FloatArray, c2: FloatArray, t: FloatArray) -> FloatArray:
    """Largest ``|c0 + c1 x + c2 x^2|`` over ``[0, t]``."""
    end = np.abs(c0 + t * (c1 + t * c2))
    with np.errstate(divide="ignore", invalid="ignore"):
        xs = np.where(c2 != 0, -c1 / (2 * c2), -1.0)
    inside = (xs > 0) & (xs < t)
    mid = np.where(inside, np.abs(c0 + xs * (c1 + xs * c2)), 0.0)
    out: FloatArray = np.maximum(np.maximum(np.abs(c0), end), mid)
    return out


def axis_bounds(traj: Trajectory) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Upper bounds of ``|v_i|``, ``|a_i|``, ``|j_i|`` over each phase, ``(n, m)`` each.

    Straight phases: the exact extremes of their cubics.  Curved phases: the smaller of
    two rigorous bounds, the triangle inequality on ``v = p' s'``, ``a = p'' s'^2 + p' s''``,
    ``j = p''' s'^3 + 3 p'' s' s'' + p' s'''`` with each axis' largest ``|p'|``, ``|p''|``,
    ``|p'''|`` over the phase's own sweep, and the orthogonal form of a plane axis
    (tangential and normal parts ``-A sin``, ``A cos`` of one angle: ``A hypot(...)``);
    both with the largest ``|s'|``, ``|s''|``, ``|s'''|`` of the law."""
    d = traj.duration_s[:, None]
    v0, a0, j = traj.v0_mm_s, traj.a0_mm_s2, traj.j_mm_s3
    vb = _abs_quad_max(v0, a0, j / 2, d)
    ab = np.maximum(np.abs(a0), np.abs(a0 + j * d))
    jb = np.abs(j)
    bent = np.flatnonzero(traj.curved)
    if bent.size == 0 or traj.path is None:
        return vb, ab, jb
    law, geo = traj.path, traj.path.geometry
    g = law.seg[bent]
    t = traj.duration_s[bent]
    s_end, _, _, _ = law.s_at(bent, t)
    th_a = geo.theta0[g] + geo.kappa[g] * law.s0_mm[bent]
    th_b = geo.theta0[g] + geo.kappa[g] * s_end
    lo, hi = np.minimum(th_a, th_b), np.maximum(th_a, th_b)
    amp, phi = geo.amplitude(g)
    rel_lo, rel_hi = lo[:, None] - phi, hi[:, None] - phi
    t_b = amp * _abs_sin_max(rel_lo, rel_hi)  # tangent component -A sin(th - phi)
    n_b = amp * _abs_sin_max(rel_lo + np.pi / 2, rel_hi + np.pi / 2)  # normal component A cos(th - phi)
    k = np.abs(geo.kappa[g])[:, None]
    dr = np.abs(geo.dr[g])[:, None]
    rho = np.maximum(geo.r0[g], geo.r0[g] + geo.dr[g] * geo.length[g])[:, None]
    p1 = dr * n_b + rho * k * t_b + np.abs(geo.w[g])
    p2 = 2 * dr * k * t_b + rho * k * k * n_b
    p3 = 3 * dr * k * k * n_b + rho * k**3 * t_b
    sv, sa, sj = law.v_mm_s[bent], law.a_mm_s2[bent], law.j_mm_s3[bent]
    sd = _abs_quad_max(sv, sa, sj / 2, t)[:, None]
    sdd = np.maximum(np.abs(sa), np.abs(sa + sj * t))[:, None]
    sddd = np.abs(sj)[:, None]
    vb[bent] = p1 * sd
    ab_tri = p2 * sd * sd + p1 * sdd
    jb_tri = p3 * sd**3 + 3 * p2 * sd * sdd + p1 * sddd
    # plane axes: tangential and normal parts are -A sin and A cos of one angle (orthogonal);
    # the radius change's own terms (dr) are added on top
    c1, c2, c3 = rho * k, rho * k * k, rho * k**3
    ab_orth = amp * (np.hypot(c1 * sdd, c2 * sd * sd) + dr * sdd + 2 * dr * k * sd * sd)
    jb_orth = amp * (np.hypot(c1 * sddd + c3 * sd**3, 3 * c2 * sd * sdd)
                     + dr * sddd + 6 * dr * k * sd * sdd + 3 * dr * k * k * sd**3)
    axial = np.abs(geo.w[g])
    ab_orth += axial * sdd
    jb_orth += axial * sddd
    ab[bent] = np.minimum(ab_tri, ab_orth)
    jb[bent] = np.minimum(jb_tri, jb_orth)
    return vb, ab, jb


def _cubic_extent(p0: FloatArray, p_end: FloatArray, v0: FloatArray, a0: FloatArray, j: FloatArray,
                  dur: FloatArray) -> tuple[FloatArray, FloatArray]:
    lo, hi = np.minimum(p0, p_end), np.maximum(p0, p_end)
    disc = a0 * a0 - 2 * j * v0
    for sign in (-1.0, 1.0):
        with np.errstate(divide="ignore", invalid="ignore"):
            root = np.where(j != 0, (-a0 + sign * np.sqrt(np.maximum(disc, 0))) / j,
                            np.where(a0 != 0, -v0 / a0, -1.0))
        ok = (root > 0) & (root < dur[:, None]) & (disc >= 0)
        p = p0 + v0 * root + a0 * root**2 / 2 + j * root**3 / 6
        lo = np.where(ok, np.minimum(lo, p), lo)
        hi = np.where(ok, np.maximum(hi, p), hi)
    return lo, hi


def position_bounds(traj: Trajectory) -> tuple[FloatArray, FloatArray]:
    """Smallest and largest position of every axis over each phase, ``(n, m)`` each: the
    cubic's extremes on straight phases; on arcs the end points and the points of the
    sweep where a plane axis turns (angles ``k pi / 2``)."""
    p_end = traj.end_positions()
    d = traj.duration_s[:, None]
    lo, hi = _cubic_extent(traj.p0_mm, p_end, traj.v0_mm_s, traj.a0_mm_s2, traj.j_mm_s3, d[:, 0])
    bent = np.flatnonzero(traj.curved)
    if bent.size == 0 or traj.path is None:
        return lo, hi
    law, geo = traj.path, traj.path.geometry
    lo[bent] = np.minimum(traj.p0_mm[bent], p_end[bent])
    hi[bent] = np.maximum(traj.p0_mm[bent], p_end[bent])
    g = law.seg[bent]
    s_a = law.s0_mm[bent]
    s_b, _, _, _ = law.s_at(bent, traj.duration_s[bent])
    th_a = geo.theta0[g] + geo.kappa[g] * s_a
    th_b = geo.theta0[g] + geo.kappa[g] * s_b
    th_lo, th_hi = np.minimum(th_a, th_b), np.maximum(th_a, th_b)
    amp, phi = geo.amplitude(g)
    kap = np.where(geo.kappa[g] != 0, geo.kappa[g], 1.0)
    blo, bhi = lo[bent], hi[bent]
    for i in range(amp.shape[1]):
        ax = amp[:, i] > 0
        if not ax.any():
            continue
        first = phi[:, i] + np.ceil((th_lo - phi[:, i]) / np.pi) * np.pi  # turning points phi + k pi
        for q in range(2):
            th = first + q * np.pi
            use = ax & (th <= th_hi)
            s = np.clip((th - geo.theta0[g]) / kap, 0, geo.length[g])
            p, _, _, _ = geo.derivatives(g, s)
            blo[:, i] = np.where(use, np.minimum(blo[:, i], p[:, i]), blo[:, i])
            bhi[:, i] = np.where(use, np.maximum(bhi[:, i], p[:, i]), bhi[:, i])
    lo[bent], hi[bent] = blo, bhi
    return lo, hi
