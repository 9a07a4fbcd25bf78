"""The command list of one expanded canned cycle, built move by move.

:class:`CyclePath` tracks the tool position while a cycle's sequence (one function per
cycle kind, :data:`Sequence`) adds rapids, feeds, dwells and spindle events.  The
sequences live in ``expand_cycles.py`` (the shared kinds), ``linuxcnc_cycles.py`` and
``series8_cycles.py``; each of the two dialect modules keeps its own ``SEQUENCES`` table,
which ``expand_cycles.SEQUENCES`` merges, so none of them imports another back (no import
circle; tests/test_layers.py).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

from cncc.ir import (
    Command,
    Cycle,
    CycleKind,
    Dwell,
    Linear,
    Motion,
    Origin,
    OriginKind,
    PathMode,
    Rapid,
    Spindle,
    SpindleState,
    SpindleSync,
    Vec6,
    Wait,
)


class CyclePath:
    """Builds the command list of one cycle, tracking the tool position."""

    def __init__(self, c: Cycle) -> None:
        self.c = c
        self.out: list[Command] = []
        self.pos: Vec6 = c.start
        self.hole: Vec6 = c.start
        self.motion: Motion = replace(c.motion, mode=PathMode.EXACT_STOP)
        self.origin = Origin(OriginKind.CYCLE, c.code)
        running = c.spindle in (SpindleState.CW, SpindleState.CCW)
        default = SpindleState.CCW if c.kind in (CycleKind.TAP_LEFT, CycleKind.TAP_LEFT_RS274) else SpindleState.CW
        self.forward = c.spindle if running else default
        self.down = -1.0 if c.bottom_mm < c.r_mm else 1.0
        self.frame = c.frame
        held = c.frame.held_axes
        # After a transform cancel the positioning keeps the drilling axis where the tool is;
        # R, the bottom and the return levels are absolute positions of that axis.
        self.levels_frame = c.frame if not held[c.axis] else replace(
            c.frame, held_axes=tuple(h and k != c.axis for k, h in enumerate(held)))  # type: ignore[arg-type]

    def position(self, p: Vec6) -> None:
        """The rapid that puts the tool above the hole.  Under a transform (or after a cancel) it is
        emitted even when it is zero-length in program coordinates: a rotation, mirror or scaling
        switched since the previous hole puts the hole's machine position elsewhere, and the
        transform passes map this rapid there.  (Offset changes already move the program position:
        ``Interpreter.set_frame``.)"""
        f = self.frame
        if p == self.pos and f.scaling is None and f.mirror is None and f.rotation is None and not f.after_cancel:
            return
        self.out.append(Rapid(self.c.span, self.frame, self.pos, p, self.motion, self.origin))
        self.pos = p

    def at(self, level: float, shifted: bool = False) -> Vec6:
        p = list(self.hole)
        p[self.c.axis] = level
        if shifted:
            p = [p[i] + self.c.shift_mm[i] for i in range(6)]
        return (p[0], p[1], p[2], p[3], p[4], p[5])

    def rapid(self, p: Vec6) -> None:
        if p != self.pos:
            self.out.append(Rapid(self.c.span, self.frame, self.pos, p, self.motion, self.origin))
            self.pos = p

    def feed(self, p: Vec6) -> None:
        if p != self.pos:
            c = self.c
            self.out.append(Linear(c.span, self.frame, self.pos, p, c.feed_mm_min, self.motion, self.origin))
            self.pos = p

    def lift(self, p: Vec6) -> None:
        """A G73/G83 peck lift: the User P8 pause first, then a rapid (or a feed)."""
        if self.c.lift_pause_s > 0:
            self.out.append(Dwell(self.c.span, self.c.frame, self.c.lift_pause_s))
        (self.feed if self.c.lift_at_feed else self.rapid)(p)

    def dwell(self) -> None:
        if self.c.dwell_s > 0 or self.c.zero_moves:
            self.out.append(Dwell(self.c.span, self.c.frame, self.c.dwell_s))

    def spindle(self, state: SpindleState) -> None:
        self.out.append(Spindle(self.c.span, self.c.frame, state, self.c.spindle_rpm))

    def reverse(self) -> SpindleState:
        return SpindleState.CCW if self.forward is SpindleState.CW else SpindleState.CW

    def sync(self, pitch_mm: float) -> None:
        self.out.append(SpindleSync(self.c.span, self.c.frame, pitch_mm))

    def wait(self, what: str) -> None:
        self.out.append(Wait(self.c.span, self.c.frame, what))


Sequence = Callable[[CyclePath], None]
"""One hole of a cycle kind: the moves after the positioning rapid."""

__all__ = ["CyclePath", "Sequence"]
