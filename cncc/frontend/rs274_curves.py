"""LinuxCNC's splines: ``G5`` cubic, ``G5.1`` quadratic, ``G5.2``/``G5.3`` NURBS.

Each curve becomes, in the IR, a ``NurbsFeed(points, order, n)`` marker
followed by the ``n`` arcs and lines of LinuxCNC's biarc approximation
(:mod:`cncc.frontend.nurbs`), all with ``origin`` the code as programmed.  The canon
backend prints the marker as LinuxCNC's ``NURBS_FEED(points, ...)`` when the
dialect's ``[canon]`` has that call (and skips the segments), or the segments.

- ``G5 I J P Q X Y``: control points start, start + (I, J), end + (P, Q), end.  Without
  I/J the start tangent continues the previous G5: (I, J) = -(P, Q) of that G5.
- ``G5.1 I J X Y``: control points start, start + (I, J), end.
- ``G5.2 X Y P L`` opens a NURBS whose first control point is the current position
  (weight P when the line has no X/Y, else 1); every following line ``X Y P`` adds a
  point of weight P > 0; L sets the order (default 3).  ``G5.3`` draws it.
Errors use LinuxCNC's texts (the dialect's ``[errors]``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from cncc import diagnostics as dg
from cncc.dialects import CodeDef
from cncc.frontend import nurbs, ops
from cncc.frontend.controller_errors import controller_error, reject
from cncc.ir import Arc, CompSide, Linear, NurbsFeed, Origin, OriginKind, Plane, Vec6

if TYPE_CHECKING:
    from cncc.frontend.interp import BlockContext, Interpreter

_OTHER_AXES = "ZABC"


# ---- G5 / G5.1 ------------------------------------------------------------------------------
@ops.handler("cubic_spline", "quadratic_spline")
def _select_spline(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    it.modal = it.modal.with_(motion=c.op, cycle="")


def _spline_checks(it: Interpreter, ctx: BlockContext) -> bool:
    if it.frame.comp_side is not CompSide.OFF:
        reject(it, ctx.span, "spline_comp", "Cannot convert spline with cutter radius compensation")
    elif it.frame.plane is not Plane.XY:
        reject(it, ctx.span, "spline_plane", "Splines must be in the XY plane")
    elif any(k in ctx.words for k in _OTHER_AXES):
        reject(it, ctx.span, "spline_axes", "Splines may not have motion in Z, A, B, or C")
    elif not it.modal.feed:
        reject(it, ctx.span, "nurbs_zero_feed", "Cannot make a NURBS with 0 feedrate")
    else:
        return True
    return False


def _offset(it: Interpreter, ctx: BlockContext, a: str, b: str) -> tuple[float, float] | None:
    wa, wb = ctx.words.get(a), ctx.words.get(b)
    if wa is None or wb is None:
        return None
    return it.reader.length_mm(wa), it.reader.length_mm(wb)


def _cubic(it: Interpreter, ctx: BlockContext, end: Vec6) -> None:
    from cncc.frontend.rs274 import state

    if not _spline_checks(it, ctx):
        return
    pq = _offset(it, ctx, "P", "Q")
    if pq is None:
        reject(it, ctx.span, "g5_pq", "Must specify both P and Q with G5")
        return
    ij = _offset(it, ctx, "I", "J")
    if ij is None and ("I" in ctx.words or "J" in ctx.words):
        reject(it, ctx.span, "g5_ij", "Must specify both I and J, or neither")
        return
    st = state(it)
    if ij is None:
        ij = (-st.g5_pq_mm[0], -st.g5_pq_mm[1])
    st.g5_pq_mm = pq
    x0, y0 = it.pos[0], it.pos[1]
    cps = [(x0, y0, 1.0), (x0 + ij[0], y0 + ij[1], 1.0), (end[0] + pq[0], end[1] + pq[1], 1.0), (end[0], end[1], 1.0)]
    _draw(it, ctx, cps, 4, "G5")


def _quadratic(it: Interpreter, ctx: BlockContext, end: Vec6) -> None:
    if not _spline_checks(it, ctx):
        return
    ij = _offset(it, ctx, "I", "J")
    if ij is None:
        reject(it, ctx.span, "g5_1_ij", "Must specify both I and J with G5.1")
        return
    x0, y0 = it.pos[0], it.pos[1]
    _draw(it, ctx, [(x0, y0, 1.0), (x0 + ij[0], y0 + ij[1], 1.0), (end[0], end[1], 1.0)], 3, "G5.1")


def _draw(it: Interpreter, ctx: BlockContext, cps: list[nurbs.CtrlPoint], order: int, code: str) -> None:
    """Append the marker and the biarcs of the curve; the tool ends at the last control point."""
    feed = ops.feed_mm_min(it, ctx)
    if feed is None:
        return
    motion = ops.block_motion(it, ctx)
    segs = nurbs.biarcs(cps, order)
    ctx.out.append(NurbsFeed(ctx.span, it.frame, len(cps), order, len(segs)))
    pos, origin = it.pos, Origin(OriginKind.CURVE, code)
    for s in segs:
        end: Vec6 = (s.end[0], s.end[1], pos[2], pos[3], pos[4], pos[5])
        if s.center is None:
            ctx.out.append(Linear(ctx.span, it.frame, pos, end, feed, motion, origin))
        else:
            centre: Vec6 = (s.center[0], s.center[1], pos[2], pos[3], pos[4], pos[5])
            ctx.out.append(Arc(ctx.span, it.frame, pos, end, centre, 1 if s.ccw else -1, Plane.XY, feed, motion,
                               origin))
        pos = end
    last = cps[-1]
    it.pos = (last[0], last[1], pos[2], pos[3], pos[4], pos[5])


# ---- G5.2 / G5.3 ----------------------------------------------------------------------------
@ops.handler("nurbs_begin")
def _nurbs_begin(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    from cncc.frontend.rs274 import state

    st = state(it)
    if it.modal.motion != "nurbs_begin" or not st.nurbs:
        has_xy = "X" in ctx.words or "Y" in ctx.words
        pw = ctx.words.get("P")
        weight = pw.value if pw is not None and not has_xy else 1.0
        st.nurbs = [(it.pos[0], it.pos[1], weight)]
        st.nurbs_order = 3
    it.modal = it.modal.with_(motion="nurbs_begin", cycle="")
    lw = ctx.words.get("L")
    if lw is not None:
        st.nurbs_order = round(lw.value)
    if not any(k in ctx.words for k in "XYZABC"):
        ctx.axis_used = True


def _nurbs_point(it: Interpreter, ctx: BlockContext, end: Vec6) -> None:
    from cncc.frontend.rs274 import state

    st = state(it)
    if ("X" in ctx.words) != ("Y" in ctx.words) or any(k in ctx.words for k in _OTHER_AXES):
        reject(it, ctx.span, "nurbs_xy", "You must specify both X and Y coordinates for Control Points")
        return
    if not st.nurbs:  # the mode was entered with no G5.2 line of its own
        st.nurbs, st.nurbs_order = [(it.pos[0], it.pos[1], 1.0)], 3
    lw = ctx.words.get("L")
    if lw is not None:
        st.nurbs_order = round(lw.value)
    pw = ctx.words.get("P")
    g5_2_line = any(c.op == "nurbs_begin" for c in ctx.codes)
    weight = pw.value if pw is not None else (1.0 if g5_2_line else 0.0)
    if weight <= 0:
        reject(it, ctx.span, "nurbs_weight", "Must specify positive weight P for every Control Point")
        return
    st.nurbs.append((end[0], end[1], weight))


@ops.handler("nurbs_end")
def _nurbs_end(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    from cncc.frontend.rs274 import state

    st = state(it)
    ctx.axis_used = True
    if it.modal.motion != "nurbs_begin" or len(st.nurbs) < 1:
        reject(it, ctx.span, "nurbs_end_without_begin", "Cannot use G5.3 without G5.2 first")
        return
    cps, order = st.nurbs, st.nurbs_order
    st.nurbs = []
    it.modal = it.modal.with_(motion="none", cycle="")
    if len(cps) < order:
        text = controller_error(it, "nurbs_order", "You must specify a number of control points at least equal "
                                                   "to the order L = {0}")
        it.emit_error(dg.CONTROLLER_REJECTS, ctx.span, text.format(order))
        return
    if not it.modal.feed:
        reject(it, ctx.span, "nurbs_zero_feed", "Cannot make a NURBS with 0 feedrate")
        return
    _draw(it, ctx, cps, order, "G5.2")


ops.MOTIONS["cubic_spline"] = _cubic
ops.MOTIONS["quadratic_spline"] = _quadratic
ops.MOTIONS["nurbs_begin"] = _nurbs_point
