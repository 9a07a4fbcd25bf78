"""Step times inside monotone pieces: the roots of ``p(u) = boundary``, vectorised over steps.

Consumes, per monotone piece of one axis, the step count, the direction, the step
count and position at the piece start, the polynomial there (``v``, ``a``, ``j``),
the piece's duration and its end state; produces the local time ``u`` (seconds from
the piece start) of every step, pieces concatenated in order.

Everything is done in the *direction frame* (distances, velocity, acceleration and
jerk multiplied by the direction), where the distance ``D`` to a boundary and the
velocity are non-negative and ``f(u) = V u + A u^2/2 + J u^3/6`` increases on the
piece.  Three kinds of piece, each solved on its own steps only:

* **cruise** (``A = J = 0``): ``u = D / V``;
* **constant acceleration** (``J = 0``): ``u = D / (V/2 + sqrt(V^2/4 + A D/2))``, exact and
  free of cancellation;
* **jerk**: a guess from the nearer end of the piece (the no-jerk root, or the pure-jerk
  cube root where that is not defined), one Halley step (cubic convergence) and one
  Newton step.  The Newton step's size bounds the error left before it; a root whose
  last step is above :data:`ACCEPT_STEP_S` goes to a bracketed Newton/bisection solver.
  The planner's jerk phases are cut into short segments (:func:`.solve.segment`), so
  the guess is close and the fallback is rare.

The error after the accepted Newton step is about ``|f''| s^2 / (2 f')`` for a step
``s``; with ``s <= 1e-9 s`` it is far below a picosecond for any phase the planner
makes, so the integer-nanosecond rounding is the only error that shows.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

F64 = npt.NDArray[np.float64]
I64 = npt.NDArray[np.int64]

ACCEPT_STEP_S = 1e-9
FALLBACK_TOL_S = 1e-13
FALLBACK_MAX_ITER = 100


def piece_times(d: F64, counts: I64, v: F64, a: F64, j: F64, length: F64,
                ends: tuple[F64, F64, F64]) -> F64:
    """Local time of every step; ``d`` (per step) and ``v a j length ends`` (per piece) in the direction frame.

    ``ends`` = (distance from the piece start to its end, velocity and acceleration at the end).
    """
    cruise = (j == 0) & (a == 0)
    with np.errstate(divide="ignore", over="ignore"):
        inv_v = np.where(cruise, 1.0 / v, 0.0)
    with np.errstate(invalid="ignore"):
        u: F64 = d * np.repeat(inv_v, counts)  # cruise steps; the others are overwritten below
    if np.any(cruise & (v == 0)):  # a boundary on a piece that stands still (0 * inf): the step is at its start
        u[np.isnan(u)] = 0.0
    if not cruise.all():
        first = np.cumsum(counts) - counts
        for kind, solver in ((~cruise & (j == 0), _accel), (j != 0, _jerk)):
            if kind.any():
                k_counts = counts[kind]
                idx = _step_index(first[kind], k_counts)
                u[idx] = solver(d[idx], k_counts, v[kind], a[kind], j[kind], length[kind],
                                tuple(e[kind] for e in ends))
    np.minimum(u, np.repeat(length, counts), out=u)
    return u


def _step_index(first: I64, counts: I64) -> I64:
    """Indices of the steps of the pieces starting at ``first`` with ``counts`` steps."""
    total = int(counts.sum())
    idx = np.arange(total, dtype=np.int64)
    idx += np.repeat(first - (np.cumsum(counts) - counts), counts)
    return idx


def _accel(d: F64, counts: I64, v: F64, a: F64, j: F64, length: F64, ends: tuple[F64, ...]) -> F64:
    w = np.repeat(0.5 * v, counts)
    root = d * np.repeat(0.5 * a, counts)
    root += w * w
    np.maximum(root, 0.0, out=root)
    np.sqrt(root, out=root)
    root += w
    with np.errstate(divide="ignore", invalid="ignore"):
        u = np.divide(d, root, out=root)
    u[d <= 0.0] = 0.0  # a boundary at the piece start (from rest: 0/0): the step is at once
    return _clamp(u, np.repeat(length, counts))


def _clamp(u: F64, lim: F64) -> F64:
    u = np.where(np.isfinite(u), u, lim)
    np.clip(u, 0.0, lim, out=u)
    return u


def _jerk(d: F64, counts: I64, v: F64, a: F64, j: F64, length: F64, ends: tuple[F64, ...]) -> F64:
    span, ve, ae = ends
    rest = np.repeat(span, counts) - d  # distance from the boundary to the piece end
    near_end = rest < d
    vs, acc, jk, lim = (np.repeat(x, counts) for x in (v, a, j, length))
    u = _guess(d, vs, acc, jk, lim)
    if near_end.any():
        sel = np.flatnonzero(near_end)
        # backwards in time from the end: Ve w - Ae w^2/2 + J w^3/6 = rest
        w = _guess(rest[sel], np.repeat(ve, counts)[sel], -np.repeat(ae, counts)[sel], jk[sel], lim[sel])
        u[sel] = lim[sel] - w
    return _refine(u, d, vs, acc, jk, lim)


def _guess(d: F64, v: F64, a: F64, j: F64, lim: F64) -> F64:
    """Root of the no-jerk part (``V u + A u^2/2 = d``), else the pure-jerk cube root, clamped to the piece."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        w = 0.5 * v
        root = w * w + 0.5 * a * d
        u = d / (w + np.sqrt(root))
        bad = ~((root >= 0) & (u <= lim))  # NaN compares False: bad
        if bad.any():
            cube = np.cbrt(6.0 * d / j)
            u = np.where(bad, np.where(cube <= lim, cube, 0.5 * lim), u)
    u = np.where(u >= 0, u, 0.0)
    return u


def _refine(u: F64, d: F64, v: F64, a: F64, j: F64, lim: F64) -> F64:
    """One Halley and one Newton step; roots whose Newton step is large go to :func:`_bracketed`."""
    j6, j2, a2 = j / 6.0, j / 2.0, a / 2.0
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        f = ((j6 * u + a2) * u + v) * u - d
        fp = (j2 * u + a) * u + v
        fpp = j * u + a
        u = u - 2.0 * f * fp / (2.0 * fp * fp - f * fpp)
        f = ((j6 * u + a2) * u + v) * u - d
        fp = (j2 * u + a) * u + v
        step = f / fp
        u -= step
        ok = (np.abs(step) <= ACCEPT_STEP_S) & (u >= -ACCEPT_STEP_S) & (u <= lim + ACCEPT_STEP_S)
    if not ok.all():
        sel = np.flatnonzero(~ok)
        u[sel] = _bracketed(u[sel], d[sel], v[sel], a[sel], j[sel], lim[sel])
    np.clip(u, 0.0, lim, out=u)
    return u


def _bracketed(u: F64, d: F64, v: F64, a: F64, j: F64, lim: F64) -> F64:
    """Roots of ``v u + a u^2/2 + j u^3/6 = d`` in ``[0, lim]`` (increasing there): Newton kept in a bracket."""
    out = np.empty_like(u)
    lo = np.zeros_like(u)
    hi = lim.copy()
    u = np.where(np.isfinite(u) & (u > 0) & (u < lim), u, 0.5 * lim)
    idx = np.arange(u.shape[0])
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for _ in range(FALLBACK_MAX_ITER):
            f = u * (v + u * (a / 2 + u * j / 6)) - d
            lo = np.where(f < 0, u, lo)
            hi = np.where(f > 0, u, hi)
            un = u - f / (v + u * (a + u * j / 2))
            un = np.where((un > lo) & (un < hi), un, 0.5 * (lo + hi))
            done = (np.abs(un - u) <= FALLBACK_TOL_S) | (f == 0) | (hi - lo <= FALLBACK_TOL_S)
            if done.any():
                out[idx[done]] = un[done]
                keep = ~done
                idx, u, d, v, a, j, lo, hi = (x[keep] for x in (idx, un, d, v, a, j, lo, hi))
                if idx.size == 0:
                    return out
            else:
                u = un
    out[idx] = u
    return out
