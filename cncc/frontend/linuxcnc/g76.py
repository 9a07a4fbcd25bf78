"""LinuxCNC's G76 threading cycle, lowered to spindle-synchronised moves.

``G76 P- Z- I- J- K- <R- Q- H- E- L->`` as LinuxCNC 2.9 runs it (``interp_convert.cc``,
``convert_threading_cycle``): from the start point (X the drive line, Z the start of the
thread) passes at depths ``|I| + |J| * n ** (1/R)`` up to ``|I| + |K|``, then H spring
passes at full depth; each pass moves off the drive line along Q's compound angle, rapids
in, feeds along the thread synchronised to the spindle (P per revolution; E/L tapers at
the entry/exit at the slanted pitch) and rapids out and back.  The cycle ends with a
rapid to the block's end point.  I/J/K are diameters in G7 mode.  G76 is a motion mode:
a later block with axis words runs it again (and needs its words again).

IR: ``SetMode("feed_override", False)`` before each synchronised stretch and ``True``
after it; ``SetMode("spindle_sync", pitch mm)`` ... ``SetMode("spindle_sync", 0.0)``
around the moves that follow the spindle (their feed is the nominal ``rpm x pitch``).
The canon back end prints LinuxCNC's DISABLE_FEED_OVERRIDE / START_SPEED_FEED_SYNC /
STOP_SPEED_FEED_SYNCH / ENABLE_FEED_OVERRIDE; a G-code translation writes plain moves.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

from cncc import diagnostics as dg
from cncc.dialects import CodeDef
from cncc.frontend import ops
from cncc.frontend.cycles import spindle_state
from cncc.frontend.linuxcnc.lathe import diameter_mode
from cncc.ir import CompSide, Linear, Rapid, SetMode, SpindleState, Vec6

if TYPE_CHECKING:
    from cncc.frontend.interp import BlockContext, Interpreter


def _fail(it: Interpreter, ctx: BlockContext, message: str, code: str = dg.LATHE_CYCLE_WORDS) -> None:
    it.emit_error(code, ctx.span, message)


@ops.handler("lathe_thread")
def _select(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    it.modal = it.modal.with_(motion="lathe_thread", cycle="")
    if not any(k in ctx.words for k in ops.AXES):  # rs274 runs the cycle without axis words too
        ctx.axis_used = True
        _g76(it, ctx, it.pos)


@dataclass(slots=True)
class _Thread:
    """One G76 in program units: the drive line, the depths and the tapers."""

    boring: bool
    safe_x: float
    start_y: float
    start_z: float
    target_z: float
    end_depth: float
    full_height: float
    taper: float
    entry: bool
    exit: bool
    pitch: float
    taper_pitch: float


def _g76(it: Interpreter, ctx: BlockContext, end: Vec6) -> None:
    w = {k: v.value for k, v in ctx.words.items()}
    if "P" not in w:
        return _fail(it, ctx, "P word missing with G76")
    if not all(k in w for k in "IJK"):
        return _fail(it, ctx, "I J or K words missing with G76")
    if spindle_state(it) not in (SpindleState.CW, SpindleState.CCW):
        return _fail(it, ctx, "Chosen spindle (0) not turning in G76", dg.CONTROLLER_REJECTS)
    if any(abs(end[a] - it.pos[a]) > 0 for a in (3, 4, 5)):
        return _fail(it, ctx, "Cannot move rotary axes with G76")
    if it.frame.comp_side is not CompSide.OFF:
        return _fail(it, ctx, "Cannot use G76 threading cycle with cutter radius compensation on",
                     dg.LATHE_CYCLE_STATE)
    i, j, kk = w["I"], w["J"], w["K"]
    if i == 0:
        return _fail(it, ctx, "In G76, I must not be 0")
    if j <= 0:
        return _fail(it, ctx, "In G76, J must be greater than 0")
    if kk <= j:
        return _fail(it, ctx, "In G76, K must be greater than J")
    if diameter_mode(it):
        i, j, kk = i / 2, j / 2, kk / 2
    u = it.frame.units.mm_per_unit
    start = (it.pos[0] / u, it.pos[1] / u, it.pos[2] / u)
    end_z = end[2] / u
    angle = w.get("Q", 0.0)
    angle = 0.0 if angle == -1 else angle * math.pi / 180.0
    if end_z > start[2]:
        angle = -angle
    springs = int(w.get("H", 0.0))
    degression = w.get("R", 1.0)
    degression = max(degression, 1.0)
    taper = max(w.get("E", 0.0), 0.0)
    pitch = w["P"]
    taper_pitch = pitch * math.hypot(taper, abs(kk)) / taper if taper > 0 else pitch
    if end_z > start[2]:
        taper = -taper
    flags = max(int(w.get("L", 0.0)), 0)
    full, cut = abs(i), abs(j)
    t = _Thread(i > 0, start[0], start[1], start[2], end_z + abs(kk) * math.tan(angle), abs(kk) + abs(i),
                abs(kk), taper, bool(flags & 1), bool(flags & 2), pitch, taper_pitch)
    passes = _Passes(it, ctx)
    depth, n = full + cut, 1
    while depth < t.end_depth:
        passes.thread(t, depth, (depth - full) * math.tan(angle))
        n += 1
        depth = full + cut * n ** (1.0 / degression)
    depth = t.end_depth
    for _ in range(springs + 1):
        passes.thread(t, depth, (depth - full) * math.tan(angle))
    passes.rapid((end[0] / u, end[1] / u, end[2] / u))
    it.pos = (end[0], end[1], end[2], it.pos[3], it.pos[4], it.pos[5])


class _Passes:
    """Writes the moves of the passes (program units in, IR in mm)."""

    def __init__(self, it: Interpreter, ctx: BlockContext) -> None:
        self.it, self.ctx = it, ctx
        self.k = it.frame.units.mm_per_unit
        self.at = it.pos
        self.motion = ops.block_motion(it, ctx)

    def _end(self, p: tuple[float, float, float]) -> Vec6:
        k, a = self.k, self.at
        return (p[0] * k, p[1] * k, p[2] * k, a[3], a[4], a[5])

    def rapid(self, p: tuple[float, float, float]) -> None:
        e = self._end(p)
        self.ctx.out.append(Rapid(self.ctx.span, self.it.frame, self.at, e, self.motion, "G76"))
        self.at = e

    def feed(self, p: tuple[float, float, float], pitch: float) -> None:
        e = self._end(p)
        rpm = self.it.modal.spindle_rpm
        self.ctx.out.append(Linear(self.ctx.span, self.it.frame, self.at, e, rpm * pitch * self.k, self.motion, "G76"))
        self.at = e

    def mode(self, name: str, value: object) -> None:
        self.ctx.out.append(SetMode(self.ctx.span, self.it.frame, name, value))

    def thread(self, t: _Thread, depth: float, zoff: float) -> None:
        """One pass (rs274's threading_pass)."""
        sign = 1.0 if t.boring else -1.0
        y, z0, z1 = t.start_y, t.start_z - zoff, t.target_z - zoff
        x_back = t.safe_x + sign * (depth - t.end_depth)
        x_cut = t.safe_x + sign * depth
        x_crest = t.safe_x + sign * (depth - t.full_height)
        self.rapid((x_back, y, z0))
        if t.taper and t.entry:
            self.mode("feed_override", False)
            self.mode("spindle_sync", t.taper_pitch * self.k)
            self.feed((x_crest, y, z0), t.taper_pitch)
            self.feed((x_cut, y, z0 - t.taper), t.taper_pitch)
            self.mode("spindle_sync", t.pitch * self.k)
        else:
            self.rapid((x_cut, y, z0))
            self.mode("feed_override", False)
            self.mode("spindle_sync", t.pitch * self.k)
        if t.taper and t.exit:
            self.feed((x_cut, y, z1 + t.taper), t.pitch)
            self.mode("spindle_sync", t.taper_pitch * self.k)
            self.feed((x_crest, y, z1), t.taper_pitch)
        else:
            self.feed((x_cut, y, z1), t.pitch)
        self.mode("spindle_sync", 0.0)
        self.rapid((x_back, y, z1))
        self.mode("feed_override", True)


ops.MOTIONS["lathe_thread"] = _g76
