"""-O3: jerk-limited time-optimal path profile over windows with CasADi/IPOPT.

Consumes the run's :class:`Segments` and the -O2 profile (used as the phase structure
and the warm start); produces constant-jerk :class:`Phases`.

The -O2 phases are split at the vertices, so each phase lies on one segment ``k``.
Per window of at most :data:`WINDOW` phases the NLP is (multiple shooting, exact
cubic integration): minimise ``sum h_p`` over durations ``h_p >= 0`` and jerks
``j_p`` with states ``(s, v, a)`` at the knots, subject to ``|j_p| <= jcap_k``,
``|a| <= acap_k`` at both ends (exact: ``a`` is linear), ``0 <= v <= vcap_k`` at both
ends and the middle, ``v <= vvert_m`` and ``s = s_m`` at the knot that crosses vertex
``m``.  Window ends keep the -O2 state, so windows solve independently.  The caps are
the raw ones (no widening): -O3 optimises the same constraint model as -O2 without
-O2's filter.  A final uniform time scaling removes any excess of the velocity inside a
phase (checked only at three points in the NLP); a window that IPOPT cannot solve
keeps its -O2 phases (W0605).
"""

from __future__ import annotations

import numpy as np

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink
from cncc.ir.trajectory import FloatArray
from cncc.passes.planning.emit import eval_phase, split_at
from cncc.passes.planning.profile import Phases
from cncc.passes.planning.segments import Segments
from cncc.source import NO_SPAN

WINDOW = 400


def optimise(seg: Segments, o2: Phases, sink: DiagnosticSink) -> Phases:
    ph = split_at(o2, seg.s0[1:-1])
    n = ph.t0.size
    s_end, v_end, a_end = eval_phase(ph, np.arange(n), ph.dur)
    s_knot = np.concatenate([ph.s0, s_end[-1:]])
    v_knot = np.concatenate([ph.v0, v_end[-1:]])
    a_knot = np.concatenate([ph.a0, a_end[-1:]])
    s_mid, _, _ = eval_phase(ph, np.arange(n), ph.dur / 2)
    k = np.clip(np.searchsorted(seg.s0, s_mid, side="right") - 1, 0, seg.count - 1)
    vertex = np.full(n + 1, -1)
    on_vertex = np.isclose(s_knot[:, None], seg.s0[None, 1:-1], rtol=0, atol=1e-9)
    hit = on_vertex.any(axis=1)
    vertex[hit] = np.argmax(on_vertex[hit], axis=1) + 1
    h_all, j_all = ph.dur.copy(), ph.j.copy()
    st = [s_knot[:-1].copy(), v_knot[:-1].copy(), a_knot[:-1].copy()]
    for lo in range(0, n, WINDOW):
        hi = min(n, lo + WINDOW)
        sol = _solve(seg, k[lo:hi], vertex[lo:hi + 1], s_knot[lo:hi + 1], v_knot[lo:hi + 1], a_knot[lo:hi + 1],
                     h_all[lo:hi], j_all[lo:hi])
        if sol is None:
            sink.emit(dg.PLAN_FALLBACK, NO_SPAN, "-O3: IPOPT failed on a window; the -O2 profile is kept there")
            continue
        h_all[lo:hi], j_all[lo:hi] = sol[0], sol[1]
        for i in range(3):
            st[i][lo:hi] = sol[2][i][:-1]
    return _scaled(h_all, j_all, st, ph.limit, seg, k)


def _solve(seg: Segments, k: np.ndarray, vertex: np.ndarray, s0: FloatArray, v0: FloatArray, a0: FloatArray,
           h_init: FloatArray, j_init: FloatArray
           ) -> tuple[FloatArray, FloatArray, list[FloatArray]] | None:
    import casadi as ca

    n = k.size
    opti = ca.Opti()
    h = opti.variable(n)
    j = opti.variable(n)
    s = opti.variable(n + 1)
    v = opti.variable(n + 1)
    a = opti.variable(n + 1)
    vc, ac, jc = seg.vcap[k], seg.acap[k], seg.jcap[k]
    opti.subject_to(s[1:] == s[:-1] + v[:-1] * h + a[:-1] * h**2 / 2 + j * h**3 / 6)
    opti.subject_to(v[1:] == v[:-1] + a[:-1] * h + j * h**2 / 2)
    opti.subject_to(a[1:] == a[:-1] + j * h)
    v_mid = v[:-1] + a[:-1] * h / 2 + j * h**2 / 8
    opti.subject_to(opti.bounded(0, h, 10 * max(float(h_init.sum()), 1e-3)))
    opti.subject_to(opti.bounded(-jc, j, jc))
    for lo_hi, cap in ((v[:-1], vc), (v[1:], vc), (v_mid, vc)):
        opti.subject_to(opti.bounded(0, lo_hi, cap))
    opti.subject_to(opti.bounded(-ac, a[:-1], ac))
    opti.subject_to(opti.bounded(-ac, a[1:], ac))
    for node in np.flatnonzero(vertex >= 0):
        m = int(vertex[node])
        opti.subject_to(s[int(node)] == seg.s0[m])
        opti.subject_to(v[int(node)] <= seg.vvert[m])
    for var, val in ((s, s0), (v, v0), (a, a0)):
        opti.subject_to(var[0] == val[0])
        opti.subject_to(var[n] == val[-1])
    opti.minimize(ca.sum1(h))
    opti.set_initial(h, h_init)
    opti.set_initial(j, j_init)
    opti.set_initial(s, s0)
    opti.set_initial(v, v0)
    opti.set_initial(a, a0)
    opti.solver("ipopt", {"print_time": False}, {"print_level": 0, "max_iter": 1500, "max_cpu_time": 30.0, "tol": 1e-9,
                                                 "sb": "yes"})
    try:
        sol = opti.solve()
    except RuntimeError:
        return None
    h_opt = np.maximum(np.array(sol.value(h), float).reshape(-1), 0.0)
    if h_opt.sum() > h_init.sum():
        return None
    states = [np.array(sol.value(x), float).reshape(-1) for x in (s, v, a)]
    return h_opt, np.array(sol.value(j), float).reshape(-1), states


def _scaled(h: FloatArray, j: FloatArray, st: list[FloatArray], limit: np.ndarray, seg: Segments,
            k: np.ndarray) -> Phases:
    """Phases from the solved knot states; time scaled so no cap is exceeded inside a phase."""
    s, v, a = st
    v_end = v + a * h + j * h**2 / 2
    a_end = a + j * h
    with np.errstate(divide="ignore", invalid="ignore"):
        t_star = np.where(j != 0, -a / j, 0.0)
    inside = (t_star > 0) & (t_star < h)
    v_peak = np.maximum(np.maximum(v, v_end), np.where(inside, v + a * t_star + j * t_star**2 / 2, 0))
    ratio = max(1.0, float(np.max(v_peak / seg.vcap[k])))
    ratio = max(ratio, float(np.sqrt(np.max(np.maximum(np.abs(a), np.abs(a_end)) / seg.acap[k]))))
    ratio = max(ratio, float(np.cbrt(np.max(np.abs(j) / seg.jcap[k]))))
    lam = ratio * (1 + 1e-9) if ratio > 1 else 1.0
    h2 = h * lam
    keep = h2 > 1e-13
    t0 = np.concatenate([[0.0], np.cumsum(h2[keep])[:-1]])
    return Phases(t0, h2[keep], s[keep], (v / lam)[keep], (a / lam**2)[keep], (j / lam**3)[keep], limit[keep])
