"""Handlers of the SERIES 8 codes that have no counterpart in the shared op table.

* ``sine_loop`` G06, ``corner_insert`` G10 (the corner itself: :mod:`.corners`);
* ``linear_sharp`` / ``arc_cw_sharp`` / ``arc_ccw_sharp`` G21-G23 (exact stop);
* ``rotate_s8`` / ``scale_s8`` and their cancels G55-G58, about program zero;
* ``absolute_once`` / ``incremental_once`` / ``machine_once`` G67-G69;
* ``vendor_cycle`` (G34-G36, G43, G49-G51), ``aux_s8`` (M58, M59, M73, M74);

and the block hook that runs before the codes of a SERIES 8 block: the G21-G23 exact
stop, the two forms of G92 (A-01), G80 after G87 (A-41), F carried over in G93; and
a wrapper of G41/G42 for the side (A-04).
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import TYPE_CHECKING

from cncc import diagnostics as dg
from cncc.dialects import CodeDef
from cncc.frontend import ops, rs274
from cncc.frontend.ops import target
from cncc.frontend.series8 import state
from cncc.frontend.series8.layer import LAYER
from cncc.frontend.syntax import Word
from cncc.ir import (
    Aux,
    Dwell,
    FeedRate,
    Frame,
    Linear,
    Origin,
    OriginKind,
    SetCssReference,
    SetRotation,
    SetScaling,
    Vec6,
)
from cncc.ir.frame import Rotation, Scaling

if TYPE_CHECKING:
    from cncc.frontend.interp import BlockContext, Interpreter

_SHARP = {"linear_sharp": "linear", "arc_cw_sharp": "arc_cw", "arc_ccw_sharp": "arc_ccw"}
_ONCE = ("absolute_once", "incremental_once", "machine_once")
for _op in _ONCE:
    LAYER.set_order(_op, 82)  # after G90/G91 in the same block


def _state(it: Interpreter) -> state.S8State:
    st = state.get(it)
    assert st is not None, "a SERIES 8 code outside the SERIES 8 front end"
    return st


# ---- G04 ------------------------------------------------------------------------------------
def _dwell_of(inner: ops.Handler) -> ops.Handler:
    def dwell(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
        st = state.get(it)
        if st is None:
            inner(it, ctx, c)
        else:
            _dwell(it, ctx, c, st)

    return dwell


def _dwell(it: Interpreter, ctx: BlockContext, c: CodeDef, st: state.S8State) -> None:
    """G04 X or F seconds; the hook has taken F out of the block so it is not a feed (A-40)."""
    ctx.axis_used = True
    xw, fw = ctx.words.pop("X", None), st.dwell_f
    st.dwell_f = None
    moving = [a for a in "YZABC" if a in ctx.words]
    if moving:  # the block's axis words are the dwell's: never drop a move silently
        it.emit_error(dg.DWELL_WITH_MOTION, ctx.span, f"{c.name} with axis words ({' '.join(moving)}): put the move "
                                                       "in a block of its own (neither is run)")
        return
    if xw is not None and fw is not None:
        it.emit_error(dg.BAD_DWELL, it.word_span(fw), f"{c.name} takes the time in X or in F, not both")
        return
    w = xw if xw is not None else fw
    if w is None:
        it.emit_error(dg.BAD_DWELL, ctx.span, f"{c.name} needs a time in seconds (X or F)")
        return
    if w.value < 0:
        it.emit_error(dg.BAD_DWELL, it.word_span(w), "dwell time must not be negative")
        return
    seconds = w.value
    if it.modal.per_rev and state.option(it, "g04_revolutions_in_g95", False):
        if it.modal.spindle_rpm <= 0:
            it.emit_error(dg.BAD_DWELL, it.word_span(w), f"{c.name} in revolutions needs a spindle speed")
            return
        seconds = 60.0 * w.value / it.modal.spindle_rpm
    ctx.out.append(Dwell(ctx.span, it.frame, seconds))


# ---- G06 ------------------------------------------------------------------------------------
@LAYER.handler("sine_loop")
def _sine_loop(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    """S -> E -> S ``g06_cycles`` times; each stroke at the mean speed 2F/pi of p(t) = S + (E-S)(1-cos)/2."""
    ctx.axis_used = True
    others = [k for k in "ZABC" if k in ctx.words]
    if others:
        it.emit_error(dg.TRANSFORM_WORDS, ctx.span, f"{c.name} moves X and Y only (not {''.join(others)})")
        return
    end = target(it, ctx)
    feed = ops.feed_mm_min(it, ctx)
    if feed is None:
        return
    st = _state(it)
    cycles = int(state.option(it, "g06_cycles", 1))
    if not st.g06_warned:
        st.g06_warned = True
        it.sink.emit(dg.ASSUMED, ctx.span, f"{c.name} loops until the PMI variable @RUNG6 goes false; cncc runs "
                                           f"{cycles} loop(s) (option g06_cycles, spec A-07)")
    start = it.pos
    mean = 2.0 * feed / math.pi
    motion, origin = ops.block_motion(it, ctx), Origin(OriginKind.CODE, c.name)
    for _ in range(cycles):
        ctx.out.append(Linear(ctx.span, it.frame, start, end, mean, motion, origin))
        ctx.out.append(Linear(ctx.span, it.frame, end, start, mean, motion, origin))
    st.moved = True


# ---- G10 ------------------------------------------------------------------------------------
@LAYER.handler("corner_insert")
def _corner(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    rw, lw = ctx.words.get("R"), ctx.words.get("L")
    if (rw is None) == (lw is None):
        it.emit_error(dg.CORNER_INSERT, ctx.span, f"{c.name} takes a radius R or a chamfer L (one of them)")
        return
    w = rw if rw is not None else lw
    assert w is not None
    size = it.reader.length_mm(w)
    if size <= 0:
        it.emit_error(dg.CORNER_INSERT, it.word_span(w), f"{c.name} {w.letter} must be positive")
        return
    _state(it).corner = (w.letter, size, ctx.span)


# ---- G21-G23 --------------------------------------------------------------------------------
@LAYER.handler(*_SHARP)
def _sharp(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    it.modal = it.modal.with_(motion=_SHARP[c.op], cycle="")
    _state(it).sharp = True


# ---- G55-G58 --------------------------------------------------------------------------------
def _plane_map(frame: Frame, p: Vec6, inverse: bool) -> Vec6:
    """``p`` through the frame's scaling and rotation about program zero (or back)."""
    i, j = frame.plane.first, frame.plane.second
    k = frame.scaling.factors[i] if frame.scaling is not None else 1.0
    a = math.radians(frame.rotation.angle_deg) if frame.rotation is not None else 0.0
    x, y = p[i], p[j]
    if inverse:
        a, k = -a, 1.0 / k
    q = list(p)
    q[i] = k * (x * math.cos(a) - y * math.sin(a))
    q[j] = k * (x * math.sin(a) + y * math.cos(a))
    return (q[0], q[1], q[2], q[3], q[4], q[5])


def _switch(it: Interpreter, ctx: BlockContext, frame: Frame, scaling: bool) -> None:
    """New transform records; semantics B keeps the actual point (A-13), A the programmed one."""
    if state.option(it, "rotation_unprogrammed_axes", "last_programmed") == "current_position":
        it.pos = _plane_map(frame, _plane_map(it.frame, it.pos, False), True)
    it.set_frame(frame)
    ctx.out.append(SetScaling(ctx.span, it.frame, frame.scaling) if scaling else
                   SetRotation(ctx.span, it.frame, frame.rotation))


@LAYER.handler("rotate_s8")
def _rotate(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    rw = ctx.words.get("R")
    if rw is None:
        it.emit_error(dg.TRANSFORM_WORDS, ctx.span, f"{c.name} needs the angle R (degrees)")
        return
    rot = Rotation(it.frame.plane, (0.0, 0.0), it.reader.angle_deg(rw))
    _switch(it, ctx, replace(it.frame, rotation=rot), False)


@LAYER.handler("rotate_off_s8")
def _rotate_off(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    if it.frame.rotation is not None:
        _switch(it, ctx, replace(it.frame, rotation=None), False)


@LAYER.handler("scale_s8")
def _scale(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    rw = ctx.words.get("R")
    if rw is None:
        it.emit_error(dg.TRANSFORM_WORDS, ctx.span, f"{c.name} needs the scale factor R")
        return
    k = rw.value
    if k == 0 or (k < 0 and state.option(it, "scale_nonpositive", "error") != "allow"):
        it.emit_error(dg.TRANSFORM_WORDS, it.word_span(rw), f"{c.name} R{k:g}: the factor must be positive "
                                                             "(spec A-14; option scale_nonpositive)")
        return
    plane = it.frame.plane
    factors = [1.0, 1.0, 1.0]
    factors[plane.first] = factors[plane.second] = k
    scaling = Scaling((0.0, 0.0, 0.0), (factors[0], factors[1], factors[2]))
    _switch(it, ctx, replace(it.frame, scaling=scaling), True)


@LAYER.handler("scale_off_s8")
def _scale_off(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    if it.frame.scaling is not None:
        _switch(it, ctx, replace(it.frame, scaling=None), True)


# ---- G67-G69 --------------------------------------------------------------------------------
@LAYER.handler(*_ONCE)
def _once(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    st = _state(it)
    if st.restore_incremental is None:
        st.restore_incremental = it.modal.incremental
    if c.op == "machine_once":
        ctx.block_flags.add("machine_coords")
        return
    it.modal = it.modal.with_(incremental=c.op == "incremental_once")


# ---- codes without words, M codes -----------------------------------------------------------
def vendor_gate(it: Interpreter, ctx: BlockContext, c: CodeDef, reading: str = "") -> bool:
    """A code the manual names without words: True when cncc expands it with its own reading
    (``vendor_cycles = "expand"`` and a ``reading`` to announce, once per code and program);
    otherwise the block is refused (``"error"``, E0255) or skipped with a warning (``"skip"``)."""
    ctx.axis_used = True
    mode = state.option(it, "vendor_cycles", "expand")
    text = f"{c.name} ({c.summary.split(';')[0].rstrip('.')}): the manual defines no words for it"
    if mode == "expand" and reading:
        st = _state(it)
        if c.name not in st.vendor_noted:
            st.vendor_noted.add(c.name)
            it.sink.emit(dg.ASSUMED, ctx.span, f"{text}; cncc reads {reading} (docs/dialects-notes.md; "
                                               'vendor_cycles = "error" refuses it, "skip" leaves it out)')
        return True
    if mode == "skip":
        it.sink.emit(dg.ASSUMED, ctx.span, f"{text}; the block is skipped (option vendor_cycles)")
    else:
        it.emit_error(dg.VENDOR_CYCLE, ctx.span, f"{text}; it needs a cycle macro")
    return False


@LAYER.handler("vendor_cycle")
def _vendor(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    vendor_gate(it, ctx, c)


@LAYER.handler("aux_s8")
def _aux(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    ctx.out.append(Aux(ctx.span, it.frame, c.tenths))


# ---- the block hook ---------------------------------------------------------------------------
def _hook(it: Interpreter, ctx: BlockContext) -> None:
    st = state.get(it)
    if st is None:
        return
    if "F" in ctx.words and any(cd.op == "dwell" for cd in ctx.codes):  # G04 F: a time, not a feed
        fw = st.dwell_f = ctx.words.pop("F")
        it.modal = it.modal.with_(feed=st.feed_before)
        ctx.out[:] = [c for c in ctx.out if not (isinstance(c, FeedRate) and c.span == it.word_span(fw))]
    for k, cd in enumerate(ctx.codes):
        if cd.group == "motion":
            st.sharp = cd.op in _SHARP
            if st.sharp:  # the shared motion ops run it; the exact stop is the block flag
                ctx.codes[k] = replace(cd, op=_SHARP[cd.op])
        elif cd.op == "set_origin":
            _preset(it, ctx, st, cd)
        elif cd.op == "cycle_off" and st.at_depth:
            st.at_depth = False
            it.sink.emit(dg.ASSUMED, ctx.span, f"{cd.name} after G87: the tool stays at depth (no automatic "
                                               "retract, spec A-41)")
    if st.sharp and any(a in ctx.words for a in ops.AXES):
        ctx.block_flags.add("exact_stop_once")
    _inverse_time(it, ctx, st)


def _inverse_time(it: Interpreter, ctx: BlockContext, st: state.S8State) -> None:
    """G93: the manual's example gives F in the G93 block and moves in the next, so F carries
    over to the following feed blocks unless ``g93_f_every_block`` asks for one per block (A-29)."""
    if not rs274.state(it).inverse_time:
        st.inverse_f = None
        return
    fw = ctx.words.get("F")
    if fw is not None:
        st.inverse_f = fw.value
        return
    motion = next((c.op for c in ctx.codes if c.group == "motion"), it.modal.motion)
    feed_move = motion in ("linear", "arc_cw", "arc_ccw") and any(a in ctx.words for a in ops.AXES)
    if st.inverse_f is None or state.option(it, "g93_f_every_block", False) or not feed_move:
        return
    ctx.words["F"] = Word("F", st.inverse_f, True, ctx.block.start, ctx.block.start + 1)
    ctx.out.append(FeedRate(ctx.span, it.frame, 0.0))  # the G93 hook sets the block's path feed


def _sided(inner: ops.Handler) -> ops.Handler:
    """G41/G42: the side the option picks (A-04), with one warning per program."""

    def comp(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
        st = state.get(it)
        if st is None or c.op not in ("comp_left", "comp_right"):
            inner(it, ctx, c)
            return
        swapped = bool(state.option(it, "crc_sides_swapped", False))
        if not st.comp_warned:
            st.comp_warned = True
            it.sink.emit(dg.SOURCE_INCONSISTENT, ctx.span,
                         f"the manual's index calls G41 right and G42 left of the path, its text and example the "
                         f"opposite; cncc takes {'G42' if swapped else 'G41'} as left (option crc_sides_swapped, "
                         "spec A-04)")
        if swapped:
            c = replace(c, op="comp_right" if c.op == "comp_left" else "comp_left")
        inner(it, ctx, c)

    return comp


def _preset(it: Interpreter, ctx: BlockContext, st: state.S8State, cd: CodeDef) -> None:
    """G92 X Y Z A presets program zero; G92 R S (lathe) sets the CSS radius and top speed (A-01)."""
    axes = [a for a in "XYZA" if a in ctx.words]
    css = [a for a in "RS" if a in ctx.words]
    if not css:
        return
    if cd.name != "G92" or axes:
        why = "G98 has no R/S form" if cd.name != "G92" else "a G92 block is either X Y Z A or R S"
        it.emit_error(dg.TRANSFORM_WORDS, ctx.span, f"{cd.name} {' '.join(axes + css)}: {why} (spec A-01)")
        for a in axes + css:
            ctx.words.pop(a)
        return
    rw = ctx.words.pop("R", None)
    if rw is not None:
        st.css_reference = (abs(it.reader.length_mm(rw)), it.pos[0])
        ctx.out.append(SetCssReference(ctx.span, it.frame, *st.css_reference))


LAYER.hook_first(_hook)
LAYER.wrap_handler("dwell", _dwell_of)
for _op in ("comp_left", "comp_right"):
    LAYER.wrap_handler(_op, _sided)
