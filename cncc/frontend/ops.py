"""Handlers of the canonical operations named in the dialect tables, and the block driver.

The handlers here register into :mod:`cncc.frontend.registry`'s ``HANDLERS`` and
``MOTIONS`` (re-exported here, with ``handler``, for the modules that add ops: canned
cycles, transforms, RS274 ...).  This module imports none of them:
:mod:`cncc.frontend.handler_tables` composes the core table from all of them.
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

from cncc import diagnostics as dg
from cncc.dialects import CodeDef
from cncc.frontend import arcs, catalogue
from cncc.frontend.controller_errors import controller_error
from cncc.frontend.polar import polar_target
from cncc.frontend.registry import (
    BLOCK_HOOKS,
    DEFAULT_ORDER,
    HANDLERS,
    MOTIONS,
    BlockHook,
    Handler,
    HandlerTable,
    Layer,
    MotionHandler,
    handler,
)
from cncc.ir import (
    MACHINE_ORIGIN,
    PROGRAMMED,
    Arc,
    Coolant,
    CoolantState,
    Dwell,
    FeedMode,
    FeedRate,
    Linear,
    Motion,
    Origin,
    OriginKind,
    PathMode,
    Plane,
    PresetG92,
    Rapid,
    SelectTool,
    SetFeedMode,
    SetG92Offset,
    SetLocalOffset,
    SetPathMode,
    SetPlane,
    SetUnits,
    SetWorkSystem,
    Spindle,
    SpindleSpeed,
    SpindleState,
    Stop,
    StopKind,
    ToolChange,
    Units,
    Vec6,
)
from cncc.ir.frame import NOT_HELD

if TYPE_CHECKING:
    from cncc.frontend.interp import BlockContext, Interpreter


AXES = "XYZABC"
AXES_OR_POLAR = "XYZABC@^"  # LinuxCNC's @ radius and ^ angle stand for X and Y (cncc/frontend/rs274_words.py)


# ---- block driver -----------------------------------------------------------------
M_ORDER = catalogue.M_ORDER  # M ops that run before the block's G codes (the op catalogue's)


def run_block(it: Interpreter, ctx: BlockContext) -> None:
    order = it.table.order
    gs = [c for c in ctx.codes if c.letter == "G"]
    ms = [c for c in ctx.codes if c.letter == "M"]
    early = [c for c in gs if order.get(c.op, DEFAULT_ORDER) < 20]
    for c in early:
        _dispatch(it, ctx, c)
    _feed_speed_tool(it, ctx)
    for hook in it.table.block_hooks:
        hook(it, ctx)
    for c in sorted((m for m in ms if m.op in M_ORDER), key=lambda m: M_ORDER[m.op]):
        _dispatch(it, ctx, c)
    for c in gs:
        if c not in early:
            _dispatch(it, ctx, c)
    if not ctx.axis_used and (any(k in ctx.words for k in AXES_OR_POLAR) or _full_circle(it, ctx)):
        _motion(it, ctx)
    elif ctx.axis_used and any(k in ctx.words for k in AXES):
        _note_taken_words(it, ctx, gs)
    for c in ms:
        if c.op not in M_ORDER:
            _dispatch(it, ctx, c)


AXIS_TAKERS = catalogue.AXIS_TAKERS  # ops that take the block's axis words (the op catalogue's)


def _note_taken_words(it: Interpreter, ctx: BlockContext, gs: list[CodeDef]) -> None:
    """``G92 X0 G01 Y5``: the axis words are G92's; say so rather than drop the G01's move silently."""
    motion = [c for c in gs if c.group == "motion"]
    takers = [c for c in gs if c.op in AXIS_TAKERS]
    if motion and takers:
        it.sink.emit(dg.AXIS_WORDS_TAKEN, ctx.span, f"the axis words belong to {takers[0].name}; {motion[0].name} "
                                                     "sets the motion mode but this block does not move")


def _full_circle(it: Interpreter, ctx: BlockContext) -> bool:
    """An arc block with only centre words (``G02 I10``) is a full circle."""
    return it.modal.motion in ("arc_cw", "arc_ccw") and not it.modal.cycle and any(
        k in ctx.words for k in "IJK")


def _dispatch(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    fn = it.table.handlers.get(c.op)
    if fn is None:
        it.emit_error(dg.NOT_SUPPORTED, ctx.span, f"{c.name} ({c.summary.rstrip('.')}) is not supported yet")
        if c.group not in ("non_modal",) and c.letter == "G":
            ctx.axis_used = True
        return
    fn(it, ctx, c)
    if c.letter == "G" and c.group not in ("non_modal", "hshp", "smoothing"):
        it.set_modal(c.group, c)


def _feed_speed_tool(it: Interpreter, ctx: BlockContext) -> None:
    w = ctx.words.get("F")
    if w is not None:
        if w.value < 0:
            it.emit_error(dg.NUMBER_RANGE, it.word_span(w), "F must not be negative")
        else:
            it.modal = it.modal.with_(feed=w.value)
            ctx.out.append(FeedRate(it.word_span(w), it.frame, w.value * it.frame.units.mm_per_unit,
                                    it.modal.per_rev))
    w = ctx.words.get("S")
    if w is not None and not any(c.op == "set_origin" for c in ctx.codes):
        if w.value < 0:
            it.emit_error(dg.NUMBER_RANGE, it.word_span(w), "S must not be negative")
        else:
            it.modal = it.modal.with_(spindle_rpm=w.value)
            ctx.out.append(SpindleSpeed(it.word_span(w), it.frame, w.value, it.modal.css))
    w = ctx.words.get("T")
    if w is not None:
        if w.value < 0 or w.value != int(w.value):
            it.emit_error(dg.NUMBER_RANGE, it.word_span(w), "T must be a non-negative integer")
        elif not_in_tool_table(it, int(w.value)):
            it.emit_error(dg.CONTROLLER_REJECTS, it.word_span(w), tool_not_found(it, int(w.value)))
        else:
            it.modal = it.modal.with_(tool_selected=int(w.value))
            ctx.out.append(SelectTool(it.word_span(w), it.frame, int(w.value)))


def not_in_tool_table(it: Interpreter, tool: int) -> bool:
    """Whether the dialect checks tools against the given table (``tool_table_check``) and it
    does not list ``tool`` (T0, no tool, is always allowed; without a table nothing is checked)."""
    listed = it.options.tool_numbers
    checked = bool(it.dialect.option("tool_table_check", False))
    return checked and bool(tool) and listed is not None and tool not in listed


def tool_not_found(it: Interpreter, tool: int) -> str:
    return controller_error(it, "tool_not_found", "Requested tool {0} not found in the tool table").replace(
        "{0}", str(tool))



# ---- positions ------------------------------------------------------------------------
def target(it: Interpreter, ctx: BlockContext) -> Vec6:
    """The block's end point in program coordinates (mm/deg)."""
    if it.frame.polar is not None and "machine_coords" not in ctx.block_flags:
        return polar_target(it, ctx)
    p = list(it.pos)
    machine = "machine_coords" in ctx.block_flags
    off = it.frame.total_offset_mm
    rd = it.reader
    for i, letter in enumerate(AXES):
        w = ctx.words.get(letter)
        if w is None:
            continue
        v = rd.axis_value(w)
        if machine:
            p[i] = v - off[i] - (it.frame.tool_length_mm if i == 2 else 0.0)
        elif it.modal.incremental:
            p[i] += v
        else:
            p[i] = v
    return (p[0], p[1], p[2], p[3], p[4], p[5])


def _release_named(it: Interpreter, ctx: BlockContext, cycle: bool) -> None:
    """Axes the block gives an absolute position no longer keep a cancelled transform's point.

    In a cycle block only the plane axes are positions (the drilling axis word is the hole
    bottom; ``expand-cycles`` releases that axis after the positioning move).
    """
    if it.frame.held_axes == NOT_HELD:
        return
    machine = "machine_coords" in ctx.block_flags
    if it.modal.incremental and not machine:
        return
    plane = it.frame.plane
    axes = [k for k, letter in enumerate(AXES) if letter in ctx.words
            and not (cycle and k == plane.normal)]
    if it.frame.polar is not None and not machine and any(k in (plane.first, plane.second) for k in axes):
        axes += [plane.first, plane.second]  # a polar radius or angle places both plane axes
    it.release_axes(axes)


def _motion(it: Interpreter, ctx: BlockContext) -> None:
    if "@" in ctx.words or "^" in ctx.words:
        from cncc.frontend.rs274_words import polar_to_xy

        if not polar_to_xy(it, ctx):
            return
    _release_named(it, ctx, bool(it.modal.cycle))
    if it.modal.cycle:
        fn = it.table.motions.get("cycle")
        if fn is None:
            it.emit_error(dg.NOT_SUPPORTED, ctx.span, "canned cycles are not supported yet")
            return
        fn(it, ctx, target(it, ctx))
        return
    fn = it.table.motions.get(it.modal.motion)
    if fn is None:
        it.emit_error(dg.NOT_SUPPORTED, ctx.span, f"motion mode {it.modal.motion} is not supported yet")
        return
    fn(it, ctx, target(it, ctx))


def block_motion(it: Interpreter, ctx: BlockContext) -> Motion:
    m = it.modal.path
    if "exact_stop_once" in ctx.block_flags and m.mode is not PathMode.EXACT_STOP:
        m = it.intern_motion(replace(m, mode=PathMode.EXACT_STOP))
    return m


def feed_mm_min(it: Interpreter, ctx: BlockContext) -> float | None:
    f = it.modal.feed
    if f is None:
        d = it.dialect
        f = d.default_feed_mm_rev if it.modal.per_rev else d.default_feed_mm_min
        if f <= 0:
            it.emit_error(dg.NO_FEED, ctx.span, "feed move without a feed rate (program F first)")
            return None
        if not it.modal.default_feed_noted:
            it.modal = it.modal.with_(default_feed_noted=True)
            it.sink.emit(dg.DEFAULT_FEED, ctx.span, f"no F programmed; using the {d.name} default F{f:g}")
        return f * _feed_scale(it)
    if f == 0.0:  # Fanuc PS0011, LinuxCNC "zero feed rate", grbl error 22: the controller alarms
        fw = ctx.words.get("F")
        it.emit_error(dg.ZERO_FEED, it.word_span(fw) if fw is not None else ctx.span,
                      "F0: a feed move needs a feed rate above 0; the move is not made")
        return None
    return f * _feed_scale(it)


def _feed_scale(it: Interpreter) -> float:
    scale = it.frame.units.mm_per_unit
    if it.modal.per_rev:
        scale *= it.modal.spindle_rpm
    return scale


def _rapid(it: Interpreter, ctx: BlockContext, end: Vec6) -> None:
    machine = "machine_coords" in ctx.block_flags  # transforms leave G53 moves alone
    ctx.out.append(Rapid(ctx.span, it.frame, it.pos, end, block_motion(it, ctx),
                         MACHINE_ORIGIN if machine else PROGRAMMED))
    it.pos = end
    if machine:
        it.hold_axes(_axes_named(ctx), ctx)  # in machine terms: the program's next absolute word is written again


def _linear(it: Interpreter, ctx: BlockContext, end: Vec6) -> None:
    f = feed_mm_min(it, ctx)
    if f is None:
        return
    machine = "machine_coords" in ctx.block_flags
    ctx.out.append(Linear(ctx.span, it.frame, it.pos, end, f, block_motion(it, ctx),
                          MACHINE_ORIGIN if machine else PROGRAMMED))
    it.pos = end
    if machine:
        it.hold_axes(_axes_named(ctx), ctx)


def _arc(it: Interpreter, ctx: BlockContext, end: Vec6, clockwise: bool) -> None:
    plane = it.frame.plane
    letters = {Plane.XY: ("I", "J"), Plane.ZX: ("K", "I"), Plane.YZ: ("J", "K")}[plane]
    rw = ctx.words.get("R")
    w1, w2 = ctx.words.get(letters[0]), ctx.words.get(letters[1])
    start = it.pos
    rd = it.reader
    if rw is not None:
        if w1 is not None or w2 is not None:
            it.emit_error(dg.ARC_NO_CENTER, ctx.span, "an arc takes either I/J/K or R, not both")
            return
        tol = float(it.dialect.option("r_arc_semicircle_tolerance_mm", 0.001))
        center, err = arcs.center_from_radius(start, end, plane, rd.length_mm(rw), clockwise, tol)
        if err == "full":
            it.emit_error(dg.ARC_R_FULL_CIRCLE, it.word_span(rw), "an R arc cannot be a full circle; use I/J/K")
            return
        if err == "small":
            it.emit_error(dg.ARC_R_TOO_SMALL, it.word_span(rw),
                          f"radius {abs(rd.length_mm(rw)):.4f} mm is less than half the chord")
            return
    elif w1 is None and w2 is None:
        it.emit_error(dg.ARC_NO_CENTER, ctx.span, f"arc without a centre: give {letters[0]}/{letters[1]} or R")
        return
    else:
        o1 = rd.length_mm(w1) if w1 is not None else 0.0
        o2 = rd.length_mm(w2) if w2 is not None else 0.0
        if abs(o1) < 1e-9 and abs(o2) < 1e-9:
            it.emit_error(dg.ARC_ZERO_RADIUS, ctx.span, "the arc's centre is its start point (zero radius)")
            return
        center = arcs.center_from_offsets(start, plane, o1, o2)
    f = feed_mm_min(it, ctx)
    if f is None:
        return
    if it.dialect.option("helix_feed", "projection") == "projection" and end[plane.normal] != start[plane.normal]:
        f = _helix_path_feed(start, end, center, plane, clockwise, f)
    turns = _turns(it, ctx)
    if turns is None:
        return
    turns = -turns if clockwise else turns
    ctx.out.append(Arc(ctx.span, it.frame, start, end, center, turns, plane, f, block_motion(it, ctx)))
    it.pos = end


def _turns(it: Interpreter, ctx: BlockContext) -> int | None:
    """The number of turns of an arc: 1, or the dialect's turns word (LinuxCNC: P on G2/G3)."""
    letter = str(it.dialect.option("arc_turns_word", ""))
    w = ctx.words.get(letter) if letter else None
    if w is None:
        return 1
    if w.value < 1 or w.value != int(w.value):
        it.emit_error(dg.NUMBER_RANGE, it.word_span(w), f"the number of turns {letter} of an arc must be a positive "
                      "integer")
        return None
    return int(w.value)


def _helix_path_feed(start: Vec6, end: Vec6, center: Vec6, plane: Plane, clockwise: bool, feed: float) -> float:
    """Path feed that moves the in-plane projection of a helix at ``feed`` (Fanuc convention)."""
    import math

    i, j, n = plane.first, plane.second, plane.normal
    r = math.hypot(start[i] - center[i], start[j] - center[j])
    a0 = math.atan2(start[j] - center[j], start[i] - center[i])
    a1 = math.atan2(end[j] - center[j], end[i] - center[i])
    sweep = (a0 - a1) if clockwise else (a1 - a0)
    sweep %= 2 * math.pi
    if sweep <= 1e-12:
        sweep = 2 * math.pi
    planar = sweep * r
    if planar <= 0.0:
        return feed
    return feed * math.hypot(planar, end[n] - start[n]) / planar


MOTIONS["rapid"] = _rapid
MOTIONS["linear"] = _linear
MOTIONS["arc_cw"] = lambda it, ctx, end: _arc(it, ctx, end, True)
MOTIONS["arc_ccw"] = lambda it, ctx, end: _arc(it, ctx, end, False)


# ---- G codes ------------------------------------------------------------------------
@handler("rapid", "linear", "arc_cw", "arc_ccw")
def _set_motion(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    it.modal = it.modal.with_(motion=c.op, cycle="")


@handler("feed_per_min", "feed_per_rev")
def _feed_mode(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    per_rev = c.op == "feed_per_rev"
    if per_rev != it.modal.per_rev:
        it.modal = it.modal.with_(per_rev=per_rev)
        ctx.out.append(SetFeedMode(ctx.span, it.frame, FeedMode.PER_REV if per_rev else FeedMode.PER_MIN))


@handler("dwell")
def _dwell(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    time_letters = {letter for letter, kind in c.words.items() if kind.startswith("time")}
    if time_letters & set(AXES):  # Fanuc family: G04 X is a time, so the block's axis words are the dwell's
        ctx.axis_used = True
        moving = [a for a in AXES if a in ctx.words and a not in time_letters]
        if moving or ("X" in ctx.words and "P" in ctx.words and "P" in time_letters):
            it.emit_error(dg.DWELL_WITH_MOTION, ctx.span,
                          f"{c.name} with axis words ({' '.join(moving or ['X'])}): {it.dialect.name} reads a block's "
                          "axis words as the dwell's; put the move in a block of its own (neither is run)")
            return
    # else (LinuxCNC, grbl: only P is a time): the dwell runs, then the block's move (order of execution)
    pw, xw = ctx.words.get("P"), ctx.words.get("X") if "X" in time_letters else None
    w = pw if pw is not None else xw
    if w is None:
        it.emit_error(dg.BAD_DWELL, ctx.span, f"{c.name} needs a time (X or P)")
        return
    if w is pw and pw.point and c.words.get("P") == "time_ms":
        if it.dialect.option("g04_p_decimal", "truncate") == "error" or it.options.strict:
            it.emit_error(dg.DECIMAL_NOT_ALLOWED, it.word_span(pw), "G04 P takes integer milliseconds")
            return
        it.sink.emit(dg.DECIMAL_P_DWELL, it.word_span(pw),
                     f"G04 P{pw.value:g}: P is in integer milliseconds; read as {int(pw.value)} ms")
        pw = replace(pw, value=float(int(pw.value)), point=False)
        w = pw
    seconds = it.reader.value(w, c.words.get(w.letter, "time"))
    if seconds < 0:
        it.emit_error(dg.BAD_DWELL, it.word_span(w), "dwell time must not be negative")
        return
    ctx.out.append(Dwell(ctx.span, it.frame, seconds))


@handler("plane_xy", "plane_zx", "plane_yz")
def _plane(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    plane = {"plane_xy": Plane.XY, "plane_zx": Plane.ZX, "plane_yz": Plane.YZ}[c.op]
    if plane is not it.frame.plane:
        it.set_frame(replace(it.frame, plane=plane))
        ctx.out.append(SetPlane(ctx.span, it.frame, plane))


@handler("inch", "metric")
def _units(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    units = Units.INCH if c.op == "inch" else Units.MM
    if units is not it.frame.units:
        it.set_frame(replace(it.frame, units=units))
        ctx.out.append(SetUnits(ctx.span, it.frame, units))


@handler("work")
def _work(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    off = it.options.work_offsets_mm.get(c.index, (0.0,) * 6)
    if c.index != it.frame.work_index or off != it.frame.work_offset_mm:
        it.set_frame(replace(it.frame, work_index=c.index, work_offset_mm=off))
        ctx.out.append(SetWorkSystem(ctx.span, it.frame, c.index))


@handler("exact_stop_mode", "continuous_mode", "curve_mode", "tapping_mode")
def _path_mode(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    mode = PathMode.EXACT_STOP if c.op == "exact_stop_mode" else PathMode.CONTINUOUS
    if mode is not it.modal.path.mode:
        it.modal = it.modal.with_(path=it.intern_motion(replace(it.modal.path, mode=mode)))
        ctx.out.append(SetPathMode(ctx.span, it.frame, mode))


@handler("exact_stop_once")
def _exact_once(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    ctx.block_flags.add("exact_stop_once")


@handler("absolute", "incremental")
def _distance(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    it.modal = it.modal.with_(incremental=c.op == "incremental")
    if it.frame.incremental != it.modal.incremental:  # transforms treat increments differently
        it.set_frame(replace(it.frame, incremental=it.modal.incremental))


@handler("return_initial", "return_r")
def _return_level(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    it.modal = it.modal.with_(cycle_return_initial=c.op == "return_initial")


@handler("css_on", "css_off")
def _css(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    it.modal = it.modal.with_(css=c.op == "css_on")


@handler("modal_call_off", "cycle_off")  # (G15, G50, G50.1, G69 ...: frontend/transforms.py)
def _off_when_off(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    """Cancel codes are no-ops while the feature they cancel is not in force."""
    if c.op == "cycle_off":
        it.modal = it.modal.with_(cycle="")


@handler("machine_coords")
def _g53(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    if it.modal.incremental:
        it.sink.emit(dg.G53_INCREMENTAL, ctx.span, "G53 is ignored in incremental mode (G91)")
        ctx.axis_used = True
        return
    ctx.block_flags.add("machine_coords")


@handler("set_origin")
def _g92(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    ctx.axis_used = True
    sw = ctx.words.get("S")
    if sw is not None:
        it.modal = it.modal.with_(spindle_clamp_rpm=sw.value)
    shift = list(it.frame.g92_offset_mm)
    changed = False
    for i, letter in enumerate(AXES):
        w = ctx.words.get(letter)
        if w is None:
            continue
        new_pos = it.reader.axis_value(w)
        shift[i] += it.pos[i] - new_pos
        changed = True
    if changed:
        it.set_frame(replace(it.frame, g92_offset_mm=tuple(shift)))  # type: ignore[arg-type]
        ctx.out.append(SetG92Offset(ctx.span, it.frame, it.frame.g92_offset_mm))
        # the preset depends on where the machine is: a translation writes it even when the offset
        # came out unchanged from the assumed start
        ctx.out.append(PresetG92(ctx.span, it.frame, tuple(_axes_named(ctx))))


@handler("local_offset")
def _g52(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    ctx.axis_used = True
    local = list(it.frame.local_offset_mm)
    for i, letter in enumerate(AXES):
        w = ctx.words.get(letter)
        if w is not None:
            local[i] = it.reader.axis_value(w)
    new: Vec6 = (local[0], local[1], local[2], local[3], local[4], local[5])
    if new != it.frame.local_offset_mm:
        it.set_frame(replace(it.frame, local_offset_mm=new))
        ctx.out.append(SetLocalOffset(ctx.span, it.frame, new))


def _reference_program(it: Interpreter, index: int) -> Vec6 | None:
    refs = it.options.reference_mm
    if index - 1 >= len(refs):
        return None
    ref, off = refs[index - 1], it.frame.total_offset_mm
    z_tool = it.frame.tool_length_mm
    return tuple(ref[i] - off[i] - (z_tool if i == 2 else 0.0) for i in range(6))  # type: ignore[return-value]


def _axes_named(ctx: BlockContext) -> list[int]:
    return [i for i, letter in enumerate(AXES) if letter in ctx.words]


def _home_via(it: Interpreter, ctx: BlockContext, c: CodeDef, index: int) -> None:
    ctx.axis_used = True
    named = _axes_named(ctx)
    if not named:
        return
    mid = target(it, ctx)
    ref = _reference_program(it, index)
    if ref is None:
        it.emit_error(dg.BAD_OFFSET_INDEX, ctx.span, f"the machine has no reference position {index}")
        return
    if not it.modal.incremental:  # an absolute intermediate point (in G91: an increment from the tool)
        it.release_axes(named)
    ctx.out.append(Rapid(ctx.span, it.frame, it.pos, mid, block_motion(it, ctx), Origin(OriginKind.HOME, c.name)))
    it.pos = mid
    it.release_axes(named)  # the named axes end at the reference position (SYNTEC §1.2.23: "G28 or G30")
    end = tuple(ref[i] if i in named else mid[i] for i in range(6))
    ctx.out.append(Rapid(ctx.span, it.frame, mid, end, block_motion(it, ctx),  # type: ignore[arg-type]
                         Origin(OriginKind.REFERENCE, c.name)))  # the leg no transform applies to
    it.pos = end  # type: ignore[assignment]
    it.hold_axes(named, ctx)  # at the machine's reference, which the program does not know
    flags = tuple(i in named for i in range(6))
    from cncc.frontend.modal import Reference

    it.refs = replace(it.refs, intermediate=Reference(mid, flags))


@handler("home")
def _g28(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    _home_via(it, ctx, c, 1)


@handler("home2")
def _g30(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    pw = ctx.words.get("P")
    index = int(pw.value) if pw is not None else 2
    if index < 2 or index > 4:
        it.emit_error(dg.BAD_OFFSET_INDEX, ctx.span, f"G30 P{index}: reference positions are P2 to P4")
        ctx.axis_used = True
        return
    _home_via(it, ctx, c, index)


@handler("home_return")
def _g29(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    ctx.axis_used = True
    named = _axes_named(ctx)
    if not named:
        return
    mid = tuple(it.refs.intermediate.point[i] if i in named else it.pos[i] for i in range(6))
    it.release_axes(named)  # the intermediate point is an absolute position
    ctx.out.append(Rapid(ctx.span, it.frame, it.pos, mid, block_motion(it, ctx),  # type: ignore[arg-type]
                         Origin(OriginKind.HOME, c.name)))
    it.pos = mid  # type: ignore[assignment]
    end = target(it, ctx)  # incremental words are taken from the intermediate point
    ctx.out.append(Rapid(ctx.span, it.frame, it.pos, end, block_motion(it, ctx), Origin(OriginKind.HOME, c.name)))
    it.pos = end


# ---- M codes ------------------------------------------------------------------------
@handler("program_stop", "optional_stop", "program_end", "program_end_rewind")
def _stop(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    kind = {"program_stop": StopKind.PROGRAM_STOP, "optional_stop": StopKind.OPTIONAL_STOP,
            "program_end": StopKind.PROGRAM_END, "program_end_rewind": StopKind.END_REWIND}[c.op]
    ctx.out.append(Stop(ctx.span, it.frame, kind))
    if kind in (StopKind.PROGRAM_END, StopKind.END_REWIND):
        it.ended = True


@handler("spindle_cw", "spindle_ccw", "spindle_off", "spindle_orient")
def _spindle(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    state = {"spindle_cw": SpindleState.CW, "spindle_ccw": SpindleState.CCW, "spindle_off": SpindleState.OFF,
             "spindle_orient": SpindleState.ORIENT}[c.op]
    ctx.out.append(Spindle(ctx.span, it.frame, state, it.modal.spindle_rpm))


@handler("coolant_flood", "coolant_mist", "coolant_off", "coolant_mist_off")
def _coolant(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    state = {"coolant_flood": CoolantState.FLOOD, "coolant_mist": CoolantState.MIST}.get(c.op, CoolantState.OFF)
    ctx.out.append(Coolant(ctx.span, it.frame, state))


@handler("tool_change")
def _tool_change(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    it.modal = it.modal.with_(tool_loaded=it.modal.tool_selected)
    ctx.out.append(ToolChange(ctx.span, it.frame, it.modal.tool_selected))
    it.hold_axes(range(3), ctx)  # the changer may move X Y Z: a translation writes each axis's next word

# the registry's names are re-exported: the modules that register ops use ops.handler, ops.MOTIONS ...
__all__ = ["AXES", "BLOCK_HOOKS", "DEFAULT_ORDER", "HANDLERS", "MOTIONS", "BlockHook", "Handler", "HandlerTable",
           "Layer", "MotionHandler", "block_motion", "feed_mm_min", "handler", "run_block", "target"]
