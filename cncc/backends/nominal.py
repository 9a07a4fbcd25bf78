"""Nominal timing (``--emit=timing -O0``): length / feed, as CAM systems estimate.

Rapids run at the machine's rapid rate (interpolated: the slowest axis sets the
time; independent: each axis at its own rate, the longest wins), feeds at the
programmed feed along the path (arcs along their helical length), dwells for their
time, and tool changes / spindle starts for the machine model's times.  No
acceleration is modelled: that is what the planner levels add.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass, field

from cncc.ir import Arc, Command, Dwell, Linear, Rapid, Spindle, SpindleState, Stop, StopKind, ToolChange
from cncc.ir.machine import MachineModel


@dataclass(slots=True)
class NominalTiming:
    total_s: float = 0.0
    by_category_s: dict[str, float] = field(default_factory=dict)
    by_line_s: dict[tuple[int, int], float] = field(default_factory=dict)  # (source_id, offset of line) -> s
    by_command: list[tuple[Command, float, str]] = field(default_factory=list)


def arc_length_mm(c: Arc) -> float:
    p = c.plane
    i, j, n = p.first, p.second, p.normal
    r = math.hypot(c.start[i] - c.center[i], c.start[j] - c.center[j])
    a0 = math.atan2(c.start[j] - c.center[j], c.start[i] - c.center[i])
    a1 = math.atan2(c.end[j] - c.center[j], c.end[i] - c.center[i])
    sweep = a1 - a0
    if c.turns > 0:
        while sweep <= 1e-12:
            sweep += 2 * math.pi
        sweep += 2 * math.pi * (c.turns - 1)
    else:
        while sweep >= -1e-12:
            sweep -= 2 * math.pi
        sweep -= 2 * math.pi * (-c.turns - 1)
    planar = abs(sweep) * r
    helix = c.end[n] - c.start[n]
    return math.hypot(planar, helix)


def rapid_time_s(start: tuple[float, ...], end: tuple[float, ...], machine: MachineModel) -> float:
    t = 0.0
    for k, axis in enumerate(machine.axes[: len(start)]):
        d = abs(end[k] - start[k])
        if d > 0:
            t = max(t, d / (axis.rapid_mm_min / 60.0))
    return t


def command_time_s(c: Command, machine: MachineModel) -> tuple[float, str]:
    match c:
        case Rapid():
            return rapid_time_s(c.start, c.end, machine), "rapid"
        case Linear():
            length = math.dist(c.start[:3], c.end[:3])
            if length == 0.0:
                length = math.dist(c.start, c.end)
            return (length / (c.feed_mm_min / 60.0) if c.feed_mm_min > 0 else 0.0), "feed"
        case Arc():
            return (arc_length_mm(c) / (c.feed_mm_min / 60.0) if c.feed_mm_min > 0 else 0.0), "arc"
        case Dwell():
            return c.seconds, "dwell"
        case ToolChange():
            return machine.tool_change_s, "tool change"
        case Spindle():
            if c.state in (SpindleState.CW, SpindleState.CCW):
                return machine.spindle_ramp_s, "spindle"
            return 0.0, "spindle"
        case Stop():
            if c.kind is StopKind.OPTIONAL_STOP or c.kind is StopKind.PROGRAM_STOP:
                return machine.optional_stop_s, "stop"
            return 0.0, "stop"
    return 0.0, ""


def nominal_timing(cmds: Iterable[Command], machine: MachineModel, line_of: dict[int, int] | None = None) -> NominalTiming:
    """Sum the nominal times; ``by_line_s`` is keyed by (source id, span start)."""
    out = NominalTiming()
    for c in cmds:
        t, cat = command_time_s(c, machine)
        if not cat:
            continue
        out.total_s += t
        out.by_category_s[cat] = out.by_category_s.get(cat, 0.0) + t
        key = (c.span.source_id, c.span.start)
        out.by_line_s[key] = out.by_line_s.get(key, 0.0) + t
        out.by_command.append((c, t, cat))
    return out
