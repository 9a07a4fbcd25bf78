"""LinuxCNC's spindle-synchronised motion: ``G33`` and ``G33.1`` rigid tapping.

``G33 X.. Z.. K..``: a straight move whose axes follow the spindle, K the distance per
revolution.  In the IR it is the move between ``SpindleSync(K mm)`` and
``SpindleSync(0.0)`` (the representation the tapping cycles use), its
feed the nominal ``rpm x |K|``.

``G33.1 X.. Y.. Z.. K..``: rigid tapping.  The tool feeds to the end point
synchronised, the spindle reverses, the tool comes back to where it started and the
spindle turns forward again.  In the IR: the synchronisation marks around
``RigidTap(end, 4)``, a feed in, a spindle reversal, a feed out and the
spindle restored; the canon backend prints LinuxCNC's single ``RIGID_TAP(x, y, z)``
for the marker when the dialect's ``[canon]`` has it.  The tool ends at the start.

Both need K, a turning spindle, and no F word in the block (LinuxCNC's texts).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from cncc.dialects import CodeDef
from cncc.frontend import ops
from cncc.frontend.controller_errors import reject
from cncc.frontend.cycles import spindle_state
from cncc.ir import Linear, Origin, OriginKind, RigidTap, Spindle, SpindleState, SpindleSync, Vec6

if TYPE_CHECKING:
    from cncc.frontend.interp import BlockContext, Interpreter


@ops.handler("spindle_sync_rs274", "rigid_tap_rs274")
def _select(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    it.modal = it.modal.with_(motion=c.op, cycle="")


def _pitch_mm(it: Interpreter, ctx: BlockContext, code: str) -> float | None:
    """K in mm per revolution, after LinuxCNC's checks; None after an error."""
    kw = ctx.words.get("K")
    if kw is None:
        reject(it, ctx.span, "sync_no_k", "K word missing with g33/g33.1")
        return None
    if "F" in ctx.words:
        reject(it, ctx.span, "sync_f_word", "F word used with a g33/g33.1")
        return None
    if spindle_state(it) not in (SpindleState.CW, SpindleState.CCW):
        key = "sync_no_spindle_g33" if code == "G33" else "sync_no_spindle_g33_1"
        reject(it, ctx.span, key, f"Spindle not turning in {code}")
        return None
    return it.reader.length_mm(kw)


def _g33(it: Interpreter, ctx: BlockContext, end: Vec6) -> None:
    pitch = _pitch_mm(it, ctx, "G33")
    if pitch is None:
        return
    feed = it.modal.spindle_rpm * abs(pitch)
    ctx.out.append(SpindleSync(ctx.span, it.frame, pitch))
    origin = Origin(OriginKind.SYNC, "G33")
    ctx.out.append(Linear(ctx.span, it.frame, it.pos, end, feed, ops.block_motion(it, ctx), origin))
    ctx.out.append(SpindleSync(ctx.span, it.frame, 0.0))
    it.pos = end


def _g33_1(it: Interpreter, ctx: BlockContext, end: Vec6) -> None:
    pitch = _pitch_mm(it, ctx, "G33.1")
    if pitch is None:
        return
    forward = spindle_state(it)
    reverse = SpindleState.CCW if forward is SpindleState.CW else SpindleState.CW
    rpm = it.modal.spindle_rpm
    feed, motion, start, f = rpm * abs(pitch), ops.block_motion(it, ctx), it.pos, it.frame
    origin = Origin(OriginKind.SYNC, "G33.1")
    ctx.out += [SpindleSync(ctx.span, f, pitch), RigidTap(ctx.span, f, end, 4),
                Linear(ctx.span, f, start, end, feed, motion, origin), Spindle(ctx.span, f, reverse, rpm),
                Linear(ctx.span, f, end, start, feed, motion, origin), Spindle(ctx.span, f, forward, rpm),
                SpindleSync(ctx.span, f, 0.0)]


ops.MOTIONS["spindle_sync_rs274"] = _g33
ops.MOTIONS["rigid_tap_rs274"] = _g33_1
