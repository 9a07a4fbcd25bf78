"""SERIES 8 arcs (spec 4.1): the modal radius, small radii and unsigned one-quadrant I/J.

The shared arc motion (``ops.MOTIONS["arc_cw"/"arc_ccw"]``) is wrapped; for a SERIES 8
interpreter the block's words are first rewritten into the form the shared code reads:

* an arc block without R and without I/J uses the last R programmed in an arc block
  (an R in G10, G55, G57, G92 or a cycle does not count, A-11);
* |R| less than half the chord is enlarged to half the chord, a half circle, keeping
  the sign (the manual; W0256 says so, A-12; option ``arc_r_small = "error"``);
* I and J are distances (a minus sign is ignored with W0254, or refused with
  ``arc_ij_sign = "error"``): of the up to four centres start + (+-I, +-J), the one
  whose circle passes through the end (within ``arc_ij_tolerance_mm``) with the arc
  inside one quadrant is taken and written back as signed offsets; none is
  ``INVALID ARC`` (E0253) and the block does not move.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import TYPE_CHECKING

from cncc import diagnostics as dg
from cncc.frontend import ops, rs274
from cncc.frontend.series8 import state
from cncc.frontend.series8.layer import LAYER
from cncc.frontend.syntax import Word
from cncc.ir import Plane, Vec6

if TYPE_CHECKING:
    from cncc.frontend.interp import BlockContext, Interpreter

QUARTER = math.pi / 2.0
_LETTERS = {Plane.XY: ("I", "J"), Plane.ZX: ("K", "I"), Plane.YZ: ("J", "K")}


def quadrant_centre(start: tuple[float, float], end: tuple[float, float], i: float, j: float, clockwise: bool,
                    tol: float) -> tuple[float, float] | None:
    """The centre of the one-quadrant arc from ``start`` to ``end`` with unsigned offsets ``i``, ``j``.

    None when no candidate centre start + (+-i, +-j) has the end on its circle (within
    ``tol``) and the arc inside one quadrant of the axes through it.
    """
    best: tuple[float, tuple[float, float]] | None = None
    seen = set()
    for sx in (1.0, -1.0):
        for sy in (1.0, -1.0):
            c = (start[0] + sx * abs(i), start[1] + sy * abs(j))
            if c in seen:
                continue
            seen.add(c)
            r0 = math.hypot(start[0] - c[0], start[1] - c[1])
            r1 = math.hypot(end[0] - c[0], end[1] - c[1])
            if r0 <= tol or abs(r1 - r0) > tol or not _one_quadrant(start, end, c, r0, clockwise, tol):
                continue
            if best is None or abs(r1 - r0) < best[0]:
                best = (abs(r1 - r0), c)
    return None if best is None else best[1]


def _one_quadrant(start: tuple[float, float], end: tuple[float, float], c: tuple[float, float], r: float,
                  clockwise: bool, tol: float) -> bool:
    eps = 1e-9 + tol / r
    a0 = math.atan2(start[1] - c[1], start[0] - c[0])
    a1 = math.atan2(end[1] - c[1], end[0] - c[0])
    sweep = ((a0 - a1) if clockwise else (a1 - a0)) % (2 * math.pi)
    if sweep < eps or sweep > QUARTER + eps:
        return False
    if clockwise:
        high = math.ceil((a0 - eps) / QUARTER) * QUARTER
        return a0 - sweep >= high - QUARTER - eps
    low = math.floor((a0 + eps) / QUARTER) * QUARTER
    return a0 + sweep <= low + QUARTER + eps


def _word(w: Word | None, letter: str, value_mm: float, mm_per_unit: float, at: tuple[int, int]) -> Word:
    if w is None:
        return Word(letter, value_mm / mm_per_unit, True, at[0], at[1])
    return replace(w, value=value_mm / mm_per_unit, point=True)


def _rewrite(it: Interpreter, ctx: BlockContext, end: Vec6, clockwise: bool) -> bool:
    """Put the block's arc words in the shared form; False when the block must not move."""
    st = state.get(it)
    assert st is not None
    plane = it.frame.plane
    l1, l2 = _LETTERS[plane]
    rw, w1, w2 = ctx.words.get("R"), ctx.words.get(l1), ctx.words.get(l2)
    rd = it.reader
    at = (ctx.block.start, ctx.block.start + 1)
    if rw is not None and (w1 is not None or w2 is not None):
        return True  # the shared code reports "either I/J/K or R"
    if rw is None and w1 is None and w2 is None:
        if st.arc_r_mm is None:
            return True  # no centre at all: E0207 from the shared code
        rw = ctx.words["R"] = _word(None, "R", st.arc_r_mm, rd.mm_per_unit, at)
    elif rw is not None:
        st.arc_r_mm = rd.length_mm(rw)
    if rw is not None:
        return _radius(it, ctx, rw, end)
    return _centre(it, ctx, end, clockwise, (l1, l2))


def _radius(it: Interpreter, ctx: BlockContext, rw: Word, end: Vec6) -> bool:
    p = it.frame.plane
    start = it.pos
    half = math.hypot(end[p.first] - start[p.first], end[p.second] - start[p.second]) / 2.0
    r_mm = it.reader.length_mm(rw)
    if half == 0.0 or abs(r_mm) >= half or state.option(it, "arc_r_small", "enlarge") == "error":
        return True
    it.sink.emit(dg.ASSUMED, it.word_span(rw) if rw.end > rw.start + 1 else ctx.span,
                 f"radius {abs(r_mm) / it.reader.mm_per_unit:.4f} is less than half the chord; the arc is made "
                 f"a half circle of radius {half / it.reader.mm_per_unit:.4f} (spec A-12)")
    ctx.words["R"] = replace(rw, value=math.copysign(half, r_mm) / it.reader.mm_per_unit, point=True)
    return True


def _centre(it: Interpreter, ctx: BlockContext, end: Vec6, clockwise: bool, letters: tuple[str, str]) -> bool:
    p = it.frame.plane
    rd = it.reader
    w1, w2 = ctx.words.get(letters[0]), ctx.words.get(letters[1])
    for w in (w1, w2):
        if w is not None and w.value < 0:
            if state.option(it, "arc_ij_sign", "ignore") == "error":
                it.emit_error(dg.INVALID_ARC, it.word_span(w), f"INVALID ARC: {w.letter} is a distance and takes "
                                                               "no sign")
                return False
            it.sink.emit(dg.DIALECT_IGNORED, it.word_span(w), f"{w.letter}{w.value:g}: the sign is ignored "
                                                                 "(I/J are unsigned distances)")
    o1 = abs(rd.length_mm(w1)) if w1 is not None else 0.0
    o2 = abs(rd.length_mm(w2)) if w2 is not None else 0.0
    s, e = it.pos, end
    tol = float(state.option(it, "arc_ij_tolerance_mm", 0.0254))
    c = quadrant_centre((s[p.first], s[p.second]), (e[p.first], e[p.second]), o1, o2, clockwise, tol)
    if c is None:
        it.emit_error(dg.INVALID_ARC, ctx.span,
                      "INVALID ARC: no centre at the unsigned distances puts the end point on the arc "
                      "within one quadrant")
        return False
    at = (ctx.block.start, ctx.block.start + 1)
    ctx.words[letters[0]] = _word(w1, letters[0], c[0] - s[p.first], rd.mm_per_unit, at)
    ctx.words[letters[1]] = _word(w2, letters[1], c[1] - s[p.second], rd.mm_per_unit, at)
    return True


def _wrap(inner: ops.MotionHandler, clockwise: bool) -> ops.MotionHandler:
    def arc(it: Interpreter, ctx: BlockContext, end: Vec6) -> None:
        if state.get(it) is None:
            inner(it, ctx, end)
            return
        if not _rewrite(it, ctx, end, clockwise):
            return
        if rs274.state(it).inverse_time and "F" in ctx.words:
            rs274._inverse_time_feed(it, ctx)  # G93: the feed from the arc's real length
        inner(it, ctx, end)

    return arc


LAYER.wrap_motion("arc_cw", lambda inner: _wrap(inner, True))
LAYER.wrap_motion("arc_ccw", lambda inner: _wrap(inner, False))
