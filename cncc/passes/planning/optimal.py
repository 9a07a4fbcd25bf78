"""-O3: jerk-limited time-optimal path profile over overlapping windows with CasADi/IPOPT.

Consumes a part's :class:`Segments` (rest to rest) and its -O2 profile; produces
constant-jerk :class:`Phases` that are never slower than -O2's.

The -O2 phases, split at the vertices so that each lies on one segment ``k``, give the
structure and the warm start.  Per window of at most :data:`WINDOW` phases the NLP is
(multiple shooting, exact cubic integration)::

    minimise  sum h_p   over durations h_p >= 0, jerks |j_p| <= jcap_k and the knot states
    s, v, a:  s' = s + v h + a h^2/2 + j h^3/6,  v' = v + a h + j h^2/2,  a' = a + j h
              0 <= v <= vcap_k at both ends and in the middle of each phase,
              |a| <= acap_k at both ends (a is linear), v <= vvert_m and s = s_m at the
              knot that crosses vertex m, the first and last knot fixed.

Every constraint but the dynamics is a *bound*, so one compiled solver per window size
serves all windows (the caps are bound values).  Windows overlap by :data:`OVERLAP`
phases: only the first ``WINDOW - OVERLAP`` phases of a solution are kept and the next
window starts from the state reached there, its end fixed to -O2's state further on, so
improvements propagate.  The caps are the raw ones (no widening): -O3 optimises the
constraint model of -O2 without -O2's filter.  After all windows the exact extremes of
every phase (the velocity inside a phase is checked only at three points by the NLP)
are measured and the whole part is slowed down by the tiny factor that removes any
excess.  A window IPOPT cannot solve keeps its -O2 phases (W0605).

Bounded work per window: IPOPT stops after :data:`MAX_ITER` iterations or
:data:`MAX_CPU_S` CPU seconds, whichever first; such a window counts as failed and keeps
its start phases (W0605), so the cost is linear in the number of windows.

With ``vertex_acap`` (:func:`accel_step_caps`: ``min_i j_i T / |du_i|`` at each vertex),
the path acceleration at a knot on a vertex is bounded too: the per-axis acceleration
steps by ``a |du_i|`` there, and verify's E0618 wants that within ``j_i T``.
"""

from __future__ import annotations

from functools import lru_cache
from typing import Any

import numpy as np

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink
from cncc.ir.trajectory import FloatArray
from cncc.passes.planning.emit import eval_phase, split_at
from cncc.passes.planning.profile import Phases
from cncc.passes.planning.segments import Segments
from cncc.source import NO_SPAN

Solution = tuple[FloatArray, FloatArray, list[FloatArray]]

WINDOW = 96
OVERLAP = 32
MAX_ITER = 400
MAX_CPU_S = 20.0
_SOLVED = ("Solve_Succeeded", "Solved_To_Acceptable_Level")


def accel_step_caps(seg: Segments, jmax_mm_s3: FloatArray, period_s: float) -> FloatArray:
    """``(k + 1,)`` bounds on ``|a|`` at the vertices (inf at the ends and where the direction
    does not change): the per-axis step ``a |du_i|`` stays within ``j_i T`` (``du`` between
    the end tangent of one segment and the start tangent of the next, when curved segments
    give them)."""
    out = np.full(seg.count + 1, np.inf)
    u_in = getattr(seg, "u_in", None)  # tangents at the segment ends, where segments are curved
    u_out = getattr(seg, "u_out", None)
    if u_in is not None and u_out is not None:
        du = np.abs(u_in[1:] - u_out[:-1])
    else:
        du = np.abs(seg.u[1:] - seg.u[:-1])
    if du.size:
        with np.errstate(divide="ignore"):
            per_axis = np.where(du > 1e-12, jmax_mm_s3[None, :du.shape[1]] * period_s / np.maximum(du, 1e-300), np.inf)
        out[1:-1] = per_axis.min(axis=1)
    return out


def optimise(seg: Segments, o2: Phases, sink: DiagnosticSink, vertex_acap: FloatArray | None = None) -> Phases:
    """-O3's profile of one part, never slower than ``o2`` (see the module docstring)."""
    if seg.count < 2 or o2.t0.size < 3:
        return o2
    ph = split_at(o2, seg.s0[1:-1])
    n = ph.t0.size
    s_end, v_end, a_end = eval_phase(ph, np.arange(n), ph.dur)
    knots = [np.append(ph.s0, s_end[-1]), np.append(ph.v0, v_end[-1]), np.append(ph.a0, a_end[-1])]
    s_mid, _, _ = eval_phase(ph, np.arange(n), ph.dur / 2)
    k = np.clip(np.searchsorted(seg.s0, s_mid, side="right") - 1, 0, seg.count - 1)
    vertex = _vertex_of_knots(seg, knots[0])
    h, j = ph.dur.copy(), ph.j.copy()
    state = [x.copy() for x in knots]  # knot states of the result so far
    lo, failed = 0, 0
    prev: tuple[int, int, Solution] | None = None
    while lo < n:
        hi = min(n, lo + WINDOW)
        sol = _solve_window(seg, k[lo:hi], vertex[lo:hi + 1], [x[lo:hi + 1] for x in knots],
                            [x[lo] for x in state], h[lo:hi], j[lo:hi], vertex_acap)
        if not isinstance(sol, tuple):
            # keep the previous window's solution to its end (where it meets -O2's state),
            # then -O2's own phases up to this window's end
            failed += sol == "failed"
            resume = lo
            if prev is not None:
                _apply(prev[2], prev[0], lo, prev[1], h, j, state)
                resume = prev[1]
            h[resume:hi], j[resume:hi] = ph.dur[resume:hi], ph.j[resume:hi]
            for i in range(3):
                state[i][resume:hi + 1] = knots[i][resume:hi + 1]
            prev, lo = None, max(hi, resume)
            continue
        keep = hi - lo if hi == n else max(1, hi - lo - OVERLAP)
        _apply(sol, lo, lo, lo + keep, h, j, state)
        prev = (lo, hi, sol)
        lo += keep
    if failed:
        sink.emit(dg.PLAN_FALLBACK, NO_SPAN, f"-O3: IPOPT failed on {failed} window(s); -O2's profile is kept there")
    out = _scaled(h, j, state, ph.limit, seg, k)
    return out if out is not None and out.end_time <= o2.end_time else o2


def _apply(sol: Solution, origin: int, lo: int, hi: int, h: FloatArray, j: FloatArray,
           state: list[FloatArray]) -> None:
    """Copy phases ``[lo, hi)`` (and their knots) of a window solved from phase ``origin``."""
    a, b = lo - origin, hi - origin
    h[lo:hi], j[lo:hi] = sol[0][a:b], sol[1][a:b]
    for i in range(3):
        state[i][lo:hi + 1] = sol[2][i][a:b + 1]


def _vertex_of_knots(seg: Segments, s_knot: FloatArray) -> np.ndarray:
    """Index of the interior vertex each knot sits on, or -1."""
    inner = seg.s0[1:-1]
    if inner.size == 0:
        return np.full(s_knot.size, -1)
    right = np.clip(np.searchsorted(inner, s_knot), 0, inner.size - 1)
    left = np.maximum(right - 1, 0)
    pick = np.where(np.abs(inner[right] - s_knot) <= np.abs(inner[left] - s_knot), right, left)
    out: np.ndarray = np.where(np.abs(inner[pick] - s_knot) <= 1e-9, pick + 1, -1)
    return out


@lru_cache(maxsize=8)
def _solver(n: int) -> Any:
    import casadi as ca

    x = ca.SX.sym("x", 5 * n + 3)
    h, j = x[:n], x[n:2 * n]
    s, v, a = x[2 * n:3 * n + 1], x[3 * n + 1:4 * n + 2], x[4 * n + 2:]
    h2 = h * h
    g = ca.vertcat(
        s[1:] - (s[:-1] + v[:-1] * h + a[:-1] * h2 / 2 + j * h2 * h / 6),
        v[1:] - (v[:-1] + a[:-1] * h + j * h2 / 2),
        a[1:] - (a[:-1] + j * h),
        v[:-1] + a[:-1] * h / 2 + j * h2 / 8,
    )
    opts: dict[str, Any] = {
        "print_time": False, "ipopt.print_level": 0, "ipopt.sb": "yes", "ipopt.max_iter": MAX_ITER,
        "ipopt.max_cpu_time": MAX_CPU_S, "ipopt.tol": 1e-9, "ipopt.constr_viol_tol": 1e-10,
        "ipopt.acceptable_tol": 1e-7, "ipopt.acceptable_constr_viol_tol": 1e-9,
        "ipopt.mu_strategy": "adaptive", "ipopt.bound_relax_factor": 0.0}
    return ca.nlpsol(f"o3_{n}", "ipopt", {"x": x, "f": ca.sum1(h), "g": g}, opts)


def _solve_window(seg: Segments, k: np.ndarray, vertex: np.ndarray, o2: list[FloatArray], start: list[float],
                  h0: FloatArray, j0: FloatArray, vertex_acap: FloatArray | None = None) -> Solution | str:
    """The window's solution, or ``"failed"`` / ``"no gain"``."""
    n = k.size
    vc, ac, jc = seg.vcap[k], seg.acap[k], seg.jcap[k]
    v_knot = np.minimum(np.append(vc, vc[-1]), np.insert(vc, 0, vc[0]))
    a_knot = np.minimum(np.append(ac, ac[-1]), np.insert(ac, 0, ac[0]))
    on_v = vertex >= 0
    if vertex_acap is not None:
        a_knot = np.where(on_v, np.minimum(a_knot, vertex_acap[np.maximum(vertex, 0)]), a_knot)
    v_knot = np.where(on_v, np.minimum(v_knot, seg.vvert[np.maximum(vertex, 0)]), v_knot)
    s_lo, s_hi = np.full(n + 1, -np.inf), np.full(n + 1, np.inf)
    s_lo[on_v] = s_hi[on_v] = seg.s0[vertex[on_v]]
    v_lo, v_hi = np.zeros(n + 1), v_knot.copy()
    a_lo, a_hi = -a_knot, a_knot.copy()
    for arr_lo, arr_hi, val in ((s_lo, s_hi, (start[0], o2[0][-1])), (v_lo, v_hi, (start[1], o2[1][-1])),
                                (a_lo, a_hi, (start[2], o2[2][-1]))):
        arr_lo[0] = arr_hi[0] = val[0]
        arr_lo[-1] = arr_hi[-1] = val[1]
    if v_lo[0] > v_hi[0] * (1 + 1e-9) + 1e-12 or abs(a_lo[0]) > a_knot[0] * (1 + 1e-9) + 1e-9:
        return "failed"  # the start state left by the previous window is outside this window's caps
    h_max = 10.0 * max(float(h0.sum()), 1e-6)
    lbx = np.concatenate([np.zeros(n), -jc, s_lo, v_lo, a_lo])
    ubx = np.concatenate([np.full(n, h_max), jc, s_hi, v_hi, a_hi])
    x0 = np.concatenate([h0, j0, o2[0], o2[1], o2[2]])
    x0[2 * n] = start[0]
    x0[3 * n + 1] = start[1]
    x0[4 * n + 2] = start[2]
    lbg = np.concatenate([np.zeros(3 * n), np.zeros(n)])
    ubg = np.concatenate([np.zeros(3 * n), vc])
    solver = _solver(n)
    try:
        res = solver(x0=np.clip(x0, lbx, ubx), lbx=lbx, ubx=ubx, lbg=lbg, ubg=ubg)
    except RuntimeError:
        return "failed"
    status = str(solver.stats()["return_status"])
    x = np.array(res["x"], float).reshape(-1)
    g = np.array(res["g"], float).reshape(-1)
    v_mid = g[3 * n:]
    bad_mid = bool((v_mid < -1e-9).any() or (v_mid > vc * (1 + 1e-9) + 1e-12).any())
    if not np.all(np.isfinite(x)) or np.abs(g[:3 * n]).max(initial=0.0) > 1e-7 or bad_mid:
        return "failed" if status not in _SOLVED else "no gain"
    h = np.maximum(x[:n], 0.0)
    if h.sum() > h0.sum():
        return "failed" if status not in _SOLVED else "no gain"
    return h, x[n:2 * n], [x[2 * n:3 * n + 1], x[3 * n + 1:4 * n + 2], x[4 * n + 2:]]


def _scaled(h: FloatArray, j: FloatArray, st: list[FloatArray], limit: np.ndarray, seg: Segments,
            k: np.ndarray) -> Phases | None:
    """Phases from the knot states; time scaled so that no cap is exceeded inside a phase
    (None if the path would run backwards somewhere)."""
    s, v, a = (x[:-1] for x in st)
    v_end = v + a * h + j * h**2 / 2
    a_end = a + j * h
    with np.errstate(divide="ignore", invalid="ignore"):
        t_star = np.where(j != 0, -a / j, 0.0)
    inside = (t_star > 0) & (t_star < h)
    v_in = np.where(inside, v + a * t_star + j * t_star**2 / 2, v)
    v_peak = np.maximum(np.maximum(v, v_end), v_in)
    if float(np.minimum(np.minimum(v, v_end), v_in).min()) < -1e-9:
        return None
    ratio = max(1.0, float(np.max(v_peak / seg.vcap[k])))
    ratio = max(ratio, float(np.sqrt(np.max(np.maximum(np.abs(a), np.abs(a_end)) / seg.acap[k]))))
    ratio = max(ratio, float(np.cbrt(np.max(np.abs(j) / seg.jcap[k]))))
    lam = ratio * (1 + 1e-9) if ratio > 1 else 1.0
    h2 = h * lam
    keep = h2 > 1e-13
    t0 = np.concatenate([[0.0], np.cumsum(h2[keep])[:-1]])
    return Phases(t0, h2[keep], s[keep], np.maximum(v / lam, 0.0)[keep], (a / lam**2)[keep], (j / lam**3)[keep],
                  limit[keep])
