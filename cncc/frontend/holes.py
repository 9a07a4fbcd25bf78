"""Hole patterns (SYNTEC G134, G135, G136, G137.1): positions for the cycle in force.

A pattern block drills nothing by itself: it lists hole positions and runs the canned
cycle in force with its stored data (usually set by a ``G81 ... K0`` block).  The
pattern's X/Y (the two axes of the plane) follow G90/G91; angles are counter-clockwise
from the plane's first axis.  Spec: syntec-mill-v8.20.md sections 4.49-4.52.

=========  ==========================================  ==========================
code       holes (i = 0 .. n-1)                         words
=========  ==========================================  ==========================
G134       centre + I (cos, sin)(J + sign(K) i 360/|K|)  I radius, J angle, K count
G135       start + i I (cos J, sin J)                   I pitch, J angle, K count
G136       centre + I (cos, sin)(J + i P)               I radius, J, P step, K
G137.1     start + (a I, b J), P x K grid               I, P (along X), J, K
=========  ==========================================  ==========================

G137.1 runs row by row, reversing every other row (option ``g137_order``:
``serpentine``, or ``raster`` to start every row at the first column).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING

from cncc import diagnostics as dg
from cncc.dialects import CodeDef
from cncc.frontend import cycles, ops
from cncc.ir import AXES, Vec6

if TYPE_CHECKING:
    from cncc.frontend.interp import BlockContext, Interpreter

MAX_COUNT = 9999
Points = list[tuple[float, float]]
Pattern = Callable[["Interpreter", "BlockContext", CodeDef, tuple[float, float]], "Points | None"]


def _word(it: Interpreter, ctx: BlockContext, c: CodeDef, letter: str, *, required: bool) -> float | None:
    w = ctx.words.get(letter)
    if w is None:
        if required:
            it.emit_error(dg.PATTERN_BAD_WORD, ctx.span, f"{c.name} needs {letter}")
            return None
        return 0.0
    return it.reader.value(w, c.words.get(letter))


def _count(it: Interpreter, ctx: BlockContext, c: CodeDef, letter: str, *, signed: bool = False) -> int | None:
    v = _word(it, ctx, c, letter, required=True)
    if v is None:
        return None
    if v != int(v) or v == 0 or abs(v) > MAX_COUNT or (v < 0 and not signed):
        low = f"-{MAX_COUNT}" if signed else "1"
        it.emit_error(dg.PATTERN_BAD_WORD, ctx.span,
                      f"{c.name} {letter}{v:g}: the hole count is a non-zero integer from {low} to {MAX_COUNT}")
        return None
    return int(v)


def _positive(it: Interpreter, ctx: BlockContext, c: CodeDef, letter: str) -> float | None:
    v = _word(it, ctx, c, letter, required=True)
    if v is not None and v <= 0:
        it.emit_error(dg.PATTERN_BAD_WORD, ctx.span, f"{c.name} {letter}{v:g}: the radius must be positive")
        return None
    return v


def _polar(centre: tuple[float, float], radius: float, angles_deg: list[float]) -> Points:
    return [(centre[0] + radius * math.cos(math.radians(a)), centre[1] + radius * math.sin(math.radians(a)))
            for a in angles_deg]


def _circle(it: Interpreter, ctx: BlockContext, c: CodeDef, origin: tuple[float, float]) -> Points | None:
    radius = _positive(it, ctx, c, "I")
    start = _word(it, ctx, c, "J", required=False)
    k = _count(it, ctx, c, "K", signed=True)
    if radius is None or start is None or k is None:
        return None
    n = abs(k)
    step = math.copysign(360.0 / n, k)
    return _polar(origin, radius, [start + i * step for i in range(n)])


def _line(it: Interpreter, ctx: BlockContext, c: CodeDef, origin: tuple[float, float]) -> Points | None:
    pitch = _word(it, ctx, c, "I", required=True)
    angle = _word(it, ctx, c, "J", required=False)
    k = _count(it, ctx, c, "K")
    if pitch is None or angle is None or k is None:
        return None
    dx, dy = math.cos(math.radians(angle)), math.sin(math.radians(angle))
    return [(origin[0] + i * pitch * dx, origin[1] + i * pitch * dy) for i in range(k)]


def _arc(it: Interpreter, ctx: BlockContext, c: CodeDef, origin: tuple[float, float]) -> Points | None:
    radius = _positive(it, ctx, c, "I")
    start = _word(it, ctx, c, "J", required=False)
    step = _word(it, ctx, c, "P", required=True)
    k = _count(it, ctx, c, "K")
    if radius is None or start is None or step is None or k is None:
        return None
    return _polar(origin, radius, [start + i * step for i in range(k)])


def _grid(it: Interpreter, ctx: BlockContext, c: CodeDef, origin: tuple[float, float]) -> Points | None:
    pitch_1 = _word(it, ctx, c, "I", required=True)
    pitch_2 = _word(it, ctx, c, "J", required=True)
    n1 = _count(it, ctx, c, "P")
    n2 = _count(it, ctx, c, "K")
    if pitch_1 is None or pitch_2 is None or n1 is None or n2 is None:
        return None
    serpentine = it.dialect.option("g137_order", "serpentine") == "serpentine"
    out: Points = []
    for b in range(n2):
        cols = range(n1 - 1, -1, -1) if serpentine and b % 2 else range(n1)
        out.extend((origin[0] + a * pitch_1, origin[1] + b * pitch_2) for a in cols)
    return out


PATTERNS: dict[str, Pattern] = {"circle": _circle, "line": _line, "arc": _arc, "grid": _grid}


@ops.handler("pattern")
def _pattern(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    ctx.axis_used = True
    data = cycles.cycle_data(it)
    if data is None:
        it.emit_error(dg.PATTERN_NO_CYCLE, ctx.span,
                      f"{c.name} drills with the canned cycle in force; program one first (e.g. G81 ... K0)")
        return
    fn = PATTERNS.get(c.cycle)
    if fn is None:
        it.emit_error(dg.CYCLE_UNKNOWN, ctx.span, f"{c.name}: hole pattern {c.cycle!r} is not known to cncc")
        return
    if not cycles.check_levels(it, ctx, data):
        return
    plane = data.plane
    first, second = plane.first, plane.second
    at = ops.target(it, ctx)
    points = fn(it, ctx, c, (at[first], at[second]))
    if points is None:
        return
    holes: list[Vec6] = []
    for u, v in points:
        p = list(at)
        p[first], p[second], p[plane.normal] = u, v, it.pos[plane.normal]
        holes.append((p[0], p[1], p[2], p[3], p[4], p[5]))
    words = [(AXES[first], at[first]), (AXES[second], at[second])]
    words += [(k, it.reader.value(ctx.words[k], c.words.get(k))) for k in "IJKP" if k in ctx.words]
    cycles.emit_cycle(it, ctx, data, tuple(holes), 1, c.name, tuple(words))
