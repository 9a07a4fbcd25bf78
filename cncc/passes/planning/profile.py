"""Acceleration-limited time-optimal speed profile on a line of intervals (TOPP).

Consumes intervals along the path coordinate ``s`` with a speed cap ``vcap``, an
acceleration cap ``acap`` and a length each, and caps ``xcap`` on the squared speed at
the interval boundaries; produces the time-optimal profile with piecewise-constant
acceleration (bang-bang), as phases ``(t0, duration, s0, v0, a)``.

For such a path the reachability analysis of TOPP-RA (Pham & Pham 2018) decouples:
the controllable set at each boundary is an interval of ``x = v^2`` and one backward
and one forward pass give the optimum.  Each pass is a min-plus scan,
``x[b+1] = min(xcap[b+1], x[b] + 2 a l)``, computed in closed form with
``numpy.minimum.accumulate`` — no Python loop, so a million intervals take well under
a second.  ``tests/passes/test_plan.py`` checks it against the ``toppra`` package.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cncc.ir.trajectory import FloatArray


@dataclass
class Phases:
    """Constant-acceleration (or, after filtering, constant-jerk) phases on ``s``."""

    t0: FloatArray
    dur: FloatArray
    s0: FloatArray
    v0: FloatArray
    a0: FloatArray
    j: FloatArray
    limit: np.ndarray  # int8, the Limit of each phase
    interval: np.ndarray | None = None  # index of the interval of each phase, when known
    segments: tuple[np.ndarray, np.ndarray] | None = None  # first and last segment each phase may cover

    @property
    def end_time(self) -> float:
        return float(self.t0[-1] + self.dur[-1]) if self.t0.size else 0.0


def min_plus_scan(xcap: FloatArray, step: FloatArray) -> FloatArray:
    """``x[0] = xcap[0]``, ``x[b+1] = min(xcap[b+1], x[b] + step[b])`` for all ``b``."""
    acc = np.concatenate([[0.0], np.cumsum(step)])
    out: FloatArray = acc + np.minimum.accumulate(xcap - acc)
    return out


def boundary_speeds(length: FloatArray, vcap: FloatArray, acap: FloatArray, xcap: FloatArray) -> FloatArray:
    """Optimal squared speeds at the ``n + 1`` boundaries of ``n`` intervals."""
    vc2 = vcap * vcap
    cap = np.minimum(xcap, np.concatenate([[np.inf], vc2]))
    cap = np.minimum(cap, np.concatenate([vc2, [np.inf]]))
    step = 2.0 * acap * length
    fwd = min_plus_scan(cap, step)
    bwd = min_plus_scan(cap[::-1], step[::-1])[::-1]
    out: FloatArray = np.maximum(np.minimum(fwd, bwd), 0.0)
    return out


def trapezoids(length: FloatArray, vcap: FloatArray, acap: FloatArray, x: FloatArray,
               limit: np.ndarray, accel_limit: int) -> Phases:
    """Per interval: accelerate, cruise, decelerate between the boundary speeds ``sqrt(x)``."""
    v_in, v_out = np.sqrt(x[:-1]), np.sqrt(x[1:])
    a = acap
    vp2 = np.minimum(vcap * vcap, (2 * a * length + x[:-1] + x[1:]) / 2)
    vp = np.sqrt(np.maximum(vp2, np.maximum(x[:-1], x[1:])))
    t_acc = (vp - v_in) / a
    t_dec = (vp - v_out) / a
    d_acc = (vp * vp - x[:-1]) / (2 * a)
    d_dec = (vp * vp - x[1:]) / (2 * a)
    d_cru = np.maximum(length - d_acc - d_dec, 0.0)
    t_cru = np.where(vp > 0, d_cru / np.maximum(vp, 1e-300), 0.0)
    n = length.size
    dur = np.stack([t_acc, t_cru, t_dec], axis=1).reshape(-1)
    v0 = np.stack([v_in, vp, vp], axis=1).reshape(-1)
    acc = np.stack([a, np.zeros(n), -a], axis=1).reshape(-1)
    s_start = np.concatenate([[0.0], np.cumsum(length)[:-1]])
    s0 = np.stack([s_start, s_start + d_acc, s_start + d_acc + d_cru], axis=1).reshape(-1)
    lim = np.stack([np.full(n, accel_limit), limit, np.full(n, accel_limit)], axis=1).reshape(-1)
    interval = np.repeat(np.arange(n), 3)
    keep = dur > 1e-12
    dur, v0, acc, s0, lim, interval = dur[keep], v0[keep], acc[keep], s0[keep], lim[keep], interval[keep]
    t0 = np.concatenate([[0.0], np.cumsum(dur)[:-1]]) if dur.size else dur
    return Phases(t0, dur, s0, v0, acc, np.zeros_like(dur), lim.astype(np.int8), interval)
