"""The ``blend`` pass: decide where the path blends and where it stops exactly.

Consumes commands in machine coordinates; produces the same commands with every
motion's :class:`Motion` resolved:

* a continuous motion without a programmed tolerance (G64 without P, no G05.1 E) gets
  the machine's ``blend_tolerance_mm`` (or this pass's ``tolerance_mm`` option);
* a motion followed by a command that forces a stop (:func:`forces_stop`: dwell, tool
  change, spindle on/off, program stop, wait, pausing message and, on machines with
  ``mst_stops_motion`` such as SZGH, every M/S/T block) becomes ``EXACT_STOP``;
* G09/G61/G60 motions (``EXACT_STOP`` from the front end) stay as they are;
  ``exact_stop=True`` makes every motion stop (a global G61).

The geometry of the rounded corners is built by the planner (vectorised, see
``cncc/passes/planning/blending.py``): this pass says *where* and *how much*, the
planner says *how*.  Streaming: one motion command of look-ahead.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from typing import ClassVar

from cncc.ir.commands import (
    Arc,
    Aux,
    Command,
    Coolant,
    Dwell,
    Linear,
    Message,
    Motion,
    PathMode,
    Rapid,
    SelectTool,
    Spindle,
    SpindleSpeed,
    Stop,
    ToolChange,
    Wait,
)
from cncc.ir.machine import MachineModel
from cncc.passes import Pass, PassContext, register

MotionCommand = Rapid | Linear | Arc


def forces_stop(cmd: Command, machine: MachineModel | None) -> bool:
    """True if the path must be at rest where ``cmd`` (a non-motion command) executes."""
    match cmd:
        case Dwell() | ToolChange() | Stop() | Wait() | Spindle():
            return True
        case Message(pause=pause):
            return pause
        case SpindleSpeed() | Coolant() | SelectTool() | Aux():
            return machine is not None and machine.mst_stops_motion
        case _:
            return False


@register
@dataclass(frozen=True, kw_only=True)
class Blend(Pass):
    """Resolve blend tolerances and exact stops (G64 P, G05.1 E, G09/G61/G60, M/S/T)."""

    name: ClassVar[str] = "blend"
    stage: ClassVar[str] = "plan"
    tolerance_mm: float | None = None  # override the machine default for unprogrammed G64
    exact_stop: bool = False  # stop at the end of every motion (global G61)

    def run(self, cmds: Iterable[Command], ctx: PassContext) -> Iterator[Command]:
        machine = ctx.machine
        default = self.tolerance_mm if self.tolerance_mm is not None else (
            machine.blend_tolerance_mm if machine is not None else 0.01)
        cache: dict[Motion, Motion] = {}
        pending: MotionCommand | None = None
        held: list[Command] = []
        for cmd in cmds:
            if isinstance(cmd, Rapid | Linear | Arc):
                if pending is not None:
                    yield self._resolve(pending, False, default, cache)
                yield from held
                held.clear()
                pending = cmd
            elif pending is not None and forces_stop(cmd, machine):
                yield self._resolve(pending, True, default, cache)
                yield from held
                held.clear()
                pending = None
                yield cmd
            elif pending is not None:
                held.append(cmd)
            else:
                yield cmd
        if pending is not None:
            yield self._resolve(pending, False, default, cache)
        yield from held

    def _resolve(self, cmd: MotionCommand, stop: bool, default_mm: float, cache: dict[Motion, Motion]) -> MotionCommand:
        m = cmd.motion
        mode = PathMode.EXACT_STOP if (stop or self.exact_stop) else m.mode
        tol = m.blend_tolerance_mm if m.blend_tolerance_mm is not None else default_mm
        if mode is m.mode and tol == m.blend_tolerance_mm:
            return cmd
        new = Motion(mode, tol, m.inverse_time, m.per_rev)
        motion = cache.setdefault(new, new)
        match cmd:
            case Rapid():
                return Rapid(cmd.span, cmd.frame, cmd.start, cmd.end, motion, cmd.origin)
            case Linear():
                return Linear(cmd.span, cmd.frame, cmd.start, cmd.end, cmd.feed_mm_min, motion, cmd.origin)
            case Arc():
                return Arc(cmd.span, cmd.frame, cmd.start, cmd.end, cmd.center, cmd.turns, cmd.plane,
                           cmd.feed_mm_min, motion, cmd.origin)
