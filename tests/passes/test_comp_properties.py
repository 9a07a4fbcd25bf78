"""Property tests of the transform and compensation passes on generated closed contours.

Contours are convex polygons (counter-clockwise) some of whose edges bulge outward as
arcs; the tool radius is small against the edges, so no interference is expected.
All expected values are computed here from the programmed geometry.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from cncc.diagnostics import DiagnosticSink
from cncc.ir import Arc, CompSide, Frame, Linear, Plane, Rapid
from cncc.ir.frame import Mirror, Rotation, Scaling
from cncc.passes import PassContext, run_pipeline
from cncc.passes.cutter_comp import CutterComp
from cncc.passes.mirror import MirrorPass
from cncc.passes.rotation import RotationPass
from cncc.passes.scaling import ScalingPass
from cncc.source import Span

Pt = tuple[float, float]
FEED = 1000.0


@st.composite
def contours(draw: Any) -> tuple[list[Pt], list[float], float]:
    """(vertices CCW, bulge half-angle per edge (0: a line), tool radius)."""
    n = draw(st.integers(3, 7))
    radius = draw(st.floats(20.0, 80.0))
    gaps = draw(st.lists(st.floats(0.5, 1.5), min_size=n, max_size=n))
    total = sum(gaps)
    start = draw(st.floats(0.0, 2 * math.pi))
    angles, a = [], start
    for g in gaps:
        angles.append(a)
        a += 2 * math.pi * g / total
    pts = [(radius * math.cos(t), radius * math.sin(t)) for t in angles]
    turn = min(2 * math.pi * g / total for g in gaps)  # the smallest exterior angle
    bulges = [draw(st.sampled_from([0.0, 0.0, 0.15, 0.3])) * turn for _ in range(n)]
    edge = min(math.dist(pts[k], pts[(k + 1) % n]) for k in range(n))
    r = draw(st.floats(0.02, 0.12)) * edge
    return pts, bulges, r


def _span(k: int) -> Span:
    return Span(0, 10 * k + 10, 10 * k + 11)


def _v(p: Pt, z: float = -1.0) -> tuple[float, float, float, float, float, float]:
    return (p[0], p[1], z, 0.0, 0.0, 0.0)


def _elements(pts: list[Pt], bulges: list[float], frame: Frame) -> list[Any]:
    out: list[Any] = []
    n = len(pts)
    for k in range(n):
        p0, p1 = pts[k], pts[(k + 1) % n]
        if bulges[k] == 0.0:
            out.append(Linear(_span(k), frame, _v(p0), _v(p1), FEED))
            continue
        half = math.dist(p0, p1) / 2
        rad = half / math.sin(bulges[k])
        mx, my = (p0[0] + p1[0]) / 2, (p0[1] + p1[1]) / 2
        d = (p1[0] - p0[0], p1[1] - p0[1])
        nl = (-d[1] / (2 * half), d[0] / (2 * half))  # left normal: inside of a CCW contour
        h = math.sqrt(rad * rad - half * half)
        c = (mx + h * nl[0], my + h * nl[1])  # centre inside: the arc bulges outward, CCW
        out.append(Arc(_span(k), frame, _v(p0), _v(p1), _v(c), 1, Plane.XY, FEED))
    return out


def _reverse(cmds: list[Any]) -> list[Any]:
    out = []
    for c in reversed(cmds):
        if isinstance(c, Arc):
            out.append(Arc(c.span, c.frame, c.end, c.start, c.center, -c.turns, c.plane, FEED))
        else:
            out.append(Linear(c.span, c.frame, c.end, c.start, FEED))
    return out


def _program(elements: list[Any], side: CompSide, r: float) -> list[Any]:
    """Start-up at the first vertex, once round, the first element again, cancel.

    Type A start-up and cancel do not settle the corner where they happen, so the
    closed contour is overlapped by one element: every corner of the contour's other
    elements is then a corner in offset mode.
    """
    on = Frame(comp_side=side, comp_radius_mm=r)
    off = Frame()
    els = [replace(e, frame=on) for e in elements]
    again = replace(els[0], span=Span(0, 8000, 8001))
    v0 = els[0].start
    center = (0.0, 0.0, -1.0, 0.0, 0.0, 0.0)
    return [Rapid(Span(0, 0, 1), off, (0.0, 0.0, 5.0, 0, 0, 0), center),
            Linear(Span(0, 1, 2), on, center, v0, FEED), *els, again,
            Linear(Span(0, 9000, 9001), off, again.end, center, FEED)]


def _compensate(cmds: list[Any]) -> tuple[list[Any], DiagnosticSink]:
    sink = DiagnosticSink()
    out = list(run_pipeline([CutterComp()], cmds, PassContext(sink=sink)))
    return out, sink


def _arc_points(c: Arc, n: int = 24) -> list[Pt]:
    cx, cy = c.center[0], c.center[1]
    a0 = math.atan2(c.start[1] - cy, c.start[0] - cx)
    a1 = math.atan2(c.end[1] - cy, c.end[0] - cx)
    sweep = (a1 - a0) % (2 * math.pi) if c.turns > 0 else -((a0 - a1) % (2 * math.pi))
    rad = math.hypot(c.start[0] - cx, c.start[1] - cy)
    return [(cx + rad * math.cos(a0 + sweep * k / n), cy + rad * math.sin(a0 + sweep * k / n)) for k in range(n + 1)]


def _points(c: Any) -> list[Pt]:
    if isinstance(c, Arc):
        return _arc_points(c)
    return [(c.start[0] + (c.end[0] - c.start[0]) * k / 10, c.start[1] + (c.end[1] - c.start[1]) * k / 10)
            for k in range(11)]


def _dist_to_element(p: Pt, e: Any) -> float:
    if isinstance(e, Arc):
        cx, cy = e.center[0], e.center[1]
        rad = math.hypot(e.start[0] - cx, e.start[1] - cy)
        a = math.atan2(p[1] - cy, p[0] - cx)
        a0 = math.atan2(e.start[1] - cy, e.start[0] - cx)
        a1 = math.atan2(e.end[1] - cy, e.end[0] - cx)
        sweep = (a1 - a0) % (2 * math.pi) if e.turns > 0 else (a0 - a1) % (2 * math.pi)
        rel = (a - a0) % (2 * math.pi) if e.turns > 0 else (a0 - a) % (2 * math.pi)
        if rel <= sweep:
            return abs(math.hypot(p[0] - cx, p[1] - cy) - rad)
        return min(math.dist(p, e.start[:2]), math.dist(p, e.end[:2]))
    a, b = e.start[:2], e.end[:2]
    d = (b[0] - a[0], b[1] - a[1])
    t = max(0.0, min(1.0, ((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / (d[0] ** 2 + d[1] ** 2)))
    return math.dist(p, (a[0] + t * d[0], a[1] + t * d[1]))


def _offset_mode(out: list[Any]) -> list[Any]:
    """The output of the elements whose both corners are in offset mode (all but the first)."""
    return [c for c in out if isinstance(c, Linear | Arc) and 20 <= c.span.start < 8000]


@settings(max_examples=60, deadline=None)
@given(contours(), st.sampled_from([CompSide.LEFT, CompSide.RIGHT]))
def test_compensated_path_keeps_the_tool_radius_away(data: tuple[list[Pt], list[float], float],
                                                   side: CompSide) -> None:
    pts, bulges, r = data
    elements = _elements(pts, bulges, Frame())
    out, sink = _compensate(_program(elements, side, r))
    assert not sink.has_errors, [d.message for d in sink]
    for c in _offset_mode(out):
        for p in _points(c):
            assert min(_dist_to_element(p, e) for e in elements) >= r - 1e-3, (p, r)  # 1 um


@settings(max_examples=60, deadline=None)
@given(contours(), st.sampled_from([CompSide.LEFT, CompSide.RIGHT]))
def test_each_offset_element_is_parallel_at_distance_r(data: tuple[list[Pt], list[float], float],
                                                     side: CompSide) -> None:
    pts, bulges, r = data
    elements = _elements(pts, bulges, Frame())
    out, _ = _compensate(_program(elements, side, r))
    sign = 1.0 if side is CompSide.LEFT else -1.0
    for e in elements:
        piece = next(c for c in out if c.span == e.span)  # the element's own offset piece
        if isinstance(e, Arc):
            assert isinstance(piece, Arc) and piece.turns == e.turns
            assert math.dist(piece.center[:2], e.center[:2]) < 1e-9
            rad = math.dist(e.start[:2], e.center[:2])
            assert math.dist(piece.start[:2], piece.center[:2]) == pytest.approx(rad - sign * r)
            continue
        d = (e.end[0] - e.start[0], e.end[1] - e.start[1])
        q = (piece.end[0] - piece.start[0], piece.end[1] - piece.start[1])
        length = math.hypot(*d)
        assert abs(d[0] * q[1] - d[1] * q[0]) / length < 1e-6 * max(1.0, math.hypot(*q))  # parallel
        assert d[0] * q[0] + d[1] * q[1] > 0  # same direction
        off = ((piece.start[0] - e.start[0]) * -d[1] + (piece.start[1] - e.start[1]) * d[0]) / length
        assert abs(off - sign * r) < 1e-6  # at r, on the programmed side


@settings(max_examples=60, deadline=None)
@given(contours())
def test_g41_on_a_contour_is_g42_on_the_reversed_contour(data: tuple[list[Pt], list[float], float]) -> None:
    pts, bulges, r = data
    elements = _elements(pts, bulges, Frame())
    left, _ = _compensate(_program(elements, CompSide.LEFT, r))
    right, _ = _compensate(_program(_reverse(elements), CompSide.RIGHT, r))
    for e in elements[1:-1]:  # both corners in offset mode in both programs
        fwd = next(c for c in left if c.span == e.span)
        back = next(c for c in right if c.span == e.span)
        assert math.dist(fwd.start[:2], back.end[:2]) < 1e-6 and math.dist(fwd.end[:2], back.start[:2]) < 1e-6
        if isinstance(e, Arc):
            assert isinstance(back, Arc) and back.turns == -fwd.turns
            assert math.dist(fwd.center[:2], back.center[:2]) < 1e-9


def _run(passes: list[Any], cmds: list[Any]) -> list[Any]:
    return list(run_pipeline(passes, cmds, PassContext(sink=DiagnosticSink())))


def _reframe(cmds: list[Any], **records: Any) -> list[Any]:
    return [replace(c, frame=replace(c.frame, **records)) for c in cmds]


def _with_approach(elements: list[Any]) -> list[Any]:
    """Start at the first vertex so that the transforms map every point (no unmoved start)."""
    return [Rapid(Span(0, 0, 1), elements[0].frame, elements[0].start, elements[0].start), *elements]


@settings(max_examples=40, deadline=None)
@given(contours(), st.floats(-50, 50), st.floats(-50, 50), st.sampled_from([(True, False, False),
                                                                            (False, True, False),
                                                                            (True, True, False)]))
def test_mirroring_twice_is_the_identity(data: tuple[list[Pt], list[float], float], ax: float, ay: float,
                                         axes: tuple[bool, bool, bool]) -> None:
    pts, bulges, r = data
    cmds = _with_approach(_elements(pts, bulges, Frame(comp_side=CompSide.LEFT, comp_radius_mm=r)))
    m = Mirror((ax, ay, 0.0), axes)
    once = _run([MirrorPass()], _reframe(cmds, mirror=m))
    twice = _run([MirrorPass()], _reframe(once, mirror=m))
    single = axes[0] != axes[1]
    for a, b, c in zip(cmds, once, twice, strict=True):
        assert all(abs(u - v) < 1e-9 for u, v in zip(a.end, c.end, strict=True))
        if isinstance(a, Arc):
            assert all(abs(u - v) < 1e-9 for u, v in zip(a.center, c.center, strict=True))
            assert c.turns == a.turns and b.turns == (-a.turns if single else a.turns)
        assert c.frame.comp_side is a.frame.comp_side
        assert b.frame.comp_side is (CompSide.RIGHT if single else CompSide.LEFT)


def _rot(p: tuple[float, ...], c: Pt, deg: float) -> Pt:
    t = math.radians(deg)
    x, y = p[0] - c[0], p[1] - c[1]
    return (c[0] + x * math.cos(t) - y * math.sin(t), c[1] + x * math.sin(t) + y * math.cos(t))


def _scale(p: tuple[float, ...], c: Pt, k: tuple[float, float]) -> Pt:
    return (c[0] + k[0] * (p[0] - c[0]), c[1] + k[1] * (p[1] - c[1]))


@settings(max_examples=40, deadline=None)
@given(contours(), st.floats(-180, 180), st.floats(0.2, 3.0), st.floats(0.2, 3.0), st.floats(-30, 30),
       st.floats(-30, 30))
def test_scaling_and_rotation_compose_as_scale_then_rotate(data: tuple[list[Pt], list[float], float],
                                                          deg: float, kx: float, ky: float, cx: float,
                                                          cy: float) -> None:
    pts, bulges, _ = data
    cmds = _with_approach(_elements(pts, bulges, Frame()))
    lines = [c for c in cmds if not isinstance(c, Arc)]
    framed = _reframe(lines, scaling=Scaling((cx, cy, 0.0), (kx, ky, 1.0)),
                      rotation=Rotation(Plane.XY, (0.0, 0.0), deg))
    out = _run([ScalingPass(), RotationPass()], framed)
    for a, b in zip(lines, out, strict=True):  # the rotation turns the scaled part (Fanuc order)
        want = _rot(_scale(a.end, (cx, cy), (kx, ky)), (0.0, 0.0), deg)
        assert math.dist(b.end[:2], want) < 1e-9
    # with a uniform factor about the rotation centre, the order does not matter
    uniform = _reframe(cmds, scaling=Scaling((cx, cy, 0.0), (kx, kx, 1.0)),
                       rotation=Rotation(Plane.XY, (cx, cy), deg))
    out = _run([ScalingPass(), RotationPass()], uniform)
    for a, b in zip(cmds, out, strict=True):
        other = _scale(_rot(a.end, (cx, cy), deg), (cx, cy), (kx, kx))
        assert math.dist(b.end[:2], other) < 1e-9
        if isinstance(a, Arc):
            assert b.turns == a.turns and math.dist(b.center[:2], _scale(_rot(a.center, (cx, cy), deg),
                                                                        (cx, cy), (kx, kx))) < 1e-9
