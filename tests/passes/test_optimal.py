"""-O3 (planning/optimal.py): within every limit verify checks, bounded work per window,
W0605 and the start profile where a window cannot be solved."""

from __future__ import annotations

import math
import time

import numpy as np
import pytest

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink
from cncc.passes.planning import optimal
from cncc.passes.planning.profile import Phases
from cncc.passes.planning.segments import Segments

pytest.importorskip("casadi")

J_AXIS = np.array([50000.0, 50000.0, 30000.0, 1e9, 1e9, 1e9])  # generic-mill X, Y, Z
A_AXIS = np.array([1500.0, 1500.0, 800.0, 1e9, 1e9, 1e9])
PERIOD = 0.001
V_CORNER = 5.0  # mm/s allowed at the two interior vertices


def _zigzag() -> Segments:
    """Three 2 mm segments in XY, turning by 120 degrees at both interior vertices."""
    angles = [0.0, 2 * math.pi / 3, 0.0]
    u = np.zeros((3, 6))
    u[:, 0], u[:, 1] = np.cos(angles), np.sin(angles)
    length = np.full(3, 2.0)
    p0 = np.vstack([np.zeros(6), np.cumsum(u[:-1] * 2.0, axis=0)])
    au = np.abs(u)
    with np.errstate(divide="ignore", over="ignore"):
        acap = np.where(au > 1e-12, A_AXIS / np.maximum(au, 1e-300), np.inf).min(axis=1)
        jcap = np.where(au > 1e-12, J_AXIS / np.maximum(au, 1e-300), np.inf).min(axis=1)
    return Segments(p0, u, length, np.array([0.0, 2.0, 4.0, 6.0]), np.arange(3), np.full(3, 50.0),
                    np.zeros(3, np.int8), acap, jcap, np.array([0.0, V_CORNER, V_CORNER, 0.0]))


def _slow_start(total_mm: float = 6.0, v_peak: float = V_CORNER) -> Phases:
    """Rest to rest in four phases of jerk +J, -J, -J, +J (each tau), peak speed ``v_peak``:
    distance 2 J tau^3 and peak J tau^2, so tau = D / (2 v) and J = v / tau^2."""
    tau = total_mm / (2 * v_peak)
    jerk = v_peak / tau**2
    js = np.array([jerk, -jerk, -jerk, jerk])
    t0 = tau * np.arange(4)
    s, v, a = np.zeros(4), np.zeros(4), np.zeros(4)
    for k in range(3):
        s[k + 1] = s[k] + v[k] * tau + a[k] * tau**2 / 2 + js[k] * tau**3 / 6
        v[k + 1] = v[k] + a[k] * tau + js[k] * tau**2 / 2
        a[k + 1] = a[k] + js[k] * tau
    assert s[3] + v[3] * tau + a[3] * tau**2 / 2 + js[3] * tau**3 / 6 == pytest.approx(total_mm)
    return Phases(t0, np.full(4, tau), s, v, a, js, np.zeros(4, np.int8))


def _knot_accels(ph: Phases, s_vertex: float) -> np.ndarray:
    """Path acceleration at the knots that sit on the vertex at ``s_vertex`` (both sides)."""
    d = ph.dur
    s_end = ph.s0 + ph.v0 * d + ph.a0 * d**2 / 2 + ph.j * d**3 / 6
    a_end = ph.a0 + ph.j * d
    at_start = np.abs(ph.s0 - s_vertex) < 1e-7
    at_end = np.abs(s_end - s_vertex) < 1e-7
    assert at_start.any() or at_end.any(), "no knot on the vertex"
    out: np.ndarray = np.concatenate([ph.a0[at_start], a_end[at_end]])
    return out


def test_accel_step_caps_are_the_jerk_rule_at_each_vertex() -> None:
    seg = _zigzag()
    caps = optimal.accel_step_caps(seg, J_AXIS, PERIOD)
    du = np.abs(seg.u[1] - seg.u[0])  # (1 - cos 120, sin 120) = (1.5, 0.866)
    assert du[:2] == pytest.approx([1.5, math.sqrt(3) / 2])
    assert caps[1] == pytest.approx(50000.0 * PERIOD / 1.5)
    assert caps[0] == math.inf and caps[-1] == math.inf


def test_o3_keeps_the_acceleration_step_at_vertices_within_j_t() -> None:
    seg, start = _zigzag(), _slow_start()
    caps = optimal.accel_step_caps(seg, J_AXIS, PERIOD)
    sink = DiagnosticSink()
    best = optimal.optimise(seg, start, sink, vertex_acap=caps)
    assert best.end_time < 0.8 * start.end_time  # it did optimise
    for m in (1, 2):
        a = _knot_accels(best, float(seg.s0[m]))
        # the per-axis step a |du_i| is what verify's E0618 compares with j_i T
        step = np.abs(a).max() * np.abs(seg.u[m] - seg.u[m - 1])
        assert (step <= J_AXIS * PERIOD * (1 + 1e-6) + 1e-9).all(), (m, a)
    # without the caps the optimum uses far more acceleration at the vertices: the caps bind
    free = optimal.optimise(seg, start, DiagnosticSink())
    a_free = max(np.abs(_knot_accels(free, float(seg.s0[m]))).max() for m in (1, 2))
    assert a_free > 1.5 * caps[1]


def test_a_window_that_cannot_be_solved_keeps_its_start_with_w0605() -> None:
    seg, start = _zigzag(), _slow_start()
    # caps far below the start profile's own acceleration at the vertices: the window's
    # fixed end state (on the start profile) is infeasible
    a_start = max(np.abs(_knot_accels(optimal.split_at(start, seg.s0[1:-1]), float(seg.s0[m]))).max()
                  for m in (1, 2))
    assert a_start > 0.1
    impossible = np.array([np.inf, 1e-3, 1e-3, np.inf])
    sink = DiagnosticSink()
    out = optimal.optimise(seg, start, sink, vertex_acap=impossible)
    assert out.end_time <= start.end_time * (1 + 1e-9)
    assert dg.PLAN_FALLBACK in {d.code for d in sink}


def test_each_window_stops_at_the_cpu_limit(monkeypatch: pytest.MonkeyPatch) -> None:
    seg, start = _zigzag(), _slow_start()
    optimal._solver.cache_clear()
    monkeypatch.setattr(optimal, "MAX_CPU_S", 1e-4)
    monkeypatch.setattr(optimal, "MAX_ITER", 3000)
    n = optimal.split_at(start, seg.s0[1:-1]).t0.size  # the one window's size
    try:
        c0 = time.process_time()
        out = optimal.optimise(seg, start, DiagnosticSink(), vertex_acap=optimal.accel_step_caps(seg, J_AXIS, PERIOD))
        used = time.process_time() - c0
        status = str(optimal._solver(n).stats()["return_status"])
    finally:
        optimal._solver.cache_clear()
    assert status == "Maximum_CpuTime_Exceeded"  # IPOPT stopped by the per-window limit
    assert out.end_time <= start.end_time * (1 + 1e-9)  # and the result is still never slower than its start
    assert used < 30.0
