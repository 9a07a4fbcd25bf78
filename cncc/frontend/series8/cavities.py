"""SERIES 8 G34/G35 (rectangular) and G36 (circular) milled cavities, lowered to moves.

The manual has the titles only (spec 4.6, A-02, A-43); the words are cncc's reading,
announced once per program (W0256) and refused with ``vendor_cycles = "error"``:

* ``X Y``: the centre (``cavity_reference = "corner"``: the corner with the lowest
  coordinates, rectangles only), after G90/G91 like any position;
* ``I J``: the rectangle's sizes along the plane's first and second axes; G36 ``I``:
  the diameter (``cavity_circle_size = "radius"``: the radius);
* ``Z R``: the bottom and the clearance level, absolute and kept like the cycles' (A-18);
* ``K``: the depth per pass (none: the full depth at once); ``L``: the step-over
  (none: ``cavity_stepover`` times the tool diameter; never more than the diameter);
* ``D``: the tool row (its radius, and its length as in the cycles, A-17); ``F``.

Moves: rapid in the plane to the plunge point, rapid to R, then per depth a plunge at
F and the clearing path of :mod:`.cavity_paths` (inside the cavity less the tool
radius), back to the plunge point at depth between passes; finally rapid to R and to
the centre.  G34 runs the rings counter-clockwise, G35 clockwise, G36 as
``g36_direction`` says (counter-clockwise: climb milling with M03).  The moves are
tool-centre moves: the block's frame has cutter compensation off.
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

from cncc import diagnostics as dg
from cncc.dialects import CodeDef
from cncc.frontend import ops
from cncc.frontend.series8 import cavity_paths as cp
from cncc.frontend.series8 import state
from cncc.frontend.series8.codes import vendor_gate
from cncc.frontend.series8.cycles import store_levels, tool_length
from cncc.frontend.series8.layer import LAYER
from cncc.ir import Arc, Command, CompSide, Frame, Linear, Motion, Origin, OriginKind, Rapid, Vec6

if TYPE_CHECKING:
    from cncc.frontend.interp import BlockContext, Interpreter

MAX_MOVES = 1_000_000
_READING = {
    "rect": "X Y as the centre, I J as the sizes, Z R as levels, K as the depth per pass, L as the step-over, "
            "D as the tool",
    "circle": "X Y as the centre, I as the diameter, Z R as levels, K as the depth per pass, L as the step-over, "
              "D as the tool",
}


def _bad(it: Interpreter, ctx: BlockContext, c: CodeDef, letter: str, why: str) -> None:
    w = ctx.words.get(letter)
    it.emit_error(dg.CAVITY_BAD_WORD, it.word_span(w) if w is not None else ctx.span, f"{c.name}: {why}")


def _tool_radius(it: Interpreter, ctx: BlockContext, c: CodeDef) -> float | None:
    dw = ctx.words.get("D")
    index = int(dw.value) if dw is not None and dw.value == int(dw.value) else it.frame.tool_length_index
    radius = it.options.tool_radii_mm.get(index) if index else None
    if radius is None or radius <= 0:
        _bad(it, ctx, c, "D", "the cavity needs the tool radius: D selects a row of the tool table (--tools) "
                              "with a radius")
        return None
    return radius


def _size(it: Interpreter, ctx: BlockContext, c: CodeDef, letter: str) -> float | None:
    w = ctx.words.get(letter)
    if w is None or w.value <= 0:
        _bad(it, ctx, c, letter, f"{letter} (the cavity size) is needed and must be positive")
        return None
    return it.reader.length_mm(w)


def _step(it: Interpreter, ctx: BlockContext, c: CodeDef, radius: float) -> float | None:
    w = ctx.words.get("L")
    step = it.reader.length_mm(w) if w is not None else 2.0 * radius * float(state.option(it, "cavity_stepover", 0.5))
    if step <= 0 or step > 2.0 * radius + 1e-9:
        _bad(it, ctx, c, "L", f"the step-over {step:g} mm must be positive and no larger than the tool diameter "
                              f"{2 * radius:g} mm (material would be left between the passes)")
        return None
    return step


def _levels(it: Interpreter, ctx: BlockContext, c: CodeDef) -> tuple[float, float] | None:
    store_levels(it, ctx)
    data = state.get(it)
    assert data is not None
    r, z = data.cycle.r_mm, data.cycle.z_mm
    axis = ops.AXES[it.frame.plane.normal]
    if r is None:
        it.emit_error(dg.CYCLE_NO_R, ctx.span, f"{c.name} needs an R level")
        return None
    if z is None:
        it.emit_error(dg.CYCLE_NO_BOTTOM, ctx.span, f"{c.name} needs the bottom level {axis}")
        return None
    if r == z:
        it.emit_error(dg.CYCLE_R_PAST_BOTTOM, ctx.span, f"{c.name}: {axis} and R are the same level")
        return None
    return r, z


def _path(it: Interpreter, ctx: BlockContext, c: CodeDef, radius: float, step: float) -> cp.LevelPath | None:
    zigzag = state.option(it, "cavity_clearing", "concentric") == "zigzag"
    if c.cycle == "circle":
        size = _size(it, ctx, c, "I")
        if size is None:
            return None
        rho = (size if state.option(it, "cavity_circle_size", "diameter") == "radius" else size / 2.0) - radius
        ccw = state.option(it, "g36_direction", "ccw") != "cw"
        if rho < -1e-9:
            _bad(it, ctx, c, "I", "the tool is larger than the cavity")
            return None
        return (cp.circle_zigzag if zigzag else cp.circle_concentric)(max(rho, 0.0), step, ccw)
    length, width = _size(it, ctx, c, "I"), _size(it, ctx, c, "J")
    if length is None or width is None:
        return None
    a, b = length / 2.0 - radius, width / 2.0 - radius
    if min(a, b) < -1e-9:
        _bad(it, ctx, c, "I" if a < b else "J", "the tool is larger than the cavity")
        return None
    ccw = c.cycle == "rect_ccw"
    return (cp.rect_zigzag if zigzag else cp.rect_concentric)(max(a, 0.0), max(b, 0.0), step, ccw)


@LAYER.handler("cavity")
def _cavity(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    if not vendor_gate(it, ctx, c, _READING["circle" if c.cycle == "circle" else "rect"]):
        return
    tool_length(it, ctx)
    levels = _levels(it, ctx, c)
    radius = _tool_radius(it, ctx, c)
    if levels is None or radius is None:
        return
    step = _step(it, ctx, c, radius)
    per_pass = 0.0
    if (kw := ctx.words.get("K")) is not None:
        per_pass = it.reader.length_mm(kw)
        if per_pass <= 0:
            _bad(it, ctx, c, "K", "the depth per pass K must be positive")
            return
    if step is not None and _too_many(it, ctx, c, levels, per_pass, step):
        return
    path = _path(it, ctx, c, radius, step) if step is not None else None
    feed = ops.feed_mm_min(it, ctx) if path is not None else None
    if path is None or feed is None:
        return
    centre = _centre(it, ctx, c)
    _Builder(it, ctx, c, centre, feed).run(path, levels, per_pass)
    st = state.get(it)
    assert st is not None
    st.moved = True


def _too_many(it: Interpreter, ctx: BlockContext, c: CodeDef, levels: tuple[float, float], per_pass: float,
              step: float) -> bool:
    """Refuse a cavity of more than MAX_MOVES moves (a tiny L or K on a large cavity) before building it."""
    sizes = [abs(it.reader.length_mm(w)) for k in "IJ" if (w := ctx.words.get(k)) is not None]
    passes = cp.divisions(abs(levels[1] - levels[0]), per_pass) if per_pass > 0 else 1
    moves = max(passes, 1) * (6 * cp.divisions(max(sizes, default=0.0), step) + 8)
    if moves > MAX_MOVES:
        _bad(it, ctx, c, "L", f"about {moves:.3g} moves (step-over {step:g} mm, {passes} passes): more than "
                              f"{MAX_MOVES}; use a larger L or K")
        return True
    return False


def _centre(it: Interpreter, ctx: BlockContext, c: CodeDef) -> tuple[float, float]:
    p = it.frame.plane
    end = ops.target(it, ctx)
    u, v = end[p.first], end[p.second]
    if c.cycle != "circle" and state.option(it, "cavity_reference", "centre") == "corner":
        iw, jw = ctx.words["I"], ctx.words["J"]
        u, v = u + it.reader.length_mm(iw) / 2.0, v + it.reader.length_mm(jw) / 2.0
    return u, v


class _Builder:
    """Turns the plane path into commands in the block's frame (compensation off)."""

    def __init__(self, it: Interpreter, ctx: BlockContext, c: CodeDef, centre: tuple[float, float],
                 feed: float) -> None:
        self.it, self.ctx, self.centre, self.feed = it, ctx, centre, feed
        self.origin = Origin(OriginKind.CYCLE, c.name)
        f = it.frame
        self.frame: Frame = f if f.comp_side is CompSide.OFF else replace(
            f, comp_side=CompSide.OFF, comp_radius_mm=0.0, comp_index=0)
        self.motion: Motion = ops.block_motion(it, ctx)
        self.pos: Vec6 = it.pos
        self.out: list[Command] = ctx.out

    def at(self, q: cp.Pt, level: float | None = None) -> Vec6:
        p, out = self.frame.plane, list(self.pos)
        out[p.first], out[p.second] = self.centre[0] + q[0], self.centre[1] + q[1]
        if level is not None:
            out[p.normal] = level
        return (out[0], out[1], out[2], out[3], out[4], out[5])

    def rapid(self, to: Vec6) -> None:
        if to != self.pos:
            self.out.append(Rapid(self.ctx.span, self.frame, self.pos, to, self.motion, self.origin))
            self.pos = to

    def feed_to(self, to: Vec6) -> None:
        if to != self.pos:
            self.out.append(Linear(self.ctx.span, self.frame, self.pos, to, self.feed, self.motion, self.origin))
            self.pos = to

    def arc(self, step: cp.Step) -> None:
        assert step.centre is not None
        end, centre = self.at(step.to), self.at(step.centre)
        self.out.append(Arc(self.ctx.span, self.frame, self.pos, end, centre, step.turns, self.frame.plane,
                            self.feed, self.motion, self.origin))
        self.pos = end

    def run(self, path: cp.LevelPath, levels: tuple[float, float], per_pass: float) -> None:
        r_level, bottom = levels
        self.rapid(self.at(path.start))
        self.rapid(self.at(path.start, r_level))
        for k, depth in enumerate(cp.depth_levels(r_level, bottom, per_pass)):
            if k:
                self.feed_to(self.at(path.start))
            self.feed_to(self.at(path.start, depth))
            for step in path.steps:
                if step.centre is None:
                    self.feed_to(self.at(step.to))
                else:
                    self.arc(step)
        self.rapid(self.at((self.pos[self.frame.plane.first] - self.centre[0],
                            self.pos[self.frame.plane.second] - self.centre[1]), r_level))
        self.rapid(self.at((0.0, 0.0)))
        self.it.pos = self.pos
