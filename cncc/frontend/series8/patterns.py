"""SERIES 8 G49/G50 rectangular patterns (spec 4.7, A-44): titles only in the manual.

The spec's probable reading (the default, ``rect_pattern_reading = "holes"``): hole
positions on a rectangle, visited counter-clockwise (G49) or clockwise (G50), the
canned cycle in force (G81-G89, with its stored levels) running at each one.  The
words are cncc's, announced once per program (W0256), modelled on SYNTEC's grid
pattern G137.1:

* ``X Y``: the first hole, a corner of the rectangle (G90/G91 as usual);
* ``I`` / ``J``: the signed pitch along the plane's first / second axis;
* ``P`` / ``K``: the number of holes along the first / second axis (corners included);
* ``Z R``: the cycle's levels (stored, A-18); ``D`` the tool-length row; ``F``.

``rect_pattern_layout = "perimeter"`` (default) drills the holes on the rectangle's
edge only; ``"grid"`` all P x K of them, ring by ring inwards, each ring in the same
sense.  The turning sense is geometric: the first leg runs along I when that makes the
rectangle's sides turn the programmed way, along J otherwise.

The alternative reading (``rect_pattern_reading = "frame"``): the tool mills the
rectangle with corner X Y and sides I, J at F at its current level, counter-clockwise
(G49) or clockwise (G50), and ends at the corner again.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from cncc import diagnostics as dg
from cncc.dialects import CodeDef
from cncc.dialects.series8_cycles import Series8CycleKind
from cncc.frontend import ops
from cncc.frontend.series8 import cycles, state
from cncc.frontend.series8.codes import vendor_gate
from cncc.frontend.series8.cycles import emit, store_levels, tool_length
from cncc.frontend.series8.layer import LAYER
from cncc.ir import Linear, Origin, OriginKind, Vec6

if TYPE_CHECKING:
    from cncc.frontend.interp import BlockContext, Interpreter

Pt = tuple[float, float]
MAX_COUNT = 9999
MAX_HOLES = 100_000  # a grid of P x K holes
_HOLES = ("X Y as the first hole (a corner), I J as the pitches, P K as the hole counts along the plane's "
          "axes, on the rectangle's edge; the cycle in force drills them")
_FRAME = "X Y as a corner and I J as the sides of a rectangle milled at the current level"


def _ring(x0: Pt, pitch: Pt, n_u: int, n_v: int, ccw: bool) -> list[Pt]:
    """The holes on the edge of an n_u x n_v rectangle from ``x0``, in the turning sense asked for."""
    def pt(a: int, b: int) -> Pt:
        return (x0[0] + a * pitch[0], x0[1] + b * pitch[1])

    if n_u == 1 or n_v == 1:
        return [pt(a, b) for a in range(n_u) for b in range(n_v)]
    u_first = (pitch[0] * pitch[1] > 0) == ccw  # along u then v turns counter-clockwise when I*J > 0
    idx: list[tuple[int, int]] = []
    if u_first:
        idx += [(a, 0) for a in range(n_u)] + [(n_u - 1, b) for b in range(1, n_v)]
        idx += [(a, n_v - 1) for a in range(n_u - 2, -1, -1)] + [(0, b) for b in range(n_v - 2, 0, -1)]
    else:
        idx += [(0, b) for b in range(n_v)] + [(a, n_v - 1) for a in range(1, n_u)]
        idx += [(n_u - 1, b) for b in range(n_v - 2, -1, -1)] + [(a, 0) for a in range(n_u - 2, 0, -1)]
    return [pt(a, b) for a, b in idx]


def rect_holes(x0: Pt, pitch: Pt, n_u: int, n_v: int, ccw: bool, grid: bool) -> list[Pt]:
    """Hole positions of a G49 (``ccw``) / G50 pattern: the edge, or every ring inwards (``grid``)."""
    out: list[Pt] = []
    while n_u > 0 and n_v > 0:
        out += _ring(x0, pitch, n_u, n_v, ccw)
        if not grid:
            break
        x0, n_u, n_v = (x0[0] + pitch[0], x0[1] + pitch[1]), n_u - 2, n_v - 2
    return out


def _count(it: Interpreter, ctx: BlockContext, c: CodeDef, letter: str) -> int | None:
    w = ctx.words.get(letter)
    if w is None:
        it.emit_error(dg.PATTERN_BAD_WORD, ctx.span, f"{c.name} needs the hole count {letter}")
        return None
    if w.value != int(w.value) or not 1 <= w.value <= MAX_COUNT:
        it.emit_error(dg.PATTERN_BAD_WORD, it.word_span(w),
                      f"{c.name} {letter}{w.value:g}: the hole count is an integer from 1 to {MAX_COUNT}")
        return None
    return int(w.value)


def _pitch(it: Interpreter, ctx: BlockContext, c: CodeDef, letter: str, count: int) -> float | None:
    w = ctx.words.get(letter)
    if count == 1:
        return it.reader.length_mm(w) if w is not None else 0.0
    if w is None or w.value == 0:
        it.emit_error(dg.PATTERN_BAD_WORD, it.word_span(w) if w is not None else ctx.span,
                      f"{c.name} needs a non-zero pitch {letter} for more than one hole")
        return None
    return it.reader.length_mm(w)


@LAYER.handler("rect_pattern")
def _pattern(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    frame_reading = state.option(it, "rect_pattern_reading", "holes") == "frame"
    if not vendor_gate(it, ctx, c, _FRAME if frame_reading else _HOLES):
        return
    if frame_reading:
        _frame(it, ctx, c)
        return
    st = state.get(it)
    assert st is not None
    code = st.cycle_code
    if not it.modal.cycle or code is None:
        it.emit_error(dg.PATTERN_NO_CYCLE, ctx.span, f"{c.name} drills with the canned cycle in force; program "
                                                     "one (G81-G89) first")
        return
    kind = cycles.kind_of(code.cycle)
    assert kind is not None  # checked when the cycle code was read
    if kind is Series8CycleKind.CASE_BORE:
        it.emit_error(dg.PATTERN_BAD_WORD, ctx.span, f"{c.name}: {code.name} stays at depth; a pattern cannot "
                                                     "move between its holes")
        return
    tool_length(it, ctx)
    store_levels(it, ctx)
    n_u, n_v = _count(it, ctx, c, "P"), _count(it, ctx, c, "K")
    if n_u is None or n_v is None:
        return
    pu, pv = _pitch(it, ctx, c, "I", n_u), _pitch(it, ctx, c, "J", n_v)
    if pu is None or pv is None:
        return
    p = it.frame.plane
    first = ops.target(it, ctx)
    grid = state.option(it, "rect_pattern_layout", "perimeter") == "grid"
    if grid and n_u * n_v > MAX_HOLES:
        it.emit_error(dg.PATTERN_BAD_WORD, ctx.span, f"{c.name}: {n_u} x {n_v} holes is more than {MAX_HOLES}")
        return
    points = rect_holes((first[p.first], first[p.second]), (pu, pv), n_u, n_v, c.cycle == "ccw", grid)
    emit(it, ctx, code, kind, tuple(_place(first, p.first, p.second, q) for q in points), c.name)


def _place(p: Vec6, i: int, j: int, q: Pt) -> Vec6:
    out = list(p)
    out[i], out[j] = q
    return (out[0], out[1], out[2], out[3], out[4], out[5])


def _frame(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    """The alternative reading: mill the rectangle X Y (corner), I J (sides) at the current level."""
    iw, jw = ctx.words.get("I"), ctx.words.get("J")
    if iw is None or jw is None or iw.value == 0 or jw.value == 0:
        it.emit_error(dg.PATTERN_BAD_WORD, ctx.span, f"{c.name} (frame reading) needs non-zero sides I and J")
        return
    feed = ops.feed_mm_min(it, ctx)
    if feed is None:
        return
    p = it.frame.plane
    end = list(ops.target(it, ctx))
    end[p.normal] = it.pos[p.normal]  # the frame is milled at the current level
    corner: Vec6 = (end[0], end[1], end[2], end[3], end[4], end[5])
    su, sv = it.reader.length_mm(iw), it.reader.length_mm(jw)
    u_first = (su * sv > 0) == (c.cycle == "ccw")
    legs = [(su, 0.0), (0.0, sv)] if u_first else [(0.0, sv), (su, 0.0)]
    u0, v0 = corner[p.first], corner[p.second]
    pts = [(u0 + legs[0][0], v0 + legs[0][1]), (u0 + su, v0 + sv),
           (u0 + legs[1][0], v0 + legs[1][1]), (u0, v0)]
    motion, origin = ops.block_motion(it, ctx), Origin(OriginKind.CYCLE, c.name)
    if corner != it.pos:
        ctx.out.append(Linear(ctx.span, it.frame, it.pos, corner, feed, motion, origin))
    at = corner
    for q in pts:
        nxt = _place(at, p.first, p.second, q)
        ctx.out.append(Linear(ctx.span, it.frame, at, nxt, feed, motion, origin))
        at = nxt
    it.pos = at
    st = state.get(it)
    assert st is not None
    st.moved = True
