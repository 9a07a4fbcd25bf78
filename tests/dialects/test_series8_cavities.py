"""SERIES 8 G34-G36 milled cavities, G49/G50 rectangular patterns and the A-16 corner rule.

The manual has titles only and the spec gives shapes, not numbers (spec 4.6, 4.7), so
these tests check the geometry independently of cncc's path builder: every cutting
move stays inside the cavity less the tool radius, the last pass reaches the bottom,
every point the tool can reach at the bottom is within one tool radius of the path
(so the step-over is small enough to leave nothing), the wall pass turns the way the
code says, and the pattern holes are at the corners and pitches the words give, in
the programmed turning sense.  The A-16 test checks the offset corner against r tan
of half the turn, worked out here.
"""

from __future__ import annotations

import itertools
import math
from pathlib import Path

import pytest

from tests.helpers import calls, canon, codes

S8 = "series8"
R_TOOL = 0.25  # inch
Seg = tuple[tuple[float, float], tuple[float, float], tuple[float, float] | None, int]  # start, end, centre, turn


@pytest.fixture
def tools(tmp_path: Path) -> str:
    path = tmp_path / "tools.toml"
    path.write_text(f'units = "inch"\n[tools.1]\nradius = {R_TOOL}\n[tools.2]\nradius = 0.75\n', encoding="utf-8")
    return str(path)


def _path(text: str, tools: str, **options: object) -> tuple[list[tuple[str, list[float]]], list[str]]:
    lines, r = canon(text, S8, tools_file=tools, dialect_options=options)
    return calls(lines, "STRAIGHT_TRAVERSE", "STRAIGHT_FEED", "ARC_FEED"), codes(r)


def _cuts(moves: list[tuple[str, list[float]]], start: tuple[float, float, float]) -> list[tuple[Seg, float]]:
    """(segment in the plane, z) of every feed move, with where it starts."""
    out: list[tuple[Seg, float]] = []
    at = start
    for name, a in moves:
        end = (a[0], a[1], a[5] if name == "ARC_FEED" else a[2])
        if name == "STRAIGHT_FEED":
            out.append((((at[0], at[1]), (end[0], end[1]), None, 0), end[2]))
        elif name == "ARC_FEED":
            out.append((((at[0], at[1]), (end[0], end[1]), (a[2], a[3]), int(a[4])), end[2]))
        at = end
    return out


def _distance(p: tuple[float, float], seg: Seg) -> float:
    (x0, y0), (x1, y1), centre, turn = seg
    if centre is None:
        dx, dy = x1 - x0, y1 - y0
        n2 = dx * dx + dy * dy
        t = 0.0 if n2 == 0 else max(0.0, min(1.0, ((p[0] - x0) * dx + (p[1] - y0) * dy) / n2))
        return math.hypot(p[0] - x0 - t * dx, p[1] - y0 - t * dy)
    cx, cy = centre
    radius = math.hypot(x0 - cx, y0 - cy)
    a0, a1, ap = (math.atan2(y - cy, x - cx) for x, y in ((x0, y0), (x1, y1), p))
    sweep = (a1 - a0) % (2 * math.pi) if turn > 0 else (a0 - a1) % (2 * math.pi)
    sweep = sweep or 2 * math.pi
    into = (ap - a0) % (2 * math.pi) if turn > 0 else (a0 - ap) % (2 * math.pi)
    if into <= sweep:
        return abs(math.hypot(p[0] - cx, p[1] - cy) - radius)
    return min(math.hypot(p[0] - x0, p[1] - y0), math.hypot(p[0] - x1, p[1] - y1))


def _arc_extent(seg: Seg) -> float:
    """The largest distance from the cavity centre of an arc about it (the radius)."""
    (x0, y0), _, centre, _ = seg
    assert centre is not None
    return math.hypot(x0 - centre[0], y0 - centre[1])


RECT = "G00X0Y0Z1.\nF10\n{code} X2. Y1. I3. J2. Z-.5 R.1 K.3 L.4 D1\n"  # centre (2, 1), 3 x 2, tool radius .25


@pytest.mark.parametrize("clearing", ["concentric", "zigzag"])
@pytest.mark.parametrize("code", ["G34", "G35"])
def test_rectangular_cavity_stays_inside_clears_and_reaches_depth(tools: str, code: str, clearing: str) -> None:
    moves, found = _path(RECT.format(code=code), tools, cavity_clearing=clearing)
    assert found == ["W0256"]  # cncc's reading of words the manual does not give
    cuts = _cuts(moves, (0.0, 0.0, 1.0))
    a, b = 1.5 - R_TOOL, 1.0 - R_TOOL  # half sizes the tool centre may reach
    for (p0, p1, _, _), z in cuts:
        assert z >= -0.5 - 1e-9
        if z < 0.1 - 1e-9:  # below R: cutting
            for x, y in (p0, p1):
                assert abs(x - 2.0) <= a + 1e-6 and abs(y - 1.0) <= b + 1e-6
    levels = sorted({round(z, 6) for _, z in cuts}, reverse=True)
    assert levels == [-0.2, -0.5]  # 0.6 in below R in passes of at most K .3: two equal passes
    bottom = [seg for seg, z in cuts if abs(z + 0.5) < 1e-9]
    # every point the tool can reach (within r of the centre's rectangle) is within r of the path
    for i in range(41):
        for j in range(41):
            p = (2.0 - 1.5 + 3.0 * i / 40, 1.0 - 1.0 + 2.0 * j / 40)
            outside = math.hypot(max(abs(p[0] - 2.0) - a, 0.0), max(abs(p[1] - 1.0) - b, 0.0))
            if outside <= R_TOOL:
                assert min(_distance(p, s) for s in bottom) <= R_TOOL + 1e-6, p
    assert moves[-1] == ("STRAIGHT_TRAVERSE", [2.0, 1.0, 0.1, 0.0, 0.0, 0.0])  # ends above the centre at R


@pytest.mark.parametrize(("code", "sign"), [("G34", 1.0), ("G35", -1.0)])
def test_wall_pass_turns_the_programmed_way(tools: str, code: str, sign: float) -> None:
    moves, _ = _path(RECT.format(code=code), tools)
    pts = [(a[0], a[1]) for name, a in moves if name == "STRAIGHT_FEED" and abs(a[2] + 0.5) < 1e-9]
    wall = [p for p in pts if abs(abs(p[0] - 2.0) - 1.25) < 1e-6 and abs(abs(p[1] - 1.0) - 0.75) < 1e-6][-4:]
    area = sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(wall, wall[1:] + wall[:1], strict=True)) / 2
    assert area == pytest.approx(sign * 2.5 * 1.5)  # the four corners of the wall ring, CCW for G34


def test_step_over_defaults_to_half_the_diameter_and_the_corner_reference(tools: str) -> None:
    moves, _ = _path("G00X0Y0Z1.\nF10\nG34 X.5 Y0 I3. J2. Z-.5 R.1 D1\n", tools, cavity_reference="corner")
    cuts = _cuts(moves, (0.0, 0.0, 1.0))
    assert {round(z, 6) for _, z in cuts if z < 0.1} == {-0.5}  # no K: the whole depth at once
    xs = [p[0] for (p0, p1, _, _), z in cuts if z < 0.1 for p in (p0, p1)]
    ys = [p[1] for (p0, p1, _, _), z in cuts if z < 0.1 for p in (p0, p1)]
    assert (min(xs), max(xs), min(ys), max(ys)) == pytest.approx((0.75, 3.25, 0.25, 1.75))  # corner (.5, 0)
    # rings from the slot out: the steps between them (outwards, right of the slot) are at most half
    # the diameter, and the wall is reached
    steps = [p1[0] - p0[0] for (p0, p1, _, _), z in cuts if z < 0.1 and p0[1] == p1[1] == 1.0
             and p1[0] > p0[0] > 2.0]
    assert len(steps) == 3 and max(steps) <= R_TOOL + 1e-9 and 2.5 + sum(steps) == pytest.approx(3.25)


@pytest.mark.parametrize("clearing", ["concentric", "zigzag"])
def test_circular_cavity_stays_inside_and_clears(tools: str, clearing: str) -> None:
    moves, found = _path("G00X0Y0Z1.\nF10\nG36 X2. Y1. I2. Z-.4 R.1 L.3 D1\n", tools, cavity_clearing=clearing)
    assert found == ["W0256"]
    rho = 1.0 - R_TOOL
    cuts = _cuts(moves, (0.0, 0.0, 1.0))
    bottom = [seg for seg, z in cuts if abs(z + 0.4) < 1e-9]
    for seg in bottom:
        for x, y in (seg[0], seg[1]):
            assert math.hypot(x - 2.0, y - 1.0) <= rho + 1e-6
        if seg[2] is not None:
            assert seg[2] == pytest.approx((2.0, 1.0)) and _arc_extent(seg) <= rho + 1e-6
            assert seg[3] == 1  # counter-clockwise by default
    assert max(_arc_extent(s) for s in bottom if s[2] is not None) == pytest.approx(rho)  # the wall pass
    for i in range(41):
        for j in range(41):
            p = (1.0 + 2.0 * i / 40, 2.0 * j / 40)
            if math.hypot(p[0] - 2.0, p[1] - 1.0) <= 1.0:
                assert min(_distance(p, s) for s in bottom) <= R_TOOL + 1e-6, p


def test_circular_cavity_radius_word_and_direction_options(tools: str) -> None:
    moves, _ = _path("G00X0Y0Z1.\nF10\nG36 X0 Y0 I1. Z-.4 R.1 D1\n", tools, cavity_circle_size="radius",
                     g36_direction="cw")
    arcs = [a for name, a in moves if name == "ARC_FEED"]
    assert {int(a[4]) for a in arcs} == {-1}
    assert max(math.hypot(a[0], a[1]) for a in arcs) == pytest.approx(1.0 - R_TOOL)  # I1. is the radius


def test_cavity_follows_the_rotation(tools: str) -> None:
    moves, _ = _path("G00X0Y0Z1.\nF10\nG55R90\nG34 X0 Y0 I3. J2. Z-.5 R.1 D1\n", tools)
    pts = [(a[0], a[1]) for name, a in moves if name == "STRAIGHT_FEED"]
    xs, ys = [p[0] for p in pts], [p[1] for p in pts]
    assert (max(xs) - min(xs), max(ys) - min(ys)) == pytest.approx((1.5, 2.5))  # the 3 x 2 cavity turned 90 deg


@pytest.mark.parametrize(("block", "why"), [
    ("G34 X0 Y0 I.4 J2. Z-.5 R.1 D1", "larger"),  # .4 wide, tool .5 across
    ("G34 X0 Y0 I3. J2. Z-.5 R.1 L.6 D1", "step-over"),  # more than the .5 diameter
    ("G34 X0 Y0 I3. J2. Z-.5 R.1 D3", "tool radius"),  # no row 3 in the table
    ("G34 X0 Y0 J2. Z-.5 R.1 D1", "size"),
    ("G36 X0 Y0 I1. Z-.5 R.1 K0 D1", "depth per pass"),
])
def test_cavities_that_cannot_be_milled(tools: str, block: str, why: str) -> None:
    lines, r = canon("G00X0Y0Z1.\nF10\n" + block + "\n", S8, tools_file=tools)
    errors = [d for d in r.sink if d.code == "E0258"]
    assert len(errors) == 1 and why in errors[0].message
    assert not calls(lines, "STRAIGHT_FEED", "ARC_FEED")


def test_cavity_needs_levels(tools: str) -> None:
    _, r = canon("G00X0Y0Z1.\nF10\nG34 X0 Y0 I3. J2. Z-.5 D1\n", S8, tools_file=tools)
    assert codes(r) == ["W0256", "E0401"]


# ---- G49 / G50 ---------------------------------------------------------------------------------
PATTERN = "G00X0Y0Z1.\nG81 X0 Y0 Z-.5 R.1 F10\n{block}\n"


def _holes(text: str, **options: object) -> list[tuple[float, float]]:
    """Where the tool feeds down to the bottom, in order (the first is the G81 block's own hole)."""
    lines, r = canon(text, S8, dialect_options=options)
    assert r.ok, [(d.code, d.message) for d in r.sink]
    return [(round(a[0], 6), round(a[1], 6)) for _, a in calls(lines, "STRAIGHT_FEED") if abs(a[2] + 0.5) < 1e-9]


def _signed_area(pts: list[tuple[float, float]]) -> float:
    return sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(pts, pts[1:] + pts[:1], strict=True)) / 2


@pytest.mark.parametrize(("block", "sign"), [
    ("G49 X1. Y1. I1. J.5 P3 K2", 1.0), ("G50 X1. Y1. I1. J.5 P3 K2", -1.0),
    ("G49 X1. Y1. I-1. J.5 P3 K2", 1.0), ("G50 X1. Y1. I1. J-.5 P3 K2", -1.0)])
def test_rectangular_pattern_holes_on_the_edge_in_the_programmed_sense(block: str, sign: float) -> None:
    holes = _holes(PATTERN.format(block=block))[1:]
    i, j = (-1.0 if "I-" in block else 1.0), (-0.5 if "J-" in block else 0.5)
    expected = {(round(1 + a * i, 6), round(1 + b * j, 6)) for a in range(3) for b in range(2)}
    assert holes[0] == (1.0, 1.0) and len(holes) == 6 and set(holes) == expected  # 2 (3 + 2) - 4 on the edge
    steps = [math.hypot(x1 - x0, y1 - y0) for (x0, y0), (x1, y1) in itertools.pairwise(holes)]
    assert max(steps) == pytest.approx(1.0)  # neighbours along the edge, never across
    assert math.copysign(1.0, _signed_area(holes)) == sign and abs(_signed_area(holes)) == pytest.approx(1.0)


def test_rectangular_pattern_drills_each_hole_with_the_cycle() -> None:
    lines, _ = canon(PATTERN.format(block="G49 X1. Y1. I1. J.5 P2 K2"), S8)
    got = [(name[9:], tuple(round(v, 6) for v in a[:3])) for name, a in
           calls(lines, "STRAIGHT_TRAVERSE", "STRAIGHT_FEED")][4:]  # after the G81 block's own hole
    expected = []
    for x, y in ((1.0, 1.0), (2.0, 1.0), (2.0, 1.5), (1.0, 1.5)):  # CCW: along I first (I, J > 0)
        expected += [("TRAVERSE", (x, y, 0.1)), ("FEED", (x, y, -0.5)), ("TRAVERSE", (x, y, 0.1))]
    assert got == expected  # over at R, feed to Z, rapid back to R (SERIES 8 cycles end at R)


def test_rectangular_pattern_grid_and_interior_holes() -> None:
    holes = _holes(PATTERN.format(block="G50 X0 Y0 I1. J1. P4 K3"), rect_pattern_layout="grid")[1:]
    assert len(holes) == 12 and len(set(holes)) == 12
    assert holes[-2:] == [(1.0, 1.0), (2.0, 1.0)]  # the inner ring last, from its own first corner
    edge = _holes(PATTERN.format(block="G50 X0 Y0 I1. J1. P4 K3"))[1:]
    assert edge == holes[:10]


def test_rectangular_pattern_needs_a_cycle_and_counts() -> None:
    for text, code in (("G00X0Y0Z1.\nG49 X1. Y1. I1. J1. P2 K2\n", "E0408"),
                       (PATTERN.format(block="G49 X1. Y1. I1. J1. P2"), "E0409"),
                       (PATTERN.format(block="G49 X1. Y1. I1. P2 K2"), "E0409"),
                       (PATTERN.format(block="G49 X1. Y1. I1. J1. P2.5 K2"), "E0409"),
                       ("G00X0Y0Z4.\nG87 X5. Y6. R3.5 Z3.0 F20.\nG49 X1. Y1. I1. J1. P2 K2\n", "E0409")):
        _, r = canon(text, S8)
        assert [c for c in codes(r) if c != "W0256"] == [code], text


def test_rectangular_pattern_frame_reading() -> None:
    lines, r = canon("G00X0Y0Z-.1\nF10\nG50 X1. Y1. I2. J1.\n", S8, dialect_options={"rect_pattern_reading": "frame"})
    assert codes(r) == ["W0256"]
    feeds = [(a[0], a[1], a[2]) for _, a in calls(lines, "STRAIGHT_FEED")]
    assert feeds == [(1.0, 1.0, -0.1), (1.0, 2.0, -0.1), (3.0, 2.0, -0.1), (3.0, 1.0, -0.1), (1.0, 1.0, -0.1)]


# ---- outside corners below 70 degrees get an arc ---------------------------------------------
def _comp(turn_deg: float, tools: str, **options: object) -> list[tuple[str, list[float]]]:
    x2 = 2.0 + math.cos(math.radians(-turn_deg))
    y2 = math.sin(math.radians(-turn_deg))
    prog = f"F10\nG00X0Y0\nG41 D1\nG01 X2.\nX{x2:.6f} Y{y2:.6f}\nG40\nX0 Y-2.\n"
    lines, r = canon(prog, S8, tools_file=tools, dialect_options=options)
    assert not [d for d in r.sink if d.severity.name == "ERROR"]
    return calls(lines, "STRAIGHT_FEED", "ARC_FEED")


def test_a16_sharp_outside_corner_gets_an_arc(tools: str) -> None:
    got = _comp(120.0, tools)  # a right turn of 120 degrees with G41: outside, 60 degrees included
    arc = next(a for name, a in got if name == "ARC_FEED")
    assert arc[2:4] == pytest.approx([2.0, 0.0]) and arc[4] == -1  # about the programmed corner, radius r
    assert got[1][1][:2] == pytest.approx([2.0, R_TOOL])


def test_a16_blunter_outside_corner_uses_the_intersection(tools: str) -> None:
    got = _comp(100.0, tools)  # 80 degrees included: no arc, the offset lines meet
    assert not [a for name, a in got if name == "ARC_FEED"]
    assert got[1][1][:2] == pytest.approx([2.0 + R_TOOL * math.tan(math.radians(50.0)), R_TOOL], abs=1e-4)
    old = _comp(100.0, tools, comp_outer_arc_below_deg=0.0)  # the shared rule: extensions past a 90 degree turn
    assert [v for _, a in old[1:3] for v in a[:2]] == pytest.approx([2.0, R_TOOL, 2.0 + R_TOOL, R_TOOL], abs=1e-4)


def test_huge_cavities_and_grids_are_refused_before_they_are_built(tools: str) -> None:
    _, r = canon("G00X0Y0Z1.\nF10\nG36 I10000. Z-1. R.1 D1 L.0001\nG34 I1. J1. Z-100. R.1 D1 K.00001\n", S8,
                 tools_file=tools)
    assert [c for c in codes(r) if c != "W0256"] == ["E0258", "E0258"]
    _, r = canon(PATTERN.format(block="G50 X0 Y0 I1. J1. P9999 K9999"), S8,
                 dialect_options={"rect_pattern_layout": "grid"})
    assert [c for c in codes(r) if c != "W0256"] == ["E0409"]
