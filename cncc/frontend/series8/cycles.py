"""SERIES 8 canned cycles G81-G89 with their own words (spec 4.14).

The shared cycle op and motion (``ops.HANDLERS["cycle"]``, ``ops.MOTIONS["cycle"]``)
are wrapped; for a SERIES 8 interpreter:

* Z, R and the G83 I are Z levels even in G91 (``cycle_levels_absolute``, A-18); the
  R and Z levels (and I, J, K, P) are kept between cycles of any type and across G80;
* positioning is in X, Y and A from the current level; every hole ends at R (there is
  no G98/G99; G98 presets program zero here), G87 stays at depth, G89 ends at the
  level it started from;
* a block with X, Y or A drills; a G87 block with R and Z only bores the next wall
  at the same place (X or Y while at depth is refused, A-41); other blocks store data;
* G83 I is the level of the first stroke (default R + J), J the depth of each further
  peck; G84 K is the lead (feed = rpm x K); P is seconds; G88/G89 I J is the shift;
* D selects the tool-length row for the cycle (A-17); M03/M04 and S in the block
  apply before the motion.

Each hole is one :class:`cncc.ir.Cycle` for ``expand-cycles``.
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

from cncc import diagnostics as dg
from cncc.dialects import CodeDef
from cncc.dialects.series8_cycles import Series8CycleKind
from cncc.frontend import cycles as shared
from cncc.frontend import ops
from cncc.frontend.series8 import state
from cncc.frontend.series8.layer import LAYER
from cncc.ir import CompSide, Cycle, CycleKind, CycleKindBase, SetToolLength, Vec6

if TYPE_CHECKING:
    from cncc.frontend.interp import BlockContext, Interpreter

_S8 = Series8CycleKind
_RAPID_OUT: dict[CycleKindBase, tuple[str, CycleKindBase]] = {
    _S8.BORE_DWELL_STOP_OUT: ("g86_rapid_return", _S8.BORE_DWELL_STOP_RAPID_OUT),
    _S8.BORE_ORIENT_OUT: ("g88_rapid_return", _S8.BORE_ORIENT_RAPID_OUT)}
_SHIFTED = (_S8.BORE_ORIENT_OUT, _S8.BACK_BORE_RETURN)
_NO_DWELL = (CycleKind.DRILL, _S8.PECK_FIRST, CycleKind.TAP, _S8.CASE_BORE)  # no P in their formats


def kind_of(name: str) -> CycleKindBase | None:
    """The kind a SERIES 8 table names: one of its own or a core one (None: neither)."""
    for kinds in (Series8CycleKind, CycleKind):
        try:
            return kinds(name)
        except ValueError:
            continue
    return None


def store_levels(it: Interpreter, ctx: BlockContext) -> bool:
    """Keep the block's R and Z levels (shared by the cycles, G34-G36 and G49/G50, A-18);
    True when the levels are absolute (``cycle_levels_absolute`` or G90)."""
    st = state.get(it)
    assert st is not None
    data = st.cycle
    rd = it.reader
    n = it.frame.plane.normal
    absolute = bool(state.option(it, "cycle_levels_absolute", True)) or not it.modal.incremental
    initial = it.pos[n]
    if (w := ctx.words.get("R")) is not None:
        data.r_mm = rd.length_mm(w) + (0.0 if absolute else initial)
    if (w := ctx.words.get(ops.AXES[n])) is not None:
        base = data.r_mm if data.r_mm is not None else initial
        data.z_mm = rd.length_mm(w) + (0.0 if absolute else base)
    return absolute


def _store(it: Interpreter, ctx: BlockContext, kind: CycleKindBase) -> bool:
    """Keep the block's cycle words; False after an error."""
    st = state.get(it)
    assert st is not None
    data = st.cycle
    rd = it.reader
    absolute = store_levels(it, ctx)
    initial = it.pos[it.frame.plane.normal]
    if (w := ctx.words.get("P")) is not None:
        if w.value < 0:
            it.emit_error(dg.BAD_DWELL, it.word_span(w), "dwell time must not be negative")
            return False
        data.dwell_s = w.value
    if (w := ctx.words.get("K")) is not None:
        data.lead_mm = abs(rd.length_mm(w))
    iw, jw = ctx.words.get("I"), ctx.words.get("J")
    if kind is Series8CycleKind.PECK_FIRST:
        if iw is not None:
            data.first_mm = rd.length_mm(iw) + (0.0 if absolute else initial)
        if jw is not None:
            data.peck_mm = abs(rd.length_mm(jw))
    elif kind in _SHIFTED and (iw is not None or jw is not None):
        data.shift_mm = (rd.length_mm(iw) if iw is not None else 0.0, rd.length_mm(jw) if jw is not None else 0.0)
    return True


def tool_length(it: Interpreter, ctx: BlockContext) -> None:
    """D in a cycle block: the tool-length row for this and later cycles (A-17)."""
    dw = ctx.words.get("D")
    if dw is None or dw.value < 0 or dw.value != int(dw.value):
        return
    index = int(dw.value)
    value = it.options.tool_lengths_mm.get(index, 0.0)
    if (value, index) != (it.frame.tool_length_mm, it.frame.tool_length_index):
        it.set_frame(replace(it.frame, tool_length_mm=value, tool_length_index=index))
        ctx.out.append(SetToolLength(ctx.span, it.frame, value))


def _select(inner: ops.Handler) -> ops.Handler:
    def select(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
        if state.get(it) is None:
            inner(it, ctx, c)
            return
        kind = kind_of(c.cycle)
        if kind is None:
            it.emit_error(dg.CYCLE_UNKNOWN, ctx.span, f"{c.name}: cycle kind {c.cycle!r} is not known to cncc")
            ctx.axis_used = True
            return
        st = state.get(it)
        assert st is not None
        st.cycle_code = c
        it.modal = it.modal.with_(cycle=kind.value)
        tool_length(it, ctx)
        if not any(k in ctx.words for k in ops.AXES):
            _store(it, ctx, kind)

    return select


def _drill(inner: ops.MotionHandler) -> ops.MotionHandler:
    def drill(it: Interpreter, ctx: BlockContext, end: Vec6) -> None:
        st = state.get(it)
        if st is None:
            inner(it, ctx, end)
            return
        code = st.cycle_code
        if code is None:  # pragma: no cover - a cycle is only in force after its code
            return
        kind = kind_of(code.cycle)
        assert kind is not None  # checked when the cycle code was read
        if not any(c.op == "cycle" for c in ctx.codes):
            tool_length(it, ctx)
        if not _store(it, ctx, kind):
            return
        placed = any(a in ctx.words for a in "XYA")
        if kind is Series8CycleKind.CASE_BORE and st.at_depth and placed:
            it.emit_error(dg.CONTROLLER_REJECTS, ctx.span,
                          f"{code.name}: X/Y/A while the tool is at depth; retract first (spec A-41)")
            return
        if not placed and kind is not Series8CycleKind.CASE_BORE:
            it.sink.emit(dg.ASSUMED, ctx.span, f"{code.name}: no X, Y or A in the block: the levels are stored, "
                                               "no hole is made (spec A-18)")
            return
        emit(it, ctx, code, kind, (end,))

    return drill


def _levels_ok(it: Interpreter, ctx: BlockContext, code: CodeDef, kind: CycleKindBase, data: state.CycleWords) -> bool:
    axis = ops.AXES[it.frame.plane.normal]
    if data.r_mm is None:
        it.emit_error(dg.CYCLE_NO_R, ctx.span, f"{code.name} needs an R level")
        return False
    if data.z_mm is None:
        it.emit_error(dg.CYCLE_NO_BOTTOM, ctx.span, f"{code.name} needs the level {axis}")
        return False
    if data.r_mm == data.z_mm or (kind is Series8CycleKind.BACK_BORE_RETURN and data.z_mm < data.r_mm):
        where = "above" if kind is Series8CycleKind.BACK_BORE_RETURN else "away from"
        it.emit_error(dg.CYCLE_R_PAST_BOTTOM, ctx.span, f"{code.name}: {axis}{data.z_mm:g} must be {where} "
                                                        f"R {data.r_mm:g} (mm)")
        return False
    if kind is Series8CycleKind.PECK_FIRST:
        down = 1.0 if data.z_mm > data.r_mm else -1.0
        if not data.peck_mm:
            it.emit_error(dg.CYCLE_BAD_PECK, ctx.span, f"{code.name} needs the peck depth J > 0 (spec A-19)")
            return False
        first = data.first_mm
        if first is not None and ((first - data.r_mm) * down <= 0 or (data.z_mm - first) * down < 0):
            it.emit_error(dg.CYCLE_BAD_PECK, ctx.span, f"{code.name}: the first depth I must lie between R and "
                                                       f"{axis} (spec A-19)")
            return False
    return True


def emit(it: Interpreter, ctx: BlockContext, code: CodeDef, kind: CycleKindBase, ends: tuple[Vec6, ...],
         pattern: str = "") -> None:
    """One :class:`Cycle` of the cycle in force over the hole positions ``ends`` (a G49/G50
    pattern gives several); the tool is left above the last one."""
    st = state.get(it)
    assert st is not None
    data = st.cycle
    if not _levels_ok(it, ctx, code, kind, data):
        return
    assert data.r_mm is not None and data.z_mm is not None
    option, rapid_kind = _RAPID_OUT.get(kind, ("", kind))
    if option and state.option(it, option, False):
        kind = rapid_kind
    spindle, rpm = shared.spindle_state(it), it.modal.spindle_rpm
    pitch = 0.0
    if kind is CycleKind.TAP:
        if not data.lead_mm or rpm <= 0:
            it.emit_error(dg.CYCLE_NO_PITCH, ctx.span, f"{code.name} needs the lead K and a spindle speed S "
                                                       "(feed = S x K)")
            return
        pitch = data.lead_mm
        feed: float | None = rpm * pitch
    else:
        feed = ops.feed_mm_min(it, ctx)
    if feed is None:
        return
    n, p = it.frame.plane.normal, it.frame.plane
    start = it.pos
    level = start[n]
    levels: dict[CycleKindBase, float] = {_S8.CASE_BORE: data.z_mm, _S8.BACK_BORE_RETURN: level}
    retract = levels.get(kind, data.r_mm)
    shift = [0.0] * 6
    if kind in (_S8.BORE_ORIENT_OUT, _S8.BORE_ORIENT_RAPID_OUT, _S8.BACK_BORE_RETURN):
        shift[p.first], shift[p.second] = data.shift_mm
    frame = it.frame
    if frame.comp_side is not CompSide.OFF:
        frame = replace(frame, comp_side=CompSide.OFF, comp_radius_mm=0.0, comp_index=0)
    placed = tuple(_at_level(e, n, retract) for e in ends)
    ctx.out.append(Cycle(
        ctx.span, frame, kind, code.name, start, placed, level, data.r_mm, data.z_mm, retract, feed,
        return_initial=False, peck_mm=(data.peck_mm or 0.0) if kind is Series8CycleKind.PECK_FIRST else 0.0,
        first_depth_mm=data.first_mm if kind is Series8CycleKind.PECK_FIRST else None,
        clearance_mm=float(state.option(it, "cycle_g83_clearance_mm", 1.27)) if kind is _S8.PECK_FIRST else 0.0,
        shift_mm=(shift[0], shift[1], shift[2], shift[3], shift[4], shift[5]),
        dwell_s=data.dwell_s if kind not in _NO_DWELL else 0.0,
        spindle=spindle, spindle_rpm=rpm, tap_pitch_mm=pitch, pattern=pattern, motion=ops.block_motion(it, ctx)))
    it.pos = placed[-1]
    st.at_depth = kind is Series8CycleKind.CASE_BORE
    st.moved = True


def _at_level(p: Vec6, axis: int, level: float) -> Vec6:
    q = list(p)
    q[axis] = level
    return (q[0], q[1], q[2], q[3], q[4], q[5])


LAYER.wrap_handler("cycle", _select)
LAYER.wrap_motion("cycle", _drill)
