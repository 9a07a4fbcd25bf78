"""SZGH user macro cycles G110-G117 and G132-G139 (E002-52 ... E002-59) from the cycle library.

The programs are the manual's examples (shared/spec/szgh-990mdb.md section 4) with D1 = 5 mm
(``-D#1101=5000``: the D1 radius table is in um).  The spec only names the parameters, so
the expected move sequences come from a reference model of the paths that docs/cycles.md
describes, written here from the parameters alone (no code shared with the macros), plus
independent geometric checks on the IR: feed moves stay clear of the finished wall by the
tool radius, the last pass reaches the bottom, steps never exceed K and the swept area
covers the material to remove.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from cncc.ir import Arc, Linear
from tests.helpers import calls, canon, codes, compile_commands

RT = 5.0  # D1
TOOLS = {1101: RT * 1000.0}
Token = tuple[Any, ...]
LIB = Path(__file__).resolve().parents[2] / "cncc" / "dialects" / "szgh_cycles"


def _r(v: float) -> float:
    return round(v, 6) + 0.0


def tokens(text: str, **opts: object) -> tuple[list[Token], list[str]]:
    lines, r = canon(text, "szgh", defines=TOOLS, **opts)
    out: list[Token] = []
    for name, a in calls(lines, "STRAIGHT_TRAVERSE", "STRAIGHT_FEED", "ARC_FEED"):
        if name == "ARC_FEED":
            out.append(("A", a[0], a[1], a[5], a[2], a[3], int(a[4])))
        else:
            out.append(("R" if name == "STRAIGHT_TRAVERSE" else "F", a[0], a[1], a[2]))
    return out, codes(r)


def same(got: list[Token], want: list[Token]) -> bool:
    """Equal move lists, numbers to 1 um (the canon trace prints 4 decimals)."""
    return len(got) == len(want) and all(
        a[0] == b[0] and len(a) == len(b) and all(abs(x - y) <= 1e-3 for x, y in zip(a[1:], b[1:], strict=True))
        for a, b in zip(got, want, strict=True))


def program(block: str, start: str = "X50 Y50 Z50") -> str:
    return f"G90 G00 {start} ;\n{block} ;\nG80 X50 Y50 Z50 ;\nM30 ;\n"


# ---- the reference model ---------------------------------------------------------------------
class Model:
    def __init__(self, x: float, y: float, z: float) -> None:
        self.p = (x, y, z)
        self.out: list[Token] = []

    def rapid(self, x: float, y: float, z: float) -> None:
        if (x, y, z) != self.p:
            self.out.append(("R", _r(x), _r(y), _r(z)))
        self.p = (x, y, z)

    def feed(self, x: float, y: float, z: float) -> None:
        if (x, y, z) != self.p:
            self.out.append(("F", _r(x), _r(y), _r(z)))
        self.p = (x, y, z)

    def arc(self, x: float, y: float, z: float, cx: float, cy: float, turn: int) -> None:
        self.out.append(("A", _r(x), _r(y), _r(z), _r(cx), _r(cy), turn))
        self.p = (x, y, z)

    def rect(self, cx: float, cy: float, hx: float, hy: float, rc: float, side: int, turn: int, z: float) -> None:
        """Rectangle of half widths hx, hy (corner radius rc) from the middle of the side ``side``."""
        p, q = side, side * turn
        corners = [(p, q), (-p, q), (-p, -q), (p, -q)]
        for k, (sx, sy) in enumerate(corners):
            if k % 2 == 0:  # a side along Y, then the corner
                self.feed(cx + sx * hx, cy + sy * (hy - rc), z)
                if rc:
                    self.arc(cx + sx * (hx - rc), cy + sy * hy, z, cx + sx * (hx - rc), cy + sy * (hy - rc), turn)
            else:
                self.feed(cx + sx * (hx - rc), cy + sy * hy, z)
                if rc:
                    self.arc(cx + sx * hx, cy + sy * (hy - rc), z, cx + sx * (hx - rc), cy + sy * (hy - rc), turn)
        self.feed(cx + p * hx, cy, z)


def floors(r: float, z: float, w: float, q: float) -> list[float]:
    out = [max(r - w, z)]
    while out[-1] > z:
        out.append(max(out[-1] - q, z))
    return out


def steps_up_to(step: float, last: float) -> list[float]:
    """step, 2 step, ... below ``last``, then ``last``."""
    out, v = [], step
    while v < last - 5e-4:
        out.append(v)
        v += step
    return [*out, last]


def circle_pocket(cx: float, cy: float, r: float, z: float, i: float, w: float, q: float, k: float,
                  v: float, e: float, turn: int, start: tuple[float, float, float], ret: float) -> list[Token]:
    m = Model(*start)
    rf = i - RT - e
    rh = min(k, rf)
    m.rapid(cx, cy, start[2])
    m.rapid(cx, cy, r)
    fl = floors(r, z, w, q)
    m.feed(cx + rh, cy, r)
    m.arc(cx + rh, cy, fl[0], cx, cy, turn)
    m.feed(cx, cy, fl[0])
    for n, f in enumerate(fl):
        if n:
            m.rapid(m.p[0], cy, r)
            m.rapid(cx, cy, r)
            m.rapid(cx, cy, min(fl[n - 1] + v, r))
            m.feed(cx, cy, f)
        for rad in steps_up_to(k, rf):
            m.feed(cx + rad, cy, f)
            m.arc(cx + rad, cy, f, cx, cy, turn)
    m.rapid(m.p[0], cy, ret)
    m.rapid(cx, cy, ret)
    return m.out


def rect_pocket(cx: float, cy: float, r: float, z: float, i: float, j: float, k: float, w: float, q: float,
                v: float, e: float, turn: int, start: tuple[float, float, float], ret: float) -> list[Token]:
    m = Model(*start)
    ax, ay = i / 2 - RT - e, j / 2 - RT - e
    small = min(ax, ay)
    step = min(k, (1 + math.sqrt(0.5)) * RT)
    rh = min(k, small)
    m.rapid(cx, cy, start[2])
    m.rapid(cx, cy, r)
    fl = floors(r, z, w, q)
    m.feed(cx + rh, cy, r)
    m.arc(cx + rh, cy, fl[0], cx, cy, turn)
    m.feed(cx, cy, fl[0])
    for n, f in enumerate(fl):
        if n:
            m.rapid(m.p[0], cy, r)
            m.rapid(cx, cy, r)
            m.rapid(cx, cy, min(fl[n - 1] + v, r))
            m.feed(cx, cy, f)
        for t in [0.0, *steps_up_to(step, small)]:
            hx, hy = ax - small + t, ay - small + t
            m.feed(cx + hx, cy, f)
            m.rect(cx, cy, hx, hy, 0.0, 1, turn, f)
    m.rapid(m.p[0], cy, ret)
    m.rapid(cx, cy, ret)
    return m.out


def circle_boss(cx: float, cy: float, r: float, z: float, i: float, j: float, w: float, q: float, k: float,
                c: float, e: float, turn: int, start: tuple[float, float, float], ret: float) -> list[Token]:
    m = Model(*start)
    side = -1.0 if c > 0 else 1.0
    sx = cx + side * (j + abs(c))
    rf = i + e + RT
    radii = [j + RT - n * k for n in range(1, 100) if j + RT - n * k > rf + 5e-4] + [rf]
    m.rapid(sx, cy, start[2])
    m.rapid(sx, cy, r)
    for n, f in enumerate(floors(r, z, w, q)):
        if n:
            m.rapid(m.p[0], cy, r)
            m.rapid(sx, cy, r)
        m.rapid(sx, cy, f)
        for rad in radii:
            m.feed(cx + side * rad, cy, f)
            m.arc(cx + side * rad, cy, f, cx, cy, turn)
    m.rapid(m.p[0], cy, ret)
    m.rapid(sx, cy, ret)
    return m.out


def rect_boss(cx: float, cy: float, r: float, z: float, i: float, j: float, a: float, b: float, w: float,
              q: float, k: float, c: float, e: float, turn: int, start: tuple[float, float, float],
              ret: float) -> list[Token]:
    m = Model(*start)
    side = -1 if c > 0 else 1
    sx = cx + side * (a / 2 + abs(c))
    fx, fy = i / 2 + e + RT, j / 2 + e + RT
    step = min(k, (1 + math.sqrt(0.5)) * RT)
    rings: list[tuple[float, float]] = []
    n = 1
    while not rings or rings[-1] != (fx, fy):
        rings.append((max(fx, a / 2 + RT - n * step), max(fy, b / 2 + RT - n * step)))
        n += 1
    m.rapid(sx, cy, start[2])
    m.rapid(sx, cy, r)
    for n, f in enumerate(floors(r, z, w, q)):
        if n:
            m.rapid(m.p[0], cy, r)
            m.rapid(sx, cy, r)
        m.rapid(sx, cy, f)
        for hx, hy in rings:
            m.feed(cx + side * hx, cy, f)
            m.rect(cx, cy, hx, hy, 0.0, side, turn, f)
    m.rapid(m.p[0], cy, ret)
    m.rapid(sx, cy, ret)
    return m.out


def circle_finish(cx: float, cy: float, r: float, z: float, i: float, j: float, turn: int, outer: bool,
                  start: tuple[float, float, float], ret: float) -> list[Token]:
    m = Model(*start)
    rc = i + RT if outer else i - RT
    lead = (j - rc) / 2 if outer else (rc - j) / 2
    m.rapid(cx + j, cy, start[2])
    m.rapid(cx + j, cy, r)
    m.feed(cx + j, cy, z)
    if outer:
        m.arc(cx + rc, cy, z, cx + rc + lead, cy, -turn)
        m.arc(cx - rc, cy, z, cx, cy, turn)
        m.arc(cx + rc, cy, z, cx, cy, turn)
        m.arc(cx + j, cy, z, cx + rc + lead, cy, -turn)
    else:
        m.arc(cx + rc, cy, z, cx + rc - lead, cy, turn)
        m.arc(cx + rc, cy, z, cx, cy, turn)
        m.arc(cx + j, cy, z, cx + rc - lead, cy, turn)
    m.rapid(cx + j, cy, ret)
    return m.out


def rect_finish(cx: float, cy: float, r: float, z: float, i: float, j: float, k: float, u: float, turn: int,
                outer: bool, start: tuple[float, float, float], ret: float) -> list[Token]:
    m = Model(*start)
    sign = 1 if outer else -1
    hx, hy = i / 2 + sign * RT, j / 2 + sign * RT
    rc = u + sign * RT if u else 0.0
    sx = cx + i / 2 + sign * k
    lead = (k - RT) / 2
    m.rapid(sx, cy, start[2])
    m.rapid(sx, cy, r)
    m.feed(sx, cy, z)
    lc = cx + hx + sign * lead
    m.arc(cx + hx, cy, z, lc, cy, -turn if outer else turn)
    m.rect(cx, cy, hx, hy, rc, 1, turn, z)
    m.arc(sx, cy, z, lc, cy, -turn if outer else turn)
    m.rapid(sx, cy, ret)
    return m.out


# ---- geometry of the IR -------------------------------------------------------------------------
def feed_moves(text: str) -> list[Linear | Arc]:
    cmds, r = compile_commands(text, dialect="szgh", defines=TOOLS)
    assert r.ok, [(d.code, d.message) for d in r.sink]
    return [c for c in cmds if isinstance(c, Arc) or (isinstance(c, Linear) and c.feed_mm_min > 0)]


def samples(c: Linear | Arc, step_mm: float = 0.5) -> Iterator[tuple[float, float, float]]:
    """Points along a feed move, at most ``step_mm`` apart."""
    s, e = c.start, c.end
    if isinstance(c, Linear):
        n = max(1, math.ceil(math.dist(s[:3], e[:3]) / step_mm))
        for t in range(n + 1):
            yield tuple(s[i] + (e[i] - s[i]) * t / n for i in range(3))  # type: ignore[misc]
        return
    cx, cy = c.center[0], c.center[1]
    rad = math.hypot(s[0] - cx, s[1] - cy)
    a0 = math.atan2(s[1] - cy, s[0] - cx)
    a1 = math.atan2(e[1] - cy, e[0] - cx)
    sweep = (a1 - a0) % (2 * math.pi) if c.turns > 0 else -((a0 - a1) % (2 * math.pi))
    if abs(sweep) < 1e-9:
        sweep = 2 * math.pi * (1 if c.turns > 0 else -1)
    n = max(4, math.ceil(abs(sweep) * rad / step_mm))
    for t in range(n + 1):
        a = a0 + sweep * t / n
        yield (cx + rad * math.cos(a), cy + rad * math.sin(a), s[2] + (e[2] - s[2]) * t / n)


def path_points(moves: list[Linear | Arc], z: float) -> list[tuple[float, float]]:
    return [(p[0], p[1]) for c in moves for p in samples(c) if abs(p[2] - z) < 1e-6]


def uncovered(points: list[tuple[float, float]], targets: list[tuple[float, float]], reach: float) -> list[tuple[float, float]]:
    return [t for t in targets if min(math.dist(t, p) for p in points) > reach]


def grid(x0: float, x1: float, y0: float, y1: float, step: float = 2.5) -> list[tuple[float, float]]:
    nx, ny = round((x1 - x0) / step), round((y1 - y0) / step)
    return [(x0 + a * step, y0 + b * step) for a in range(nx + 1) for b in range(ny + 1)]


# sampled paths are chords 0.5 mm apart: allow their sagitta and half the spacing
REACH = RT + 0.3


# ---- E002-52 ... E002-59 ---------------------------------------------------------------------------
E52 = "G99 G110 X25 Y25 Z-50 R5 I50 W20 Q10 K10 E0 V10 F800 D1"


def test_e002_52_g110_inner_circle_roughing() -> None:
    t, diags = tokens(program(E52))
    want = circle_pocket(25, 25, 5, -50, 50, 20, 10, 10, 10, 0, 1, (50, 50, 50), ret=5)
    assert same(t[1 : 1 + len(want)], want)
    assert t[1 + len(want):] == [("R", 50.0, 50.0, 50.0)]  # G80 X50 Y50 Z50 at rapid: G00 restored
    assert "E0311" not in diags
    # the spec's figures: radius 50 at (25, 25), 5 to 55 deep, first depth 20, steps 10, D1 = 5
    rings = sorted({tok[1] - 25 for tok in t if tok[0] == "A" and tok[3] == -50.0})
    assert rings == [10.0, 20.0, 30.0, 40.0, 45.0]
    assert floors(5, -50, 20, 10) == [-15, -25, -35, -45, -50]


def test_e002_52_geometry_inside_the_pocket() -> None:
    moves = feed_moves(program(E52))
    for c in moves:
        for x, y, _ in samples(c):
            assert math.hypot(x - 25, y - 25) <= 50 - RT + 1e-6  # the wall offset by the tool radius
    assert min(c.end[2] for c in moves) == -50.0
    rings = sorted({round(math.hypot(c.start[0] - 25, c.start[1] - 25), 6) for c in moves
                    if isinstance(c, Arc) and c.start[2] == c.end[2] == -50.0})
    assert max(b - a for a, b in itertools.pairwise([0.0, *rings])) <= 10.0  # steps <= K
    pts = path_points(moves, -50.0)
    disc = [p for p in grid(-25, 75, -25, 75) if math.hypot(p[0] - 25, p[1] - 25) <= 50 - 1e-6]
    assert not uncovered(pts, disc, REACH)


def test_g111_clockwise_is_the_mirror_turn() -> None:
    t, _ = tokens(program(E52.replace("G110", "G111")))
    want = circle_pocket(25, 25, 5, -50, 50, 20, 10, 10, 10, 0, -1, (50, 50, 50), ret=5)
    assert same(t[1 : 1 + len(want)], want)


def test_e002_53_printed_g24_is_unknown_and_g112_finishes() -> None:
    _, r = canon(program("G99 G24 X25 Y25 Z-50 R5 I50 J10 D1 F800"), "szgh", defines=TOOLS)
    assert "E0201" in codes(r)
    t, _ = tokens(program("G99 G112 X25 Y25 Z-50 R5 I50 J10 D1 F800"))
    want = circle_finish(25, 25, 5, -50, 50, 10, 1, False, (50, 50, 50), ret=5)
    assert same(t[1 : 1 + len(want)], want)
    # start 10 from the centre, lead half circles of radius (45 - 10) / 2
    assert want[:4] == [("R", 35.0, 25.0, 50.0), ("R", 35.0, 25.0, 5.0), ("F", 35.0, 25.0, -50.0),
                        ("A", 70.0, 25.0, -50.0, 52.5, 25.0, 1)]


def test_e002_54_g114_start_inside_the_boss_is_an_alarm() -> None:
    """J30 < I50 + 5 puts the start point inside the boss: the program alarms, nothing is cut."""
    t, diags = tokens(program("G99 G114 X25 Y25 Z-50 R5 I50 J30 D1 F800"))
    assert "E0311" in diags
    assert [tok for tok in t if tok[0] != "R"] == []
    t, _ = tokens(program("G99 G114 X25 Y25 Z-50 R5 I50 J70 D1 F800"))
    want = circle_finish(25, 25, 5, -50, 50, 70, 1, True, (50, 50, 50), ret=5)
    assert same(t[1 : 1 + len(want)], want)
    lead_in, lead_out = want[3], want[-2]
    assert lead_in[-1] == lead_out[-1] == -1  # the lead arcs turn against the finishing direction


E55 = "G99 G117 X50 Y50 Z-50 R5 I20 J50 W20 Q10 K10 C20 E2 D1 F800"


def test_e002_55_g117_outer_circle_roughing() -> None:
    t, _ = tokens(program(E55, "X0 Y0 Z50"))
    want = circle_boss(50, 50, 5, -50, 20, 50, 20, 10, 10, 20, 2, -1, (0, 0, 50), ret=5)
    assert same(t[1 : 1 + len(want)], want)
    rings = sorted({50 - tok[1] for tok in t if tok[0] == "A" and tok[3] == -50.0})
    assert rings == [27.0, 35.0, 45.0]  # boss 20 + allowance 2 + tool 5; raw 50 + 5 - 10k


def test_e002_55_geometry_clear_of_the_boss() -> None:
    moves = feed_moves(program(E55, "X0 Y0 Z50"))
    for c in moves:
        for x, y, _ in samples(c):
            assert math.hypot(x - 50, y - 50) >= 20 + 2 + RT - 1e-6
    assert min(c.end[2] for c in moves) == -50.0
    pts = path_points(moves, -50.0)
    ring = [p for p in grid(0, 100, 0, 100) if 22 + 1e-6 <= math.hypot(p[0] - 50, p[1] - 50) <= 50]
    assert not uncovered(pts, ring, REACH)


E56 = "G99 G133 X50 Y50 Z-50 R5 I50 J40 A100 B80 W20 Q10 K10 C20 E2 D1 F800"


def _outside_pad(x: float, y: float, hx: float, hy: float) -> float:
    dx, dy = max(abs(x) - hx, 0.0), max(abs(y) - hy, 0.0)
    return math.hypot(dx, dy)


def test_e002_56_g133_outer_rectangle_roughing() -> None:
    t, _ = tokens(program(E56, "X0 Y0 Z50"))
    want = rect_boss(50, 50, 5, -50, 50, 40, 100, 80, 20, 10, 10, 20, 2, -1, (0, 0, 50), ret=5)
    assert same(t[1 : 1 + len(want)], want)
    last = [tok for tok in t if tok[0] == "F" and tok[3] == -50.0][-5:]
    assert {(tok[1], tok[2]) for tok in last} >= {(18.0, 77.0), (82.0, 23.0)}  # pad 54 x 44 plus the tool


def test_e002_56_geometry_clear_of_the_pad_and_corners_milled() -> None:
    moves = feed_moves(program(E56, "X0 Y0 Z50"))
    for c in moves:
        for x, y, _ in samples(c):
            assert _outside_pad(x - 50, y - 50, 27, 22) >= RT - 1e-6
    xs = sorted({round(abs(c.start[0] - 50), 6) for c in moves if isinstance(c, Linear)
                 and c.start[0] != c.end[0] and c.start[1] == c.end[1] == 50 and c.start[2] == -50
                 and abs(c.start[0] - 50) <= 55 + 1e-6})
    assert max(b - a for a, b in itertools.pairwise(xs)) <= 10.0
    pts = path_points(moves, -50.0)
    raw = [p for p in grid(0, 100, 10, 90) if _outside_pad(p[0] - 50, p[1] - 50, 27, 22) > 1e-6]
    assert not uncovered(pts, raw, REACH)  # including the raw stock's corners


E57 = "G99 G134 X25 Y25 Z-50 R5 I70 J50 W20 Q10 K5 E0 V10 F800 D1"


def test_e002_57_g134_inner_rectangle_roughing() -> None:
    t, _ = tokens(program(E57))
    want = rect_pocket(25, 25, 5, -50, 70, 50, 5, 20, 10, 10, 0, 1, (50, 50, 50), ret=5)
    assert same(t[1 : 1 + len(want)], want)
    widths = sorted({tok[1] - 25 for tok in t if tok[0] == "F" and tok[2] == 25.0 and tok[3] == -50.0
                     and tok[1] > 25})
    assert widths == [10.0, 15.0, 20.0, 25.0, 30.0]  # slot half length 35 - 5 - 20, then steps of K5


def test_e002_57_geometry_inside_the_pocket() -> None:
    moves = feed_moves(program(E57))
    for c in moves:
        for x, y, _ in samples(c):
            assert abs(x - 25) <= 35 - RT + 1e-6 and abs(y - 25) <= 25 - RT + 1e-6
    assert min(c.end[2] for c in moves) == -50.0
    pts = path_points(moves, -50.0)
    assert not uncovered(pts, grid(-10 + RT, 60 - RT, 0 + RT, 50 - RT), REACH)


def _rounded_box_distance(x: float, y: float, hx: float, hy: float, u: float) -> float:
    qx, qy = abs(x) - (hx - u), abs(y) - (hy - u)
    return math.hypot(max(qx, 0.0), max(qy, 0.0)) + min(max(qx, qy), 0.0) - u


def test_e002_58_printed_g24_is_unknown_and_g136_finishes() -> None:
    _, r = canon(program("G99 G24 X10 Y10 Z-50 R5 I80 J50 K30 U10 D1 F800"), "szgh", defines=TOOLS)
    assert "E0201" in codes(r)
    block = "G99 G136 X10 Y10 Z-50 R5 I80 J50 K30 U10 D1 F800"
    t, _ = tokens(program(block))
    want = rect_finish(10, 10, 5, -50, 80, 50, 30, 10, 1, False, (50, 50, 50), ret=5)
    assert same(t[1 : 1 + len(want)], want)
    assert want[2] == ("F", 20.0, 10.0, -50.0)  # the start point, 30 inside the +X side
    loop = feed_moves(program(block))[2:-1]  # without the plunge and the lead arcs
    for c in loop:
        for x, y, _ in samples(c):
            assert _rounded_box_distance(x - 10, y - 10, 40, 25, 10) == pytest.approx(-RT, abs=1e-6)


def test_e002_59_g138_outer_rectangle_finishing() -> None:
    block = "G99 G138 X25 Y25 Z-50 R5 I80 J50 K30 U5 D1 F800"
    t, _ = tokens(program(block))
    want = rect_finish(25, 25, 5, -50, 80, 50, 30, 5, 1, True, (50, 50, 50), ret=5)
    assert same(t[1 : 1 + len(want)], want)
    assert want[3] == ("A", 70.0, 25.0, -50.0, 82.5, 25.0, -1)  # lead-in turns against the loop
    loop = feed_moves(program(block))[2:-1]
    for c in loop:
        for x, y, _ in samples(c):
            assert _rounded_box_distance(x - 25, y - 25, 40, 25, 5) == pytest.approx(RT, abs=1e-6)


# ---- modes, bad input, the library files ------------------------------------------------------------
def test_g98_returns_to_the_initial_level_and_g91_is_incremental() -> None:
    t, _ = tokens("G90 G00 X50 Y50 Z50\nG91 G98 G112 X-25 Y-25 Z-55 R-45 I50 J10 D1 F800\nG90\nM30\n")
    want = circle_finish(25, 25, 5, -50, 50, 10, 1, False, (50, 50, 50), ret=50)
    assert same(t[1:], want)


def test_missing_r_is_an_alarm_at_the_call() -> None:
    _, r = canon(program("G99 G110 X25 Y25 Z-50 I50 W20 Q10 K10 F800 D1"), "szgh", defines=TOOLS)
    alarms = [d for d in r.sink if d.code == "E0311"]
    assert alarms and "R" in alarms[0].message
    assert any("G110" in rel.message or "ProgramG110" in rel.message for rel in alarms[0].related)


@pytest.mark.parametrize("block", [
    "G99 G110 X25 Y25 Z-50 R5 I4 W20 Q10 K10 F800 D1",        # pocket smaller than the tool
    "G99 G110 X25 Y25 Z-50 R5 I50 W20 K10 F800 D1",           # no Q to reach the bottom
    "G99 G116 X25 Y25 Z-50 R5 I20 J50 W20 Q10 K10 C3 F800 D1",  # C below tool radius + 2
    "G99 G136 X10 Y10 Z-50 R5 I80 J8 K30 U10 D1 F800",        # J below the tool diameter
    "G99 G136 X10 Y10 Z-50 R5 I80 J50 K30 U3 D1 F800",        # corner radius below the tool radius
])
def test_bad_cycle_words_alarm(block: str) -> None:
    t, diags = tokens(program(block))
    assert "E0311" in diags
    assert [tok for tok in t if tok[0] != "R"] == []


@pytest.mark.parametrize(("ccw", "cw"), [(110, 111), (112, 113), (114, 115), (116, 117), (132, 133),
                                         (134, 135), (136, 137), (138, 139)])
def test_clockwise_programs_differ_only_in_the_direction(ccw: int, cw: int) -> None:
    a = (LIB / f"ProgramG{ccw}.nc").read_text().splitlines()
    b = (LIB / f"ProgramG{cw}.nc").read_text().splitlines()
    assert (a[0], b[0]) == ("#700=1", "#700=-1")
    differ = [(x, y) for x, y in zip(a[1:], b[1:], strict=True) if x != y]
    assert all(f"G{ccw}" in x or f"ProgramG{cw}" in x for x, _ in differ)  # header comments only


def test_user_p501_runs_a_program_for_g81(tmp_path: Path) -> None:
    (tmp_path / "ProgramG101.nc").write_text("G01 X#18 Y#19 Z#20 F#5\nG00 Z#12\nM99\n")
    text = "G90 G00 X0 Y0 Z10\nG99 G81 X5 Y6 Z-3 R2 F100\nX7\nG80\nM30\n"
    t, _ = tokens(text, dialect_options={"cycle_user_g81": 101}, include_dirs=[str(tmp_path)])
    assert t == [("R", 0.0, 0.0, 10.0), ("F", 5.0, 6.0, -3.0), ("R", 5.0, 6.0, 2.0), ("R", 7.0, 6.0, 2.0)]
    t, _ = tokens(text)
    assert ("F", 7.0, 6.0, -3.0) in t  # the built-in G81 is modal and drills at X7 too
    _, diags = tokens(text, dialect_options={"cycle_user_g81": 99})
    assert "E0904" in diags


@pytest.mark.parametrize(("p8", "lift"), [(200, "R"), (-200, "F"), (5, "R")])
def test_user_p8_pause_before_each_peck_lift(p8: int, lift: str) -> None:
    text = "G90 G00 X5 Y6 Z10\nG99 G83 Z-13 R2 Q8 F100\nG80\nM30\n"
    lines, r = canon(text, "szgh", dialect_options={"cycle_peck_pause_ms": p8})
    assert r.ok
    seq = [(n, a[0] if n == "DWELL" else a[2]) for n, a in calls(lines, "DWELL", "STRAIGHT_FEED",
                                                                  "STRAIGHT_TRAVERSE")][1:]
    kind = {"R": "STRAIGHT_TRAVERSE", "F": "STRAIGHT_FEED"}[lift]
    pause = [("DWELL", 0.2)] if abs(p8) > 5 else []
    # pecks of Q8 from R2: -6 then the bottom -13; G83 goes back to R, then down to d = 5 above -6
    assert seq == [("STRAIGHT_TRAVERSE", 2.0), ("STRAIGHT_FEED", -6.0), *pause, (kind, 2.0),
                   ("STRAIGHT_TRAVERSE", -1.0), ("STRAIGHT_FEED", -13.0), ("STRAIGHT_TRAVERSE", 2.0)]
