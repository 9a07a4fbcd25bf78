"""Front-end handlers of the frame and compensation codes.

Consumes the blocks' words; produces frame changes (and ``SetMode`` records) that the
passes in :mod:`cncc.passes` apply later:

* G15/G16 polar coordinates (resolved here, see below), G50/G51 scaling and SZGH
  G36/G37, G50.1/G51.1 mirror and SZGH G11/G12, G68/G69 rotation;
* G40/G41/G42 cutter radius compensation with D, G43/G44/G49 tool length with H
  (a lone H or D word changes the value while the mode is on);
* G10 programmable data input (tool lengths, radii and wear; work offsets);
* SZGH G45-G48 one-block tool offsets, which lengthen or shorten the block's travel.

Polar coordinates are the one transform resolved in the front end: the radius and
angle words, their incremental forms and R-arcs between polar points need the
current point, which only the interpreter knows.  The frame still records the polar
mode (``Frame.polar``) for emitters.  Everything else stays a record on the frame and
the positions stay as programmed.  ``docs/frames.md`` explains the choices.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import TYPE_CHECKING

from cncc import diagnostics as dg
from cncc.dialects import CodeDef
from cncc.frontend.ops import AXES, BLOCK_HOOKS, handler
from cncc.frontend.polar import polar_target
from cncc.frontend.run_state import TransformState
from cncc.ir import CompSide, SetMode, Vec6
from cncc.ir.frame import Mirror, Polar, Rotation, Scaling

if TYPE_CHECKING:
    from cncc.frontend.interp import BlockContext, Interpreter
    from cncc.frontend.syntax import Word

_ARC_OPS = ("arc_cw", "arc_ccw")


def _state(it: Interpreter) -> TransformState:
    """The interpreter's transform record (mutable, owned by the interpreter)."""
    return it.transform


def _index(it: Interpreter, w: Word) -> int | None:
    if w.value < 0 or w.value != int(w.value):
        it.emit_error(dg.BAD_OFFSET_INDEX, it.word_span(w), f"{w.letter} must be a non-negative integer")
        return None
    return int(w.value)


def _table_value(it: Interpreter, ctx: BlockContext, table: dict[int, float], wear: dict[int, float],
                 index: int, letter: str) -> float:
    if index == 0:
        return 0.0
    if index not in table and index not in wear:
        from cncc.frontend.offset_notes import offset_missing

        offset_missing(it, ctx.span, letter, index)
    return table.get(index, 0.0) + wear.get(index, 0.0)


def radius_of(it: Interpreter, ctx: BlockContext, index: int) -> float:
    """Cutter radius of offset number ``index`` (geometry + wear, mm)."""
    return _table_value(it, ctx, it.options.tool_radii_mm, _state(it).radius_wear_mm, index, "D")


# ---- polar coordinates (G15/G16) ------------------------------------------------------
@handler("polar_on")
def _polar_on(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    plane = it.frame.plane
    i, j = plane.first, plane.second
    origin = (it.pos[i], it.pos[j]) if it.modal.incremental else (0.0, 0.0)
    st = _state(it)
    st.polar_radius_mm = math.hypot(it.pos[i] - origin[0], it.pos[j] - origin[1])
    st.polar_angle_deg = math.degrees(math.atan2(it.pos[j] - origin[1], it.pos[i] - origin[0]))
    it.set_frame(replace(it.frame, polar=Polar(plane, origin)))
    ctx.out.append(SetMode(ctx.span, it.frame, "polar", origin))


@handler("polar_off")
def _polar_off(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    if it.frame.polar is not None:
        it.set_frame(replace(it.frame, polar=None))
        ctx.out.append(SetMode(ctx.span, it.frame, "polar", None))


# ---- scaling (G50/G51, SZGH G36/G37) -------------------------------------------------------
def _swapped(it: Interpreter, c: CodeDef) -> bool:
    """SYNTEC A-01: with ``g50_is_cancel = false`` G50 scales and G51 cancels (the code list)."""
    return it.dialect.option("g50_is_cancel", True) is False and c.name in ("G50", "G51")


def _factor(it: Interpreter, w: Word) -> float:
    """A scale factor: without a decimal point, in units of ``scale_factor_unit`` (0.001)."""
    if w.point or it.dialect.decimal_rule != "liu":
        return w.value
    return w.value * float(it.dialect.option("scale_factor_unit", 0.001))


@handler("scale_on")
def _scale_on(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    if _swapped(it, c):
        _scale_cancel(it, ctx, c)
    else:
        _scale_apply(it, ctx, c)


def _scale_apply(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    ctx.axis_used = True
    rd = it.reader
    named = [k for k in range(3) if AXES[k] in ctx.words]
    center = tuple(rd.length_mm(ctx.words[AXES[k]]) if k in named else it.pos[k] for k in range(3))
    pw, rw = ctx.words.get("P"), ctx.words.get("R")
    per_axis = [ctx.words.get(a) for a in "IJK"]
    factors: tuple[float, ...]
    if pw is not None:
        factors = (_factor(it, pw),) * 3
    elif rw is not None:  # SZGH G36: R scales the named axes only
        f = _factor(it, rw)
        if it.dialect.option("scale_r_semantics", "multiply") == "divide" and f != 0.0:
            f = 1.0 / f
        axes = named or [0, 1, 2]
        factors = tuple(f if k in axes else 1.0 for k in range(3))
    elif any(w is not None for w in per_axis):
        factors = tuple(_factor(it, w) if w is not None else 1.0 for w in per_axis)
    else:
        it.emit_error(dg.TRANSFORM_WORDS, ctx.span, f"{c.name} needs a scale factor (P, or I/J/K per axis)")
        return
    if any(f == 0.0 for f in factors):
        it.emit_error(dg.TRANSFORM_WORDS, ctx.span, f"{c.name}: a scale factor of 0 collapses the axis")
        return
    scaling = Scaling((center[0], center[1], center[2]), (factors[0], factors[1], factors[2]))
    it.set_frame(replace(it.frame, scaling=scaling))
    ctx.out.append(SetMode(ctx.span, it.frame, "scaling", scaling))


@handler("scale_off")
def _scale_off(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    if _swapped(it, c):
        _scale_apply(it, ctx, c)
    else:
        _scale_cancel(it, ctx, c)


def _scale_cancel(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    if it.frame.scaling is not None:
        it.set_frame(replace(it.frame, scaling=None))
        ctx.out.append(SetMode(ctx.span, it.frame, "scaling", None))
    if c.name == "G50" and it.dialect.option("g50_cancels_mirror", False) and it.frame.mirror is not None:
        it.set_frame(replace(it.frame, mirror=None))  # SYNTEC A-48: the manual's screenshot shows it
        ctx.out.append(SetMode(ctx.span, it.frame, "mirror", None))


# ---- mirror (G50.1/G51.1, SZGH G11/G12) ----------------------------------------------------
@handler("mirror_on")
def _mirror_on(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    ctx.axis_used = True
    named = [k for k in range(3) if AXES[k] in ctx.words]
    if not named:
        it.emit_error(dg.TRANSFORM_WORDS, ctx.span, f"{c.name} needs the mirror axis position (X, Y or Z)")
        return
    center, axes = [0.0, 0.0, 0.0], [False, False, False]  # only the named axes (SZGH E002-18 N70)
    for k in named:  # the mirror line is always absolute (SYNTEC A-53)
        center[k] = it.reader.length_mm(ctx.words[AXES[k]])
        axes[k] = True
    mirror = Mirror((center[0], center[1], center[2]), (axes[0], axes[1], axes[2]))
    it.set_frame(replace(it.frame, mirror=mirror))
    ctx.out.append(SetMode(ctx.span, it.frame, "mirror", mirror))


@handler("mirror_off")
def _mirror_off(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    ctx.axis_used = True
    old = it.frame.mirror
    if old is None:
        return
    named = [k for k in range(3) if AXES[k] in ctx.words]
    axes = tuple(False if (not named or k in named) else old.axes[k] for k in range(3))
    mirror = Mirror(old.center_mm, (axes[0], axes[1], axes[2])) if any(axes) else None
    it.set_frame(replace(it.frame, mirror=mirror))
    ctx.out.append(SetMode(ctx.span, it.frame, "mirror", mirror))


# ---- rotation (G68/G69) ------------------------------------------------------------------
@handler("rotate_on")
def _rotate_on(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    ctx.axis_used = True
    plane = it.frame.plane
    i, j = plane.first, plane.second
    inc = it.modal.incremental
    rd = it.reader
    wi, wj = ctx.words.get(AXES[i]), ctx.words.get(AXES[j])
    if inc:  # "only effective in absolute": in G91 the centre is the current point
        center = (it.pos[i], it.pos[j])
    else:
        center = (rd.length_mm(wi) if wi is not None else it.pos[i], rd.length_mm(wj) if wj is not None else it.pos[j])
    rw = ctx.words.get("R")
    old = it.frame.rotation
    if rw is None:
        it.sink.emit(dg.TRANSFORM_DEFAULT, ctx.span, f"{c.name} without R: the rotation angle is 0")
        angle = 0.0
    else:
        angle = rd.value(rw, c.words.get("R", "angle"))
        if inc and old is not None:  # incremental angle: added to the rotation in force
            angle += old.angle_deg
    rotation = Rotation(plane, center, angle)
    it.set_frame(replace(it.frame, rotation=rotation))
    ctx.out.append(SetMode(ctx.span, it.frame, "rotation", rotation))


@handler("rotate_off")
def _rotate_off(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    if it.frame.rotation is not None:
        it.set_frame(replace(it.frame, rotation=None))
        ctx.out.append(SetMode(ctx.span, it.frame, "rotation", None))


# ---- cutter radius compensation (G40/G41/G42) -----------------------------------------------
def _arc_in_block(it: Interpreter, ctx: BlockContext) -> bool:
    if any(cd.op in _ARC_OPS for cd in ctx.codes):
        return True
    if any(cd.group == "motion" for cd in ctx.codes):
        return False
    return it.modal.motion in _ARC_OPS and any(a in ctx.words for a in AXES)


@handler("comp_left", "comp_right", "comp_off")
def _comp(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    if _arc_in_block(it, ctx):
        it.emit_error(dg.COMP_ON_ARC, ctx.span, f"{c.name} cannot be in a G02/G03 block; start and cancel "
                                                 "compensation with G00 or G01")
    st = _state(it)
    st.comp_op = c.op
    if c.op == "comp_off":
        if it.frame.comp_side is not CompSide.OFF:
            it.set_frame(replace(it.frame, comp_side=CompSide.OFF, comp_radius_mm=0.0))
            ctx.out.append(SetMode(ctx.span, it.frame, "cutter_comp", CompSide.OFF))
        return
    dw = ctx.words.get("D")
    index = it.frame.comp_index or st.d_index
    if dw is None and it.dialect.option("offset_default", "last") == "loaded_tool":
        index = it.modal.tool_loaded  # LinuxCNC: G41/G42 without D use the tool in the spindle
    if dw is not None:
        got = _index(it, dw)
        if got is None:
            return
        index = st.d_index = got
    elif index == 0 and it.dialect.option("comp_without_d_warning", True):
        it.sink.emit(dg.COMP_NO_OFFSET, ctx.span, f"{c.name} without an offset number D: the controller "
                                                   "compensates with radius 0 (program D)")
    _set_comp(it, ctx, c.op, index)


def _set_comp(it: Interpreter, ctx: BlockContext, op: str, index: int) -> None:
    radius = radius_of(it, ctx, index)
    side = CompSide.LEFT if op == "comp_left" else CompSide.RIGHT
    if radius < 0:  # a negative offset swaps the side
        side = CompSide.RIGHT if side is CompSide.LEFT else CompSide.LEFT
        radius = -radius
    f = it.frame
    if (side, radius, index) != (f.comp_side, f.comp_radius_mm, f.comp_index):
        it.set_frame(replace(f, comp_side=side, comp_radius_mm=radius, comp_index=index))
        ctx.out.append(SetMode(ctx.span, it.frame, "cutter_comp", side))


# ---- tool length (G43/G44/G49) ---------------------------------------------------------------
@handler("length_plus", "length_minus", "length_off")
def _length(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    st = _state(it)
    st.length_op = c.op
    index = it.frame.tool_length_index
    if it.dialect.option("offset_default", "last") == "loaded_tool":
        index = it.modal.tool_loaded  # LinuxCNC: G43 without H uses the tool in the spindle
    hw = ctx.words.get("H")
    if hw is not None:
        got = _index(it, hw)
        if got is None:
            return
        index = got
    _set_length(it, ctx, c.op, index)


def _set_length(it: Interpreter, ctx: BlockContext, op: str, index: int) -> None:
    if op == "length_off":
        value, index = 0.0, 0
    else:
        value = _table_value(it, ctx, it.options.tool_lengths_mm, _state(it).length_wear_mm, index, "H")
        if op == "length_minus":
            value = -value
    axis = it.frame.plane.normal if it.dialect.option("tool_length_type", "A") == "B" else 2
    f = it.frame
    if (value, index, axis) != (f.tool_length_mm, f.tool_length_index, f.tool_length_axis):
        it.set_frame(replace(f, tool_length_mm=value, tool_length_index=index, tool_length_axis=axis))
        ctx.out.append(SetMode(ctx.span, it.frame, "tool_length_offset", value))


def _lone_words(it: Interpreter, ctx: BlockContext) -> None:
    """H or D without G43/G44 or G41/G42 in the block: a new value for the mode in force."""
    groups = {cd.group for cd in ctx.codes}
    st = _state(it)
    hw = ctx.words.get("H")
    if hw is not None and "length_comp" not in groups and st.length_op != "length_off":
        index = _index(it, hw)
        if index is not None:
            _set_length(it, ctx, st.length_op if index else "length_off", index)
    dw = ctx.words.get("D")
    if dw is not None and "cutter_comp" not in groups:
        index = _index(it, dw)
        if index is not None:
            st.d_index = index
            if st.comp_op != "comp_off":
                _set_comp(it, ctx, st.comp_op, index)


BLOCK_HOOKS.append(_lone_words)


# ---- G10 programmable data input -------------------------------------------------------------
_TOOL_TABLES = {10: "length", 11: "length_wear", 12: "radius", 13: "radius_wear"}


@handler("data_input")
def _g10(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    ctx.axis_used = True
    lw, pw = ctx.words.get("L"), ctx.words.get("P")
    if lw is None or pw is None:
        it.emit_error(dg.TRANSFORM_WORDS, ctx.span, f"{c.name} needs L (which table) and P (which entry)")
        return
    table, entry = int(lw.value), _index(it, pw)
    if entry is None:
        return
    if table in _TOOL_TABLES:
        _g10_tool(it, ctx, c, _TOOL_TABLES[table], entry)
    elif table in (2, 20):
        _g10_work(it, ctx, c, entry if table == 2 else 6 + entry)
    else:
        it.emit_error(dg.DATA_INPUT, it.word_span(lw), f"{c.name} L{table}: cncc knows L2, L20 (work offsets) "
                                                          "and L10-L13 (tool data)")


def _g10_tool(it: Interpreter, ctx: BlockContext, c: CodeDef, table: str, entry: int) -> None:
    rw = ctx.words.get("R")
    if rw is None:
        it.emit_error(dg.TRANSFORM_WORDS, ctx.span, f"{c.name} needs the value R")
        return
    st = _state(it)
    target = {"length": it.options.tool_lengths_mm, "length_wear": st.length_wear_mm,
              "radius": it.options.tool_radii_mm, "radius_wear": st.radius_wear_mm}[table]
    value = it.reader.length_mm(rw)
    target[entry] = target.get(entry, 0.0) + value if it.modal.incremental else value
    ctx.out.append(SetMode(ctx.span, it.frame, "data_input", (table, entry, target[entry])))


def _g10_work(it: Interpreter, ctx: BlockContext, c: CodeDef, index: int) -> None:
    if not 1 <= index <= 15:
        it.emit_error(dg.DATA_INPUT, ctx.span, f"{c.name}: work coordinate system {index} does not exist (1-15)")
        return
    old = it.options.work_offsets_mm.get(index, (0.0,) * 6)
    vals = list(old)
    for k, letter in enumerate(AXES):
        w = ctx.words.get(letter)
        if w is not None:
            v = it.reader.axis_value(w)
            vals[k] = vals[k] + v if it.modal.incremental else v
    new: Vec6 = (vals[0], vals[1], vals[2], vals[3], vals[4], vals[5])
    it.options.work_offsets_mm[index] = new
    ctx.out.append(SetMode(ctx.span, it.frame, "work_table", (index, old, new)))  # translation writes it (G10)
    if it.frame.work_index == index and new != it.frame.work_offset_mm:
        it.set_frame(replace(it.frame, work_offset_mm=new))
        ctx.out.append(SetMode(ctx.span, it.frame, "g5x_offset", index))


# ---- SZGH G45-G48 tool offsets ---------------------------------------------------------------
_TOOL_OFFSET_FACTOR = {"offset_increase": 1.0, "offset_decrease": -1.0,
                       "offset_double_increase": 2.0, "offset_double_decrease": -2.0}


@handler(*_TOOL_OFFSET_FACTOR)
def _tool_offset(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    """Lengthen (G45, G47) or shorten (G46, G48) each named axis's travel by the D offset.

    A zero move counts as positive in G91 and does not move in G90; arc centre words
    grow or shrink with the radius (quarter and three-quarter circles).
    """
    if it.frame.comp_side is not CompSide.OFF:
        it.emit_error(dg.TOOL_OFFSET_IN_COMP, ctx.span, f"{c.name} is not allowed while G41/G42 is active")
        return
    st = _state(it)
    dw = ctx.words.get("D")
    if dw is not None:
        got = _index(it, dw)
        if got is None:
            return
        st.d_index = got
    amount = _TOOL_OFFSET_FACTOR[c.op] * radius_of(it, ctx, st.d_index)
    rd = it.reader
    inc = it.modal.incremental
    for k, letter in enumerate(AXES[:3]):
        w = ctx.words.get(letter)
        if w is None:
            continue
        v = rd.length_mm(w)
        delta = v if inc else v - it.pos[k]
        if delta == 0.0 and not inc:
            continue
        ctx.words[letter] = _word_mm(w, v + (amount if delta >= 0.0 else -amount), rd.mm_per_unit)
    for letter in "IJK":
        w = ctx.words.get(letter)
        if w is not None and w.value != 0.0:
            v = rd.length_mm(w)
            ctx.words[letter] = _word_mm(w, v + (amount if v > 0.0 else -amount), rd.mm_per_unit)


def _word_mm(w: Word, value_mm: float, mm_per_unit: float) -> Word:
    return replace(w, value=value_mm / mm_per_unit, point=True)


__all__ = ["polar_target", "radius_of"]
