"""Canned cycles in the front end: modal cycle data -> :class:`cncc.ir.Cycle` commands.

Registers into :mod:`cncc.frontend.ops`: the ``cycle`` op (G73-G89 select a cycle),
``MOTIONS["cycle"]`` (a block with axis words while a cycle is in force drills), the
``pattern`` op (G134/G135/G136/G137.1 hole patterns, in :mod:`cncc.frontend.holes`),
and guards around the plane and spindle ops.

The rules follow the SYNTEC manuals (spec syntec-mill-v8.20.md section 4.32, with the
900M spec's resolutions) and apply to every dialect whose codes use the ``cycle`` op:

* a cycle code selects the cycle; the initial level is the drilling-axis position
  when the cycle mode is entered (the first cycle code after G80 or a group-01 code);
* only a block with an axis word drills; R, Z, Q, P (and the SZGH pitch K) are stored
  only by such blocks, or by a block whose repeat count is 0 (store only, no motion);
* R and Z are absolute in G90; in G91 R is measured from the initial level and Z from
  the R level (option ``cycle_z_incremental_from``); the stored levels are absolute;
* K (SYNTEC) or L (SZGH) repeats the positioning and the hole; in G91 every repeat
  adds the programmed increment again;
* G98 returns to the initial level, G99 to R; G87 always to the initial level;
* the plane cannot change while a cycle is in force.

Machine parameters (SYNTEC Pr4001/Pr4002/Pr4020, SZGH User P1-P7) are dialect
options; ``docs/cycles.md`` lists them.  The cycle data is a frozen snapshot in the
interpreter's ``cycle`` record (:class:`~cncc.frontend.run_state.CycleState`), replaced on
every change.
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING, Any

from cncc import diagnostics as dg
from cncc.dialects import CodeDef
from cncc.frontend import ops
from cncc.frontend.run_state import CycleData
from cncc.frontend.syntax import Word
from cncc.ir import CompSide, Cycle, CycleKind, Plane, SpindleState, Vec6

if TYPE_CHECKING:
    from cncc.frontend.interp import BlockContext, Interpreter

AXES = "XYZABC"
MAX_REPEAT = 9999
_PECKS = (CycleKind.PECK, CycleKind.PECK_HIGH_SPEED)
_TAPS = (CycleKind.TAP, CycleKind.TAP_LEFT)
_SHIFTS = (CycleKind.FINE_BORE, CycleKind.BACK_BORE)


def cycle_data(it: Interpreter) -> CycleData | None:
    """The cycle data in force, or None when no cycle is active."""
    data = it.cycle.data
    return data if data is not None and it.modal.cycle else None


def spindle_state(it: Interpreter) -> SpindleState:
    return it.cycle.spindle


def option(it: Interpreter, key: str, default: object) -> object:
    return it.dialect.option(key, default)


# ---- cycle selection ------------------------------------------------------------------
@ops.handler("cycle")
def _select(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    try:
        kind = CycleKind(c.cycle)
    except ValueError:
        it.emit_error(dg.CYCLE_UNKNOWN, ctx.span, f"{c.name}: cycle kind {c.cycle!r} is not known to cncc")
        ctx.axis_used = True
        return
    data = cycle_data(it)
    if data is None:
        plane = it.frame.plane
        data = CycleData(code=c, kind=kind, plane=plane, initial_mm=it.pos[plane.normal])
    else:
        data = replace(data, code=c, kind=kind)
    it.cycle = replace(it.cycle, data=data)
    it.modal = replace(it.modal, cycle=kind.value)
    if not any(k in ctx.words for k in AXES):
        word = ctx.words.get(repeat_letter(it))
        if word is not None and word.value == 0:
            _drill(it, ctx, it.pos)  # a K0 block stores the data without moving
            ctx.axis_used = True
            return
        stray = [k for k in "RQP" if k in ctx.words]
        if stray:
            it.sink.emit(dg.CYCLE_WORDS_NOT_STORED, ctx.span,
                         f"{'/'.join(stray)} in a block without axis words: no hole is drilled and "
                         "the value is not stored")


def repeat_letter(it: Interpreter) -> str:
    return str(option(it, "cycle_repeat_word", "K"))


# ---- a drilling block ---------------------------------------------------------------------
def _drill(it: Interpreter, ctx: BlockContext, end: Vec6) -> None:
    data = cycle_data(it)
    if data is None:  # pragma: no cover - ops only calls us while a cycle is in force
        return
    repeat = read_repeat(it, ctx)
    new = _stored(it, ctx, data)
    if repeat is None or new is None:
        return
    it.cycle = replace(it.cycle, data=new)
    if repeat == 0:
        return
    n = new.plane.normal
    start = it.pos
    step = tuple(end[i] - start[i] for i in range(6))
    if not it.modal.incremental and repeat > 1:
        it.sink.emit(dg.CYCLE_REPEAT_ABSOLUTE, ctx.span,
                     f"{repeat_letter(it)}{repeat} in G90 drills the same hole {repeat} times (use G91)")
    holes = []
    for k in range(1, repeat + 1):
        p = [start[i] + k * step[i] if it.modal.incremental else end[i] for i in range(6)]
        p[n] = start[n]
        holes.append((p[0], p[1], p[2], p[3], p[4], p[5]))
    emit_cycle(it, ctx, new, tuple(holes), repeat, "")


def read_repeat(it: Interpreter, ctx: BlockContext) -> int | None:
    """The block's repeat count (1 when absent); None after a diagnostic."""
    letter = repeat_letter(it)
    w = ctx.words.get(letter)
    if w is None:
        return 1
    if w.value != int(w.value) or not 0 <= w.value <= MAX_REPEAT:
        it.emit_error(dg.CYCLE_BAD_REPEAT, it.word_span(w),
                      f"{letter}{w.value:g}: the repeat count is an integer from 0 to {MAX_REPEAT}")
        return None
    return int(w.value)


def _value(it: Interpreter, code: CodeDef, w: Word) -> float:
    return it.reader.value(w, code.words.get(w.letter))


def _stored(it: Interpreter, ctx: BlockContext, data: CycleData) -> CycleData | None:
    """The cycle data after this drilling block's words; None after an error."""
    code, n = data.code, data.plane.normal
    words = ctx.words
    r_mm = data.r_mm
    if (w := words.get("R")) is not None:
        v = _value(it, code, w)
        r_mm = data.initial_mm + v if it.modal.incremental else v
    bottom = data.bottom_mm
    if (w := words.get(AXES[n])) is not None:
        v = it.reader.axis_value(w)
        if it.modal.incremental:
            base = data.initial_mm if option(it, "cycle_z_incremental_from", "r") == "initial" else r_mm
            if base is None:
                it.emit_error(dg.CYCLE_NO_R, ctx.span, f"incremental {AXES[n]} needs an R level to start from")
                return None
            bottom = base + v
        else:
            bottom = v
    q_mm = data.q_mm
    if (w := words.get("Q")) is not None:
        q_mm = abs(_value(it, code, w))
        if w.value < 0:
            it.sink.emit(dg.CYCLE_NEGATIVE_Q, it.word_span(w), f"Q{w.value:g}: the absolute value {q_mm:g} is used")
    dwell = data.dwell_s
    if (w := words.get("P")) is not None:
        dwell = _value(it, code, w)
        if option(it, "cycle_dwell_unit", "s") == "ms":
            dwell *= 0.001
        if dwell < 0:
            it.emit_error(dg.BAD_DWELL, it.word_span(w), "dwell time must not be negative")
            return None
        if dwell > 60:
            it.sink.emit(dg.CYCLE_LONG_DWELL, it.word_span(w), f"P{w.value:g} is a dwell of {dwell:g} s")
    pitch = data.pitch_mm
    pitch_letter = str(option(it, "cycle_pitch_word", ""))
    if pitch_letter and data.kind in _TAPS and (w := words.get(pitch_letter)) is not None:
        pitch = abs(it.reader.length_mm(w))
    new = replace(data, r_mm=r_mm, bottom_mm=bottom, q_mm=q_mm, dwell_s=dwell, pitch_mm=pitch)
    new = _back_bore_order(it, ctx, new)
    return new if check_levels(it, ctx, new, warn=new.r_mm != data.r_mm) else None


def _back_bore_order(it: Interpreter, ctx: BlockContext, d: CycleData) -> CycleData:
    """Option ``cycle_back_bore_order = "lower_first"``: a G87 with R above Z starts at the lower one."""
    if (d.kind is not CycleKind.BACK_BORE or d.r_mm is None or d.bottom_mm is None or d.r_mm <= d.bottom_mm
            or option(it, "cycle_back_bore_order", "strict") != "lower_first"):
        return d
    it.sink.emit(dg.CYCLE_BACK_BORE_SWAPPED, ctx.span,
                 f"{d.code.name}: R {d.r_mm:g} is above {AXES[d.plane.normal]}{d.bottom_mm:g}; the tool goes down "
                 f"to {d.bottom_mm:g} and cuts up to {d.r_mm:g}")
    return replace(d, r_mm=d.bottom_mm, bottom_mm=d.r_mm)


def check_levels(it: Interpreter, ctx: BlockContext, d: CycleData, warn: bool = False) -> bool:
    """Errors for missing or inverted levels and pecks; ``warn``: also flag R above the initial level."""
    axis = AXES[d.plane.normal]
    if d.r_mm is None:
        it.emit_error(dg.CYCLE_NO_R, ctx.span, f"{d.code.name} needs an R level (none since the cycle began)")
        return False
    if d.bottom_mm is None:
        it.emit_error(dg.CYCLE_NO_BOTTOM, ctx.span, f"{d.code.name} needs a hole bottom {axis}")
        return False
    if d.kind is CycleKind.BACK_BORE:
        if d.r_mm >= d.bottom_mm:
            it.emit_error(dg.CYCLE_R_PAST_BOTTOM, ctx.span,
                          f"{d.code.name}: R {d.r_mm:g} must be below the bore top {axis}{d.bottom_mm:g}")
            return False
    elif d.r_mm <= d.bottom_mm:
        it.emit_error(dg.CYCLE_R_PAST_BOTTOM, ctx.span,
                      f"{d.code.name}: R {d.r_mm:g} is not above the bottom {axis}{d.bottom_mm:g}")
        return False
    elif d.r_mm > d.initial_mm and warn:
        it.sink.emit(dg.CYCLE_R_ABOVE_INITIAL, ctx.span,
                     f"R level {d.r_mm:g} is above the initial level {d.initial_mm:g}")
    if d.kind in _PECKS and not d.q_mm:
        it.emit_error(dg.CYCLE_BAD_PECK, ctx.span, f"{d.code.name} needs a depth per peck Q greater than 0")
        return False
    return True


# ---- the IR command --------------------------------------------------------------------------
def emit_cycle(it: Interpreter, ctx: BlockContext, d: CycleData, holes: tuple[Vec6, ...], repeat: int,
               pattern: str, pattern_words: tuple[tuple[str, float], ...] = ()) -> None:
    """Append the :class:`Cycle` for ``holes`` and move the tool to the last hole."""
    assert d.r_mm is not None and d.bottom_mm is not None
    feed = ops.feed_mm_min(it, ctx)
    if feed is None:
        return
    spindle = spindle_state(it)
    rpm = it.modal.spindle_rpm
    pitch = _pitch(it, ctx, d, feed, spindle, rpm)
    if pitch is None:
        return
    if d.kind in _TAPS and d.pitch_mm is not None:
        feed = rpm * d.pitch_mm  # SZGH: the feed follows S x K
    shift = _shift(it, ctx, d)
    if shift is None:
        return
    retract = retract_level(it, d)
    if (retract <= d.bottom_mm) if d.kind is not CycleKind.BACK_BORE else (retract < d.bottom_mm):
        it.emit_error(dg.CYCLE_RETURN_IN_HOLE, ctx.span,
                      f"{d.code.name}: the return level {retract:g} is not above the hole ({AXES[d.plane.normal]}"
                      f"{d.bottom_mm:g}); move the tool up before the cycle or use G99")
        return
    n = d.plane.normal
    placed = tuple(_with(h, n, retract) for h in holes)
    frame = it.frame
    if frame.comp_side is not CompSide.OFF:  # cutter radius compensation is ignored in cycles
        frame = replace(frame, comp_side=CompSide.OFF, comp_radius_mm=0.0, comp_index=0)
    peck = (d.q_mm or 0.0) if d.kind in _PECKS or d.kind in _TAPS else 0.0
    ctx.out.append(Cycle(
        ctx.span, frame, d.kind, d.code.name, it.pos, placed, d.initial_mm, d.r_mm, d.bottom_mm, retract, feed,
        return_initial=it.modal.cycle_return_initial, peck_mm=peck, clearance_mm=_clearance(it, d.kind),
        peck_tap_to_r=option(it, "cycle_peck_tap", "return_r") == "return_r", shift_mm=shift,
        dwell_s=d.dwell_s, spindle=spindle, spindle_rpm=rpm, tap_pitch_mm=pitch, repeat=repeat,
        pattern=pattern, pattern_words=pattern_words, motion=ops.block_motion(it, ctx), **_lift_pause(it, d.kind)))
    it.pos = placed[-1]


def _with(p: Vec6, i: int, v: float) -> Vec6:
    q = list(p)
    q[i] = v
    return (q[0], q[1], q[2], q[3], q[4], q[5])


def retract_level(it: Interpreter, d: CycleData) -> float:
    """Where each hole ends: G98 initial, G99 R; G87 always the initial level."""
    assert d.r_mm is not None
    if d.kind is CycleKind.BACK_BORE:
        return d.initial_mm
    if not it.modal.cycle_return_initial:
        return d.r_mm
    if option(it, "cycle_return_higher", False) and d.r_mm > d.initial_mm:
        return d.r_mm
    return d.initial_mm


def _lift_pause(it: Interpreter, kind: CycleKind) -> dict[str, Any]:
    """SZGH User P8 (option ``cycle_peck_pause_ms``): |ms| > 5 pauses before each G73/G83
    peck lift; a negative value makes the lift a feed move."""
    ms = float(option(it, "cycle_peck_pause_ms", 0.0))  # type: ignore[arg-type]
    if kind not in (CycleKind.PECK, CycleKind.PECK_HIGH_SPEED) or abs(ms) <= 5.0:
        return {}
    return {"lift_pause_s": abs(ms) / 1000.0, "lift_at_feed": ms < 0}


def _clearance(it: Interpreter, kind: CycleKind) -> float:
    key = {CycleKind.PECK_HIGH_SPEED: "cycle_g73_retract_mm", CycleKind.PECK: "cycle_g83_clearance_mm",
           CycleKind.TAP: "cycle_tap_clearance_mm", CycleKind.TAP_LEFT: "cycle_tap_clearance_mm"}.get(kind)
    return float(option(it, key, 0.0)) if key else 0.0  # type: ignore[arg-type]


def _pitch(it: Interpreter, ctx: BlockContext, d: CycleData, feed: float, spindle: SpindleState,
           rpm: float) -> float | None:
    """Tapping pitch in mm (0 for other cycles); None after an error."""
    if d.kind not in _TAPS:
        return 0.0
    want = SpindleState.CCW if d.kind is CycleKind.TAP_LEFT else SpindleState.CW
    if spindle is not want:
        it.sink.emit(dg.CYCLE_SPINDLE, ctx.span,
                     f"{d.code.name} expects the spindle turning {want.value.upper()}, it is {spindle.value.upper()}")
    if option(it, "cycle_pitch_word", ""):
        if d.pitch_mm is None or d.pitch_mm <= 0:
            it.emit_error(dg.CYCLE_NO_PITCH, ctx.span,
                          f"{d.code.name} needs the pitch {option(it, 'cycle_pitch_word', '')} (feed = S x pitch)")
            return None
        if rpm <= 0:
            it.emit_error(dg.CYCLE_NO_PITCH, ctx.span, f"{d.code.name} needs a spindle speed S")
            return None
        return d.pitch_mm
    if rpm <= 0:
        it.emit_error(dg.CYCLE_NO_PITCH, ctx.span, f"{d.code.name}: the pitch is F / S but no S is programmed")
        return None
    return feed / rpm


def _shift(it: Interpreter, ctx: BlockContext, d: CycleData) -> Vec6 | None:
    """The G76/G87 shift vector (|Q| along the parameter's direction); None after an error."""
    if d.kind not in _SHIFTS or not d.q_mm:
        return (0.0,) * 6
    direction = int(option(it, "cycle_shift_direction", 0))  # type: ignore[call-overload]
    reverse = bool(option(it, "cycle_fine_bore_shift_reverse", False))
    if d.kind is CycleKind.BACK_BORE:
        own = int(option(it, "cycle_back_bore_shift_direction", -1))  # type: ignore[call-overload]
        reverse = own < 0
        direction = direction if own < 0 else own
    if not 0 <= direction <= 3:
        it.emit_error(dg.CYCLE_BAD_SHIFT, ctx.span,
                      f"shift direction {direction}: 0 +{AXES[d.plane.first]}, 1 -{AXES[d.plane.first]}, "
                      f"2 +{AXES[d.plane.second]}, 3 -{AXES[d.plane.second]}")
        return None
    axis = d.plane.first if direction < 2 else d.plane.second
    sign = -1.0 if direction % 2 else 1.0
    if reverse:
        sign = -sign
    v = [0.0] * 6
    v[axis] = sign * d.q_mm
    return (v[0], v[1], v[2], v[3], v[4], v[5])


ops.MOTIONS["cycle"] = _drill


# ---- guards around ops the cycle rules constrain ---------------------------------------------------
_PLANES = {"plane_xy": Plane.XY, "plane_zx": Plane.ZX, "plane_yz": Plane.YZ}
_SPINDLE_OPS = {"spindle_cw": SpindleState.CW, "spindle_ccw": SpindleState.CCW, "spindle_off": SpindleState.OFF,
                "spindle_orient": SpindleState.OFF}


def _guard_plane(inner: ops.Handler) -> ops.Handler:
    def guarded(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
        cancels = any(k.group == "motion" or k.op == "cycle_off" for k in ctx.codes)
        if it.modal.cycle and _PLANES[c.op] is not it.frame.plane and not cancels:
            it.emit_error(dg.CYCLE_PLANE_CHANGE, ctx.span,
                          f"{c.name}: cancel the canned cycle (G80) before changing the plane")
            return
        inner(it, ctx, c)

    return guarded


def _track_spindle(inner: ops.Handler) -> ops.Handler:
    def tracked(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
        inner(it, ctx, c)
        it.cycle = replace(it.cycle, spindle=_SPINDLE_OPS[c.op])

    return tracked


for _op in _PLANES:
    if _op in ops.HANDLERS:
        ops.HANDLERS[_op] = _guard_plane(ops.HANDLERS[_op])
for _op in _SPINDLE_OPS:
    if _op in ops.HANDLERS:
        ops.HANDLERS[_op] = _track_spindle(ops.HANDLERS[_op])

