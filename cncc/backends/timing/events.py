"""Non-motion events and their times from the machine model.

Consumes IR commands in program order; for each command yields an :class:`Event`
(time, category, whether an operator decides how long it takes) or ``None``.

The rules (``docs/timing.md`` lists them with the reasons):

* ``G04`` dwell: the programmed time.
* tool change (``M06``): ``machine.tool_change_s``.
* spindle start or reversal (``M03``/``M04``), orientation (``M19``), or a new speed
  while the spindle turns: ``machine.spindle_ramp_s``; the same start repeated costs
  nothing; ``M05`` costs nothing (the next block does not wait for the stop).
* ``M00`` program stop and ``M01`` optional stop: ``machine.optional_stop_s``, flagged
  operator-dependent.
* an M code the machine model lists (``[[m_codes]]``, e.g. ``M10`` clamp): its
  ``seconds``, category ``wait``.
* SZGH ``WAT`` waits and pausing messages: the time on the command (0 when the
  machine gives none), flagged operator-dependent.

Reversal pauses (SZGH Axis P68) are no command's event: they depend on the motion, so
the driver finds them with the pulse backend and hands them over in
:attr:`~cncc.backends.timing.model.Run.reversals` (category ``reversal``).
"""

from __future__ import annotations

from dataclasses import dataclass

from cncc.ir import Aux, Command, Dwell, Message, Spindle, SpindleSpeed, SpindleState, Stop, StopKind, ToolChange, Wait
from cncc.ir.machine import MachineModel

CATEGORIES: tuple[str, ...] = ("rapid", "feed", "arc", "dwell", "tool_change", "spindle", "wait", "reversal")
"""Every category of time, in report order (motions first, then events)."""

EVENT_TYPES = (Aux, Dwell, ToolChange, Spindle, SpindleSpeed, Stop, Wait, Message)
"""The command types :meth:`EventTimer.event` looks at (it must see all of them, in order)."""


@dataclass(frozen=True, slots=True)
class Event:
    seconds: float
    category: str
    operator_dependent: bool = False
    what: str = ""


class EventTimer:
    """Times the non-motion commands of one program for one machine (stateful: spindle)."""

    def __init__(self, machine: MachineModel) -> None:
        self.machine = machine
        self.spindle = SpindleState.OFF
        self.rpm = 0.0

    def event(self, c: Command) -> Event | None:
        m = self.machine
        match c:
            case Dwell():
                return Event(max(c.seconds, 0.0), "dwell", what="dwell")
            case ToolChange():
                return Event(m.tool_change_s, "tool_change", what=f"T{c.tool}")
            case Spindle():
                return self._spindle(c)
            case SpindleSpeed():
                running = self.spindle in (SpindleState.CW, SpindleState.CCW)
                changed = c.rpm != self.rpm
                self.rpm = c.rpm
                if running and changed:
                    return Event(m.spindle_ramp_s, "spindle", what=f"S{c.rpm:g}")
                return None
            case Stop() if c.kind in (StopKind.PROGRAM_STOP, StopKind.OPTIONAL_STOP):
                return Event(m.optional_stop_s, "wait", True, c.kind.value)
            case Wait():
                return Event(max(c.seconds, 0.0), "wait", True, c.what or "wait")
            case Aux():
                return self._aux(c)
            case Message() if c.pause:
                return Event(0.0, "wait", True, "message")
        return None

    def _aux(self, c: Aux) -> Event | None:
        whole, frac = divmod(c.code, 10)
        name = f"M{whole:02d}" + (f".{frac}" if frac else "")
        known = self.machine.m_code(name)
        if known is None or known.seconds <= 0:
            return None
        return Event(known.seconds, "wait", False, f"{name} {known.meaning}".strip())

    def _spindle(self, c: Spindle) -> Event | None:
        before, rpm_before = self.spindle, self.rpm
        self.spindle, self.rpm = c.state, c.rpm
        if c.state is SpindleState.OFF:
            return Event(0.0, "spindle", what="stop")
        if c.state is SpindleState.ORIENT:
            return Event(self.machine.spindle_ramp_s, "spindle", what="orient")
        if c.state is before and c.rpm == rpm_before:
            return None
        return Event(self.machine.spindle_ramp_s, "spindle", what=c.state.value)
