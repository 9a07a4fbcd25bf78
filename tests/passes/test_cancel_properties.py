"""Property tests (issue 17): after a transform cancel the uncommanded axes stay put, and
every canned-cycle hole is reached by a rapid to its transformed position.

Programs are generated per dialect from its own transform codes (SYNTEC and Fanuc
G51/G50, G51.1/G50.1, G68/G69; SZGH G36/G37, G11/G12, G68/G69; SERIES 8 G57/G58,
G55/G56).  The expectations are computed here from the manuals' rules:

(a) SYNTEC §1.2.23 and the scaling section, SZGH §3.22/§3.23: after the cancel the machine
    stays where it is; a block moves only the axes it names (an absolute word goes to its
    untransformed target, an incremental word moves by its increment from the tool);
(b) a hole is drilled at the image of its programmed X/Y under the transforms in force
    (scaling, then rotation, the whole mirrored: docs/frames.md), reached by a rapid
    in the plane at the current height, with R as its own rapid (no diagonal move, and no
    feed that moves in the plane).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from cncc.ir import Linear, Rapid
from tests.helpers import compile_commands

EPS = 1e-6
DIALECTS = ["syntec", "fanuc", "szgh", "series8"]

coord = st.integers(-80_000, 80_000).map(lambda v: v / 1000)
small = st.integers(-20_000, 20_000).map(lambda v: v / 1000)


@dataclass(frozen=True)
class Xf:
    """One transform as the test understands it: on-code text, off-code text, and the map."""

    kind: str  # "scale", "mirror", "rotate"
    on: str
    off: str
    center: tuple[float, float]
    value: float  # factor, mirrored-axes mask (1 = X, 2 = Y, 3 = both) or angle in degrees

    def apply(self, p: tuple[float, float]) -> tuple[float, float]:
        cx, cy = self.center
        x, y = p
        if self.kind == "scale":
            return cx + self.value * (x - cx), cy + self.value * (y - cy)
        if self.kind == "mirror":
            m = int(self.value)
            return (2 * cx - x if m & 1 else x), (2 * cy - y if m & 2 else y)
        a = math.radians(self.value)
        dx, dy = x - cx, y - cy
        return cx + dx * math.cos(a) - dy * math.sin(a), cy + dx * math.sin(a) + dy * math.cos(a)


# The image of a point: scaled, then rotated, then mirrored as a whole (docs/frames.md: with a mirror
# and a rotation in force the rotation turns the other way, which is the mirror of the rotated part).
ORDER = {"scale": 0, "rotate": 1, "mirror": 2}


@st.composite
def transform(draw: st.DrawFn, dialect: str, kind: str) -> Xf:
    cx, cy = draw(small), draw(small)
    if kind == "scale":
        k = draw(st.sampled_from([0.5, 2.0, 1.5, 0.25]))
        if dialect == "series8":  # about program zero, plane axes (spec §4.10)
            return Xf(kind, f"G57 R{k}", "G58", (0.0, 0.0), k)
        if dialect == "szgh":  # G36 scales the named axes by R (read as a factor here)
            return Xf(kind, f"G36 X{cx:.3f} Y{cy:.3f} R{k}", "G37", (cx, cy), k)
        return Xf(kind, f"G51 X{cx:.3f} Y{cy:.3f} I{k} J{k}", "G50", (cx, cy), k)
    if kind == "mirror":
        m = draw(st.sampled_from([1, 2, 3]))
        words = (f"X{cx:.3f}" if m & 1 else "") + (f" Y{cy:.3f}" if m & 2 else "")
        on, off = ("G11", "G12") if dialect == "szgh" else ("G51.1", "G50.1")
        return Xf(kind, f"{on} {words.strip()}", off, (cx, cy), m)
    a = draw(st.sampled_from([30.0, 45.0, 90.0, -60.0, 120.0]))
    if dialect == "series8":  # about program zero (spec §4.9)
        return Xf(kind, f"G55 R{a}", "G56", (0.0, 0.0), a)
    return Xf(kind, f"G68 X{cx:.3f} Y{cy:.3f} R{a}", "G69", (cx, cy), a)


def kinds_of(dialect: str) -> list[str]:
    return ["scale", "rotate"] if dialect == "series8" else ["scale", "mirror", "rotate"]


def end(dialect: str) -> str:
    return "" if dialect == "series8" else " ;"


def units(dialect: str) -> str:
    return "G71 " if dialect in ("series8", "syntec") else "G21 "  # millimetres (SERIES 8 powers up in inch)


def options(dialect: str) -> dict[str, object]:
    return {"dialect_options": {"scale_r_semantics": "multiply"}} if dialect == "szgh" else {}


def moves_by_line(text: str, dialect: str) -> tuple[list[tuple[int, Rapid | Linear]], list[str]]:
    cmds, r = compile_commands(text, dialect=dialect, **options(dialect))
    out = []
    for c in cmds:
        if isinstance(c, Rapid | Linear):
            out.append((text.count("\n", 0, c.span.start) + 1, c))
    return out, [d.code for d in r.sink if d.code.startswith("E")]


def axis_block(draw: st.DrawFn, dialect: str) -> tuple[str, dict[int, float], bool]:
    named = draw(st.lists(st.sampled_from([0, 1, 2]), min_size=1, max_size=3, unique=True))
    inc = draw(st.booleans())
    vals = {k: draw(small) for k in named}
    g = draw(st.sampled_from(["G00", "G01"]))
    words = " ".join(f"{'XYZ'[k]}{v:.3f}" for k, v in sorted(vals.items()))
    feed = " F500." if g == "G01" else ""
    return f"{'G91' if inc else 'G90'} {g} {words}{feed}{end(dialect)}", vals, inc


# ---- (a) after any cancel, a block naming a subset of axes moves only those ------------------------
@st.composite
def cancel_programs(draw: st.DrawFn) -> tuple[str, str, int, list[tuple[dict[int, float], bool]]]:
    dialect = draw(st.sampled_from(DIALECTS))
    e = end(dialect)
    kinds = draw(st.lists(st.sampled_from(kinds_of(dialect)), min_size=1, max_size=3, unique=True))
    xfs = [draw(transform(dialect, k)) for k in kinds]
    lines = [f"{units(dialect)}G90 G17 G00 X{draw(coord):.3f} Y{draw(coord):.3f} Z{draw(small):.3f}{e}"]
    lines += [x.on + e for x in xfs]
    for _ in range(draw(st.integers(1, 3))):
        lines.append(axis_block(draw, dialect)[0])
    for x in draw(st.permutations(xfs)):  # cancel every one, in any order, with moves in between
        lines.append("G90" + e)
        lines.append(x.off + e)
        if draw(st.booleans()):
            lines.append(axis_block(draw, dialect)[0])
    first_checked = len(lines) + 1
    checked = []
    for _ in range(draw(st.integers(1, 4))):
        text, vals, inc = axis_block(draw, dialect)
        lines.append(text)
        checked.append((vals, inc))
    lines.append("M30" + e)
    return dialect, "\n".join(lines) + "\n", first_checked, checked


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(cancel_programs())
def test_after_a_cancel_only_the_named_axes_move(case: tuple[str, str, int, list[tuple[dict[int, float], bool]]]
                                                 ) -> None:
    dialect, text, first, checked = case
    moves, errors = moves_by_line(text, dialect)
    assert not errors, (errors, text)
    prev = None
    for _line, m in moves:  # the path is continuous
        if prev is not None:
            assert max(abs(a - b) for a, b in zip(prev.end, m.start, strict=True)) < EPS, text
        prev = m
    for k, (vals, inc) in enumerate(checked):
        mine = [m for line, m in moves if line == first + k]
        assert len(mine) <= 1, text
        if not mine:  # a zero-length block
            continue
        m = mine[0]
        for axis in range(3):
            if axis not in vals:
                assert abs(m.end[axis] - m.start[axis]) < EPS, (dialect, text, first + k, axis, m)
            elif inc:
                assert abs(m.end[axis] - m.start[axis] - vals[axis]) < EPS, (text, first + k, axis)
            else:
                assert abs(m.end[axis] - vals[axis]) < EPS, (text, first + k, axis)


def test_the_issue_example_z_retract_after_g69() -> None:
    """G68 ... G69 then ``G00 Z10.`` and ``G91 Z5.``: X/Y stay at the rotated point (issue 17)."""
    text = "G90 G00 X10. Y0 Z5. ;\nG68 X0 Y0 R90. ;\nG01 X20. F100. ;\nG69 ;\nG00 Z10. ;\nG91 Z5. ;\nM30 ;\n"
    moves, errors = moves_by_line(text, "syntec")
    assert not errors
    rotated = (0.0, 20.0)  # (20, 0) turned by 90 degrees about the origin
    assert [(round(m.end[0], 6) + 0.0, round(m.end[1], 6) + 0.0) for _, m in moves[-2:]] == [rotated, rotated]
    assert [round(m.end[2], 6) for _, m in moves[-2:]] == [10.0, 15.0]


# ---- (b) every cycle hole is reached by a rapid to its transformed position --------------------------
CYCLES = ["G81", "G82", "G83", "G73", "G85", "G86", "G89"]


@st.composite
def cycle_programs(draw: st.DrawFn) -> tuple[str, str, list[tuple[float, float]], float]:
    dialect = draw(st.sampled_from(["syntec", "fanuc", "szgh"]))
    e = end(dialect)
    code = draw(st.sampled_from(CYCLES if dialect != "szgh" else [c for c in CYCLES if c != "G73"]))
    z0 = draw(st.integers(20, 60))
    lines = [f"{units(dialect)}G90 G17 G00 X{draw(coord):.3f} Y{draw(coord):.3f} Z{z0}.{e}"]
    active: list[Xf] = []
    expected: list[tuple[float, float]] = []
    last = (draw(coord), draw(coord))
    for _ in range(draw(st.integers(1, 4))):
        # change the transforms between cycle blocks: switch one on or cancel one
        if draw(st.booleans()):
            free = [k for k in kinds_of(dialect) if k not in {x.kind for x in active}]
            if free and (not active or draw(st.booleans())):
                x = draw(transform(dialect, draw(st.sampled_from(free))))
                lines.append("G80" + e)
                lines.append(x.on + e)
                active.append(x)
            elif active:
                x = active.pop(draw(st.integers(0, len(active) - 1)))
                lines.append("G80" + e)
                lines.append(x.off + e)
                if dialect == "syntec" and x.kind == "scale":  # SYNTEC's G50 cancels the mirror too
                    active = [a for a in active if a.kind != "mirror"]
        g = draw(st.sampled_from(["G98", "G99"]))
        holes = [last if draw(st.booleans()) else (draw(coord), draw(coord)) for _ in range(draw(st.integers(1, 3)))]
        q = " Q3." if code in ("G73", "G83") else ""
        p = " P500" if code in ("G82", "G89") and dialect != "szgh" else (" P0.5" if code in ("G82", "G89") else "")
        x0, y0 = holes[0]
        lines.append(f"{g} {code} X{x0:.3f} Y{y0:.3f} Z-5. R2.{q}{p} F300.{e}")
        lines += [f"X{hx:.3f} Y{hy:.3f}{e}" for hx, hy in holes[1:]]
        for h in holes:
            pt = h
            for x in sorted(active, key=lambda t: ORDER[t.kind]):
                pt = x.apply(pt)
            expected.append(pt)
        last = holes[-1]
    lines.append("G80" + e)
    lines.append("M30" + e)
    return dialect, "\n".join(lines) + "\n", expected, float(z0)


@settings(max_examples=120, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(cycle_programs())
def test_every_hole_is_reached_by_a_rapid_to_its_transformed_position(
        case: tuple[str, str, list[tuple[float, float]], float]) -> None:
    dialect, text, expected, z0 = case
    moves, errors = moves_by_line(text, dialect)
    assert not errors, (errors, text)
    cycle_moves = [m for _, m in moves if m.origin.code.startswith(("G7", "G8"))]
    drilled: list[tuple[float, float]] = []
    for m in cycle_moves:
        if math.hypot(m.end[0] - m.start[0], m.end[1] - m.start[1]) > EPS:
            assert isinstance(m, Rapid), ("a feed moves in the plane", text, m)
            assert abs(m.end[2] - m.start[2]) < EPS, ("a diagonal rapid (plane and drilling axis at once)", text, m)
            assert min(abs(m.end[2] - z0), abs(m.end[2] - 2.0)) < EPS, ("positioning not at initial/R", text, m)
        if isinstance(m, Linear):
            drilled.append((m.start[0], m.start[1]))
    # one feed group per hole, at the hole's transformed position (consecutive holes at one point merge)
    merged: list[tuple[float, float]] = []
    for p in expected:
        if not merged or math.hypot(p[0] - merged[-1][0], p[1] - merged[-1][1]) > 1e-4:
            merged.append(p)
    got: list[tuple[float, float]] = []
    for p in drilled:
        if not got or math.hypot(p[0] - got[-1][0], p[1] - got[-1][1]) > 1e-4:
            got.append(p)
    assert len(got) == len(merged), (text, got, merged)
    for g, x in zip(got, merged, strict=True):
        assert math.hypot(g[0] - x[0], g[1] - x[1]) < 1e-4, (text, got, merged)


def test_same_programmed_point_after_a_rotation_is_positioned() -> None:
    """Issue 17: a cycle block at the previous programmed X/Y after G68 rapids to the rotated hole
    before feeding (it used to feed diagonally from the old hole)."""
    text = ("G90 G00 X10. Y0 Z20. ;\nG99 G81 X10. Y0 Z-5. R2. F300. ;\nG80 ;\nG68 X0 Y0 R90. ;\n"
            "G99 G81 X10. Y0 Z-5. R2. F300. ;\nG80 ;\nM30 ;\n")
    moves, errors = moves_by_line(text, "syntec")
    assert not errors
    feeds = [m for _, m in moves if isinstance(m, Linear)]
    assert [(round(f.start[0], 6) + 0.0, round(f.start[1], 6) + 0.0) for f in feeds] == [(10.0, 0.0), (0.0, 10.0)]
    for f in feeds:
        assert f.start[:2] == f.end[:2]  # straight down


def test_inside_a_cycle_after_a_cancel_the_unnamed_plane_axis_stays() -> None:
    """After G69 a cycle block naming only X drills at the new X and the Y where the tool is (the rotated
    Y), and the drilling axis starts from where the tool is, then goes to the absolute R and Z levels."""
    text = ("G71 G90 G00 X10. Y0 Z20. ;\nG68 X0 Y0 R90. ;\nG01 X20. F100. ;\nG69 ;\n"
            "G99 G81 X5. Z-5. R2. F300. ;\nG80 ;\nM30 ;\n")
    moves, errors = moves_by_line(text, "syntec")
    assert not errors
    rotated_y = 20.0  # (20, 0) turned by 90 degrees about the origin is (0, 20)
    cycle = [m for _, m in moves if m.origin.code == "G81"]
    feeds = [m for m in cycle if isinstance(m, Linear)]
    assert [(round(f.start[0], 6), round(f.start[1], 6)) for f in feeds] == [(5.0, rotated_y)]
    assert [round(f.end[2], 6) for f in feeds] == [-5.0]
    first = cycle[0]  # positioning: in the plane only, at the height the tool is at
    assert round(first.end[2], 6) == 20.0 and round(first.end[1], 6) == rotated_y
