"""LinuxCNC's straight probing: ``G38.2`` / ``G38.3`` (toward the work) and ``G38.4`` /
``G38.5`` (away from it).

A probe block feeds toward its end point until the probe trips.  cncc cannot know where
that happens; it does what LinuxCNC 2.9's stand-alone interpreter (``rs274``) does: the
probe reaches the end point without tripping, and the tool is then 0.254 mm (0.01 inch)
back toward the start (the stand-alone canon's back-off).  The result parameters
#5061-#5069 hold the end point in program coordinates and #5070 is 0 (not tripped); the
LinuxCNC executor writes them before the next block (:func:`take_result`).

In the IR a probe is ``Probe(end, op, moves)`` (``op``: ``probe_toward`` ...) followed by ``moves``
(1 or 2) ``Linear`` commands: the probe move, and the back-off when it has a length.
The canon backend prints one ``STRAIGHT_PROBE`` for the marker (LinuxCNC: between
``TURN_PROBE_ON()`` and ``TURN_PROBE_OFF()``); the G-code writer writes the probe code
in a target that has it and refuses the block in one that does not (never a silent move).

Errors as rs274 checks them, in its order: cutter compensation on, zero feed rate (the
feed rate of the units-per-minute mode: an F in G93 is not one), feed per revolution,
the end point equal to the start point.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

from cncc.dialects import CodeDef
from cncc.frontend import registry
from cncc.frontend.controller_errors import reject
from cncc.ir import CompSide, FeedRate, Linear, Origin, OriginKind, Probe, Vec6

if TYPE_CHECKING:
    from cncc.frontend.interp import BlockContext, Interpreter
    from cncc.frontend.registry import MotionHandler

PROBE_OPS = ("probe_toward", "probe_toward_noerr", "probe_away", "probe_away_noerr")
PROBE_AXES = "XYZABC@^"
BACKOFF_MM = 0.254  # the stand-alone canon's back-off: 0.254 mm in G21, 0.01 inch in G20


@dataclass(slots=True)
class ProbeState:
    units_feed: float = 0.0  # rs274's feed rate: the last F outside inverse time (program units/min)
    result: tuple[float, ...] | None = None  # #5061-#5070 of the last probe, not yet written


def _state(it: Interpreter) -> ProbeState:
    st = it.extras.get(ProbeState)
    return st if st is not None else it.extras.attach(ProbeState())


def take_result(it: Interpreter) -> tuple[float, ...] | None:
    """#5061 .. #5070 of a probe made since the last call (program units, degrees), or None."""
    st = it.extras.get(ProbeState)
    if st is None or st.result is None:
        return None
    got, st.result = st.result, None
    return got


def track_feed(it: Interpreter, ctx: BlockContext) -> None:
    """Block hook: rs274's feed rate (an F outside G93), and a G38.x block without axis words."""
    if not it.modal.path.inverse_time and "F" in ctx.words:
        _state(it).units_feed = ctx.words["F"].value
    if any(c.op in PROBE_OPS for c in ctx.codes) and not any(k in ctx.words for k in PROBE_AXES):
        reject(it, ctx.span, "probe_no_axes", "All axes missing with motion code")  # a G38.x block must move


@registry.handler(*PROBE_OPS)
def select(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    it.modal = it.modal.with_(motion=c.op, cycle="")


def _probe(it: Interpreter, ctx: BlockContext, end: Vec6, op: str, code: str) -> None:
    if it.frame.comp_side is not CompSide.OFF:
        reject(it, ctx.span, "probe_comp", "Cannot probe with cutter radius comp on")
        return
    inverse_time = it.modal.path.inverse_time
    feed = _state(it).units_feed if inverse_time else (it.modal.feed or 0.0)
    if feed <= 0.0:
        reject(it, ctx.span, "probe_zero_feed", "Cannot probe with zero feed rate")
        return
    if it.modal.per_rev:
        reject(it, ctx.span, "probe_per_rev", "Cannot probe with feed per rev mode")
        return
    start = it.pos
    if start == end:
        reject(it, ctx.span, "probe_too_close", "Start point too close to probe point")
        return
    if inverse_time:  # the block's F is not a feed rate to rs274: no SET_FEED_RATE for it
        ctx.out[:] = [c for c in ctx.out if not isinstance(c, FeedRate)]
    k = it.frame.units.mm_per_unit
    feed_mm = feed * k
    motion = it.modal.path
    d = [start[i] - end[i] for i in range(3)]
    dist = math.sqrt(d[0] ** 2 + d[1] ** 2 + d[2] ** 2)
    after = end
    if dist > 0.0:
        s = BACKOFF_MM / dist
        after = (end[0] + d[0] * s, end[1] + d[1] * s, end[2] + d[2] * s, end[3], end[4], end[5])
    moves = 2 if after != end else 1
    ctx.out.append(Probe(ctx.span, it.frame, end, op, moves))
    ctx.out.append(Linear(ctx.span, it.frame, start, end, feed_mm, motion, Origin(OriginKind.PROBE, code)))
    if moves == 2:
        ctx.out.append(Linear(ctx.span, it.frame, end, after, feed_mm, motion, Origin(OriginKind.PROBE_BACKOFF, code)))
    it.pos = after
    _state(it).result = (end[0] / k, end[1] / k, end[2] / k, end[3], end[4], end[5], 0.0, 0.0, 0.0, 0.0)


def _motion_for(op: str, code: str) -> MotionHandler:
    return lambda it, ctx, end: _probe(it, ctx, end, op, code)


for _op, _code in zip(PROBE_OPS, ("G38.2", "G38.3", "G38.4", "G38.5"), strict=True):
    registry.MOTIONS[_op] = _motion_for(_op, _code)
registry.BLOCK_HOOKS.append(track_feed)
