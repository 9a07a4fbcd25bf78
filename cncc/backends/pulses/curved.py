"""Exact step times on curved phases (arcs, helices, blend arcs): through angles, no chords.

On a curved phase the axis positions are those of :class:`cncc.ir.trajectory.Geometry`
at the path coordinate ``s(tau)`` of the phase's law.  Each axis is either a plane axis
(``x = c + rho A cos(th - phi)``, ``th = theta0 + kappa s``, any plane: G17/G18/G19 arcs
and blend arcs in the plane of their corner) or an axial one (``x = c + w s``), so:

* the turning points of a plane axis are the angles ``phi + k pi``:
  :func:`turning_times` gives the times where the phase's sweep crosses them;
* a step boundary ``y`` inside a monotone piece is reached at the angle
  ``phi + k pi + acos(+-(y - c) / (rho A))`` (or ``s = (y - c) / w`` on an axial axis), and the
  time at that ``s`` is the root of the phase's cubic ``s(tau)``, solved by
  :func:`.roots.piece_times` like any constant-jerk piece.

Where the end radius differs a little from the start's (``dr != 0``) the radius at the
boundary is found by two fixed-point rounds; its turning points move by ``atan(dr / (rho
kappa))``, a few micro-radians for arcs that pass arc-check, which is ignored.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from cncc.backends.pulses.roots import piece_times
from cncc.ir.trajectory import Trajectory

F64 = npt.NDArray[np.float64]
I64 = npt.NDArray[np.int64]

MAX_SEGMENT_SWEEP_RAD = np.pi / 12
"""Curved phases are cut into segments of at most this mean sweep (at most one turning
point of any axis per segment, even where the speed changes within the phase)."""


def _axis_kind(traj: Trajectory, g: I64, i: int) -> tuple[F64, F64]:
    """Amplitude ``A`` and phase ``phi`` of axis ``i`` on geometry rows ``g`` (``A = 0``: axial)."""
    assert traj.path is not None
    geo = traj.path.geometry
    return np.hypot(geo.e1[g, i], geo.e2[g, i]), np.arctan2(geo.e2[g, i], geo.e1[g, i])


def _tau_at(traj: Trajectory, k: I64, s_target: F64, ta: F64, tb: F64) -> F64:
    """Local times in ``[ta, tb]`` of phases ``k`` where ``s`` reaches ``s_target`` (one per entry)."""
    assert traj.path is not None
    law = traj.path
    s_a, v_a, a_a, j = law.s_at(k, ta)
    s_b, v_b, a_b, _ = law.s_at(k, tb)
    d = np.clip(s_target - s_a, 0.0, np.maximum(s_b - s_a, 0.0))
    ones = np.ones(k.size, np.int64)
    u = piece_times(d, ones, v_a, a_a, j, tb - ta, (s_b - s_a, v_b, a_b))
    return ta + u


def turning_times(traj: Trajectory, k: I64, ta: F64, tb: F64, i: int) -> F64:
    """Per segment (phase ``k``, local ``[ta, tb]``): the time where axis ``i`` turns inside, NaN if none."""
    assert traj.path is not None
    law, geo = traj.path, traj.path.geometry
    g = law.seg[k]
    amp, shift = _axis_kind(traj, g, i)
    s_a, _, _, _ = law.s_at(k, ta)
    s_b, _, _, _ = law.s_at(k, tb)
    th_a = geo.theta0[g] + geo.kappa[g] * s_a
    th_b = geo.theta0[g] + geo.kappa[g] * s_b
    lo, hi = np.minimum(th_a, th_b), np.maximum(th_a, th_b)
    m = np.ceil((lo - shift) / np.pi)  # zeros of the axis' derivative: th = phi + m pi
    th = shift + m * np.pi
    inside = (amp > 1e-12) & (th > lo) & (th < hi)
    out = np.full(k.size, np.nan)
    if inside.any():
        sel = np.flatnonzero(inside)
        kap = geo.kappa[g[sel]]
        s_t = (th[sel] - geo.theta0[g[sel]]) / kap
        out[sel] = _tau_at(traj, k[sel], s_t, ta[sel], tb[sel])
        out[sel] = np.where((out[sel] > ta[sel]) & (out[sel] < tb[sel]), out[sel], np.nan)
    return out


def axis_positions(traj: Trajectory, k: I64, tau: F64, i: int) -> F64:
    """Position of axis ``i`` on curved phases ``k`` at local times ``tau``: the same arithmetic as
    :meth:`cncc.ir.trajectory.Geometry.derivatives`, for one axis and the position only."""
    assert traj.path is not None
    law, geo = traj.path, traj.path.geometry
    s, _, _, _ = law.s_at(k, tau)
    g = law.seg[k]
    th = geo.theta0[g] + geo.kappa[g] * s
    nrm = np.cos(th) * geo.e1[g, i] + np.sin(th) * geo.e2[g, i]
    rho = geo.r0[g] + geo.dr[g] * s
    out: F64 = geo.c[g, i] + rho * nrm + geo.w[g, i] * s
    return out


def all_positions(traj: Trajectory, k: I64, tau: F64) -> F64:
    """Every axis' position on curved phases ``k`` at local times ``tau``, ``(q, m)``: the
    position part of :meth:`cncc.ir.trajectory.Trajectory.states`, without the derivatives."""
    assert traj.path is not None
    law, geo = traj.path, traj.path.geometry
    s, _, _, _ = law.s_at(k, tau)
    g = law.seg[k]
    th = geo.theta0[g] + geo.kappa[g] * s
    cos, sin = np.cos(th)[:, None], np.sin(th)[:, None]
    nrm = cos * geo.e1[g] + sin * geo.e2[g]
    rho = geo.r0[g][:, None] + geo.dr[g][:, None] * s[:, None]
    out: F64 = geo.c[g] + rho * nrm + geo.w[g] * s[:, None]
    return out


def curved_step_times(traj: Trajectory, k: I64, i: int, tau_a: F64, tau_e: F64, counts: I64, y: F64) -> F64:
    """Local times (from each piece start) of the steps of monotone pieces of axis ``i``.

    Pieces: phase ``k``, local interval ``[tau_a, tau_e]``, ``counts`` steps; ``y`` the
    axis positions of the step boundaries (all pieces concatenated).

    Everything that depends on the piece only (its branch of the circle, centre, radius,
    rates) is found once per piece and spread to its steps; per step there is one
    ``arccos`` (plane axis) or one division (axial axis), then the cubic root in ``s``.
    """
    assert traj.path is not None
    law, geo = traj.path, traj.path.geometry
    g = law.seg[k]
    amp, shift = _axis_kind(traj, g, i)
    s_a, v_a, a_a, j = law.s_at(k, tau_a)
    s_e, v_e, a_e, _ = law.s_at(k, tau_e)
    kap = geo.kappa[g]
    c = geo.c[g, i]
    # the monotone branch of each piece: its angles lie in [phi + m pi, phi + (m + 1) pi]
    th_mid = geo.theta0[g] + kap * (s_a + s_e) / 2
    m = np.floor((th_mid - shift) / np.pi)
    sign = np.where(m % 2 == 0, 1.0, -1.0)
    base = shift + m * np.pi
    plane = amp > 1e-12
    lo, hi = np.minimum(s_a, s_e), np.maximum(s_a, s_e)
    s = np.empty(y.shape[0])
    first = np.cumsum(counts) - counts
    with np.errstate(divide="ignore", invalid="ignore"):
        round_ = plane & (geo.dr[g] == 0)
        if round_.all():
            rho = np.maximum(geo.r0[g] * amp, 1e-300)
            q = np.repeat(sign / rho, counts)
            x = y - np.repeat(c, counts)
            x *= q
            np.clip(x, -1.0, 1.0, out=x)
            np.arccos(x, out=x)
            x += np.repeat(base - geo.theta0[g], counts)
            x /= np.repeat(np.where(kap != 0, kap, 1.0), counts)
            s = x
        else:
            for kind, is_round, is_plane in ((round_, True, True), (plane & ~round_, False, True),
                                             (~plane, False, False)):
                if not kind.any():
                    continue
                sel = np.flatnonzero(kind)
                idx = _step_index(first[sel], counts[sel])
                s[idx] = _branch_s(traj, g[sel], i, counts[sel], y[idx], c[sel], amp[sel], sign[sel], base[sel],
                                   (s_a[sel] + s_e[sel]) / 2, is_round, is_plane)
    s = np.nan_to_num(s, nan=0.0, copy=False)
    np.clip(s, np.repeat(lo, counts), np.repeat(hi, counts), out=s)
    # s -> time: the phase's cubic from the piece start
    s -= np.repeat(s_a, counts)
    return piece_times(s, counts, v_a, a_a, j, tau_e - tau_a, (s_e - s_a, v_e, a_e))


def _step_index(first: I64, counts: I64) -> I64:
    idx = np.arange(int(counts.sum()), dtype=np.int64)
    idx += np.repeat(first - (np.cumsum(counts) - counts), counts)
    return idx


def _branch_s(traj: Trajectory, g: I64, i: int, counts: I64, y: F64, c: F64, amp: F64, sign: F64, base: F64,
              s_mid: F64, round_: bool, plane: bool) -> F64:
    """Path coordinate of the boundaries ``y`` of pieces of one kind: circles (``round_``), arcs whose
    radius changes (two fixed-point rounds more), axial axes (``not plane``)."""
    assert traj.path is not None
    geo = traj.path.geometry
    yc = y - np.repeat(c, counts)
    if not plane:
        w = geo.w[g, i]
        out: F64 = yc / np.repeat(np.where(w != 0, w, 1.0), counts)
        return out
    kap = np.repeat(np.where(geo.kappa[g] != 0, geo.kappa[g], 1.0), counts)
    off = np.repeat(base - geo.theta0[g], counts)
    sg = np.repeat(sign, counts)
    if round_:
        rho = np.repeat(np.maximum(geo.r0[g] * amp, 1e-300), counts)
        out = (off + np.arccos(np.clip(sg * yc / rho, -1.0, 1.0))) / kap
        return out
    s = np.repeat(s_mid, counts)
    r0, dr, a = np.repeat(geo.r0[g], counts), np.repeat(geo.dr[g], counts), np.repeat(amp, counts)
    for _ in range(3):
        rho = np.maximum((r0 + dr * s) * a, 1e-300)
        s = (off + np.arccos(np.clip(sg * yc / rho, -1.0, 1.0))) / kap
    return s
