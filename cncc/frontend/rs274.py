"""Handlers of the RS274/NGC operations that LinuxCNC, grbl and SERIES 8 share.

Registered in :data:`cncc.frontend.ops.HANDLERS` under their own op names, so the
Fanuc-family meaning of a code (``data_input`` for SYNTEC's G10, ``home`` for G28
through the machine's reference) stays untouched:

- ``exact_path_mode`` (LinuxCNC/grbl G61), ``continuous_tolerance`` (G64 P Q),
  ``motion_off`` (G80 as motion-mode cancel);
- ``arc_absolute`` / ``arc_incremental`` (G90.1 / G91.1 arc centre modes);
- ``length_dynamic`` (G43.1: the axis words are the offset);
- ``set_origin_clear`` / ``set_origin_suspend`` / ``set_origin_restore`` (G92.1/.2/.3);
- ``data_input_rs274`` (G10 L1/L2/L10/L11/L20 with LinuxCNC's meaning);
- ``home_stored`` / ``home_stored2`` / ``store_home`` / ``store_home2`` (G28/G30 to a
  stored position, G28.1/G30.1 storing it);
- ``inverse_time`` (G93: F is 1/minutes, resolved to a path feed per block).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace
from typing import TYPE_CHECKING

from cncc import diagnostics as dg
from cncc.dialects import CodeDef
from cncc.frontend import ops
from cncc.frontend.ops import AXES, handler, target
from cncc.frontend.rs274_state import Rs274State as Rs274State  # re-exported
from cncc.frontend.rs274_state import state as state  # re-exported
from cncc.ir import (
    ZERO6,
    FeedMode,
    FeedRate,
    Origin,
    OriginKind,
    PathMode,
    Rapid,
    SetCutterComp,
    SetFeedMode,
    SetG92Offset,
    SetPathMode,
    SetToolLength,
    Vec6,
)

if TYPE_CHECKING:
    from cncc.frontend.interp import BlockContext, Interpreter


def _vec(values: list[float]) -> Vec6:
    return (values[0], values[1], values[2], values[3], values[4], values[5])


# ---- path modes ------------------------------------------------------------------------------
def _set_path(it: Interpreter, ctx: BlockContext, mode: PathMode, tol_mm: float | None,
              naive_mm: float | None = None) -> None:
    """Set the path mode; like LinuxCNC, report it on every G61/G61.1/G64 (changed or not)."""
    new = it.intern_motion(replace(it.modal.path, mode=mode, blend_tolerance_mm=tol_mm))
    it.modal = it.modal.with_(path=new)
    continuous = mode is PathMode.CONTINUOUS
    state(it).naive_mm = naive_mm or 0.0
    ctx.out.append(SetPathMode(ctx.span, it.frame, mode, (tol_mm or 0.0) if continuous else 0.0,
                               naive_mm if continuous else None))


@handler("exact_path_mode")
def _g61(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    _set_path(it, ctx, PathMode.EXACT_PATH, None)


@handler("exact_stop_mode_rs274")
def _g61_1(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    _set_path(it, ctx, PathMode.EXACT_STOP, None)


@handler("continuous_tolerance")
def _g64(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    """G64 P (blend tolerance) Q (naive-CAM tolerance, defaults to P)."""
    pw, qw = ctx.words.get("P"), ctx.words.get("Q")
    tol = it.reader.length_mm(pw) if pw is not None else None
    naive = it.reader.length_mm(qw) if qw is not None else tol
    for w, v in ((pw, tol), (qw, naive)):
        if w is not None and v is not None and v < 0:
            it.emit_error(dg.NUMBER_RANGE, it.word_span(w), f"G64 {w.letter} must not be negative")
            return
    _set_path(it, ctx, PathMode.CONTINUOUS, tol, naive or 0.0)


@handler("motion_off")
def _g80(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    it.modal = it.modal.with_(motion="none", cycle="")


def _no_motion(it: Interpreter, ctx: BlockContext, end: Vec6) -> None:
    it.emit_error(dg.CONTROLLER_REJECTS, ctx.span, "axis words with no motion mode in force (G80)")


ops.MOTIONS.setdefault("none", _no_motion)


# ---- arc centre mode (a block hook rewrites absolute I/J/K as offsets) -----------------------
@handler("arc_absolute", "arc_incremental")
def _arc_mode(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    state(it).arc_absolute = c.op == "arc_absolute"


def _absolute_centres(it: Interpreter, ctx: BlockContext) -> None:
    for c in ctx.codes:  # G90.1/G91.1 in this block apply before its motion
        if c.op in ("arc_absolute", "arc_incremental"):
            state(it).arc_absolute = c.op == "arc_absolute"
    st = it.rs274
    motion = next((c.op for c in ctx.codes if c.group == "motion"), it.modal.motion)
    if st is None or not st.arc_absolute or motion not in ("arc_cw", "arc_ccw"):
        return
    k = it.frame.units.mm_per_unit
    for letter, axis in (("I", 0), ("J", 1), ("K", 2)):
        w = ctx.words.get(letter)
        if w is not None:
            ctx.words[letter] = replace(w, value=w.value - it.pos[axis] / k, point=True)


ops.BLOCK_HOOKS.append(_absolute_centres)


# ---- tool length -------------------------------------------------------------------------------
def shift_z(it: Interpreter, old_mm: float) -> None:
    """LinuxCNC applies a tool length offset without moving: the program Z of the unmoved
    tool changes by the change of the offset."""
    d = it.frame.tool_length_mm - old_mm
    if d:
        p = it.pos
        it.pos = (p[0], p[1], p[2] - d, p[3], p[4], p[5])


@handler("length_dynamic")
def _g43_1(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    ctx.axis_used = True
    zw = ctx.words.get("Z")
    value = it.reader.length_mm(zw) if zw is not None else 0.0
    old = it.frame.tool_length_mm
    if value != old:
        it.set_frame(replace(it.frame, tool_length_mm=value, tool_length_index=0))
        ctx.out.append(SetToolLength(ctx.span, it.frame, value))
        shift_z(it, old)  # the Z word is the offset, not a move


# ---- G41.1 / G42.1: cutter compensation with the diameter in D --------------------------------
@handler("comp_left_dynamic", "comp_right_dynamic")
def _g41_1(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    from cncc.ir import CompSide

    dw = ctx.words.get("D")
    if dw is None:
        it.emit_error(dg.TRANSFORM_WORDS, ctx.span, f"{c.name} needs the tool diameter D")
        return
    side = CompSide.LEFT if (c.op == "comp_left_dynamic") == (dw.value >= 0) else CompSide.RIGHT  # D < 0 swaps
    radius = abs(it.reader.length_mm(dw)) / 2.0
    f = it.frame
    if (side, radius) != (f.comp_side, f.comp_radius_mm):
        it.set_frame(replace(f, comp_side=side, comp_radius_mm=radius, comp_index=0))
        ctx.out.append(SetCutterComp(ctx.span, it.frame, side))


# ---- G92.1 / G92.2 / G92.3 -------------------------------------------------------------------
def _set_g92(it: Interpreter, ctx: BlockContext, shift: Vec6) -> None:
    """Set the G92 offset; like LinuxCNC, report it on every G92/G52/G92.x (changed or not)."""
    if shift != it.frame.g92_offset_mm:
        it.set_frame(replace(it.frame, g92_offset_mm=shift))
    ctx.out.append(SetG92Offset(ctx.span, it.frame, shift))


@handler("set_origin_clear", "set_origin_suspend", "set_origin_restore")
def _g92_x(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    st = state(it)
    st.g92_applied = c.op == "set_origin_restore"
    if c.op == "set_origin_restore":
        _set_g92(it, ctx, st.g92_saved_mm)
        return
    if c.op == "set_origin_clear":
        st.g92_saved_mm = ZERO6
    _set_g92(it, ctx, ZERO6)


@handler("set_origin_rs274")
def _g92(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    """G92 as LinuxCNC has it: the shift is remembered in the parameters for G92.3."""
    _shift_named_axes(it, ctx, lambda i, old, value: old + it.pos[i] - value)


@handler("local_offset_rs274")
def _g52(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    """G52 as LinuxCNC has it: the given axes' G92 offsets are set to the words (no stacking)."""
    _shift_named_axes(it, ctx, lambda i, old, value: value)


def _shift_named_axes(it: Interpreter, ctx: BlockContext, shifted: Callable[[int, float, float], float]) -> None:
    """The G92 offset with each named axis ``i`` replaced by ``shifted(i, old offset, word value)``,
    remembered for G92.3 and set."""
    ctx.axis_used = True
    shift = list(it.frame.g92_offset_mm)
    for i, letter in enumerate(AXES):
        w = ctx.words.get(letter)
        if w is not None:
            shift[i] = shifted(i, shift[i], it.reader.axis_value(w))
    state(it).g92_saved_mm = _vec(shift)
    state(it).g92_applied = True
    _set_g92(it, ctx, _vec(shift))


# ---- G10 with LinuxCNC's tables --------------------------------------------------------------
@handler("data_input_rs274")
def _g10(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    from cncc.frontend.rs274_g10 import run_g10

    ctx.axis_used = True
    run_g10(it, ctx, c)


# ---- G28 / G30 to a stored position --------------------------------------------------------
def _stored(it: Interpreter, which: int) -> Vec6:
    st = state(it)
    got = st.stored_mm.get(which)
    if got is not None:
        return got
    refs = it.options.reference_mm
    return refs[which - 1] if which - 1 < len(refs) else refs[0]


@handler("home_stored", "home_stored2")
def _g28(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    from cncc.frontend.linuxcnc.placement import home_position
    from cncc.frontend.rs274_g10 import rotation_deg

    ctx.axis_used = True
    which = 1 if c.op == "home_stored" else 2
    named = [i for i, k in enumerate(AXES) if k in ctx.words]
    only_named = bool(it.dialect.option("home_named_axes_only", False))
    if named or only_named:  # LinuxCNC makes the intermediate move even to where the tool is
        mid = target(it, ctx) if named else it.pos
        ctx.out.append(Rapid(ctx.span, it.frame, it.pos, mid, it.modal.path, Origin(OriginKind.HOME, c.name)))
        it.pos = mid
    home = home_position(it.frame, rotation_deg(it, it.frame.work_index), _stored(it, which))
    if only_named and named:  # LinuxCNC: only the named axes go home
        home = _vec([home[i] if i in named else it.pos[i] for i in range(6)])
    end = home
    ctx.out.append(Rapid(ctx.span, it.frame, it.pos, end, it.modal.path, Origin(OriginKind.REFERENCE, c.name)))
    it.pos = end


@handler("store_home", "store_home2")
def _g28_1(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    ctx.axis_used = True
    off = it.frame.total_offset_mm
    tool = it.frame.tool_length_mm
    machine = _vec([it.pos[i] + off[i] + (tool if i == 2 else 0.0) for i in range(6)])
    if state(it).rotation_deg.get(it.frame.work_index):  # XY: the program point placed by the rotated system
        from cncc.frontend.rs274_g10 import machine_xy

        xy = machine_xy(it)
        machine = (xy[0], xy[1], machine[2], machine[3], machine[4], machine[5])
    state(it).stored_mm[1 if c.op == "store_home" else 2] = machine


# ---- G93 inverse time --------------------------------------------------------------------------
@handler("inverse_time")
def _g93(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    st = state(it)
    if not st.inverse_time:
        st.inverse_time = True
        it.modal = it.modal.with_(per_rev=False, path=it.intern_motion(replace(it.modal.path, inverse_time=True)))
        ctx.out.append(SetFeedMode(ctx.span, it.frame, FeedMode.INVERSE_TIME))


@handler("feed_per_min_rs274", "feed_per_rev_rs274")
def _g94(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    st = state(it)
    per_rev = c.op == "feed_per_rev_rs274"
    if st.inverse_time or per_rev != it.modal.per_rev:
        st.inverse_time = False
        it.modal = it.modal.with_(per_rev=per_rev, path=it.intern_motion(replace(it.modal.path,
                                                                                   inverse_time=False)))
        ctx.out.append(SetFeedMode(ctx.span, it.frame, FeedMode.PER_REV if per_rev else FeedMode.PER_MIN))


def _inverse_time_feed(it: Interpreter, ctx: BlockContext) -> None:
    """In G93 the block's F (1/min) becomes the path feed length x F for this block."""
    st = it.rs274
    motion = next((c.op for c in ctx.codes if c.group == "motion"), it.modal.motion)
    if st is None or not st.inverse_time or motion not in ("linear", "arc_cw", "arc_ccw"):
        return
    if not any(k in ctx.words for k in AXES):
        return
    fw = ctx.words.get("F")
    if fw is None or fw.value <= 0:
        it.emit_error(dg.NO_FEED, ctx.span, "in inverse time feed mode (G93) every feed move needs its own F")
        it.modal = it.modal.with_(feed=None)
        return
    end = target(it, ctx)
    length_mm = _path_length_mm(it, ctx, end, motion)
    feed = fw.value * length_mm / it.frame.units.mm_per_unit
    it.modal = it.modal.with_(feed=feed)
    ctx.out[:] = [FeedRate(c.span, c.frame, feed * it.frame.units.mm_per_unit) if isinstance(c, FeedRate) else c
                  for c in ctx.out]


def _path_length_mm(it: Interpreter, ctx: BlockContext, end: Vec6, motion: str) -> float:
    from cncc.frontend import arcs

    start = it.pos
    if motion == "linear":
        chord = math.dist(start[:3], end[:3])
        return chord if chord > 0 else math.dist(start[3:], end[3:])
    p = it.frame.plane
    cw = motion == "arc_cw"
    rw = ctx.words.get("R")
    if rw is not None:
        centre, _ = arcs.center_from_radius(start, end, p, it.reader.length_mm(rw), cw, 1e-3)
    else:
        names = "IJK"
        o1, o2 = ctx.words.get(names[p.first]), ctx.words.get(names[p.second])
        centre = arcs.center_from_offsets(start, p, it.reader.length_mm(o1) if o1 else 0.0,
                                          it.reader.length_mm(o2) if o2 else 0.0)
    i, j = p.first, p.second
    r = math.hypot(start[i] - centre[i], start[j] - centre[j])
    a0 = math.atan2(start[j] - centre[j], start[i] - centre[i])
    a1 = math.atan2(end[j] - centre[j], end[i] - centre[i])
    sweep = ((a0 - a1) if cw else (a1 - a0)) % (2 * math.pi)
    if sweep <= 1e-12:
        sweep = 2 * math.pi
    return math.hypot(r * sweep, end[p.normal] - start[p.normal])


ops.BLOCK_HOOKS.append(_inverse_time_feed)

