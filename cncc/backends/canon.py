"""Canonical-call trace in the format of LinuxCNC's standalone interpreter.

One call per line, `` N..... NAME(args)`` (``rs274 -g`` with its sequence column
dropped), floats as ``%.4f``.  Positions are program coordinates in program units:
work (G5x), local (G52) and G92 offsets and tool length are reported by their own
calls, while everything that changes the path itself (cutter compensation, cycles,
polar, scaling, mirror, rotation) is already applied to the positions.

Consumes IR commands whose coordinates are still in their programmed frames (the
driver runs the path passes but not the lowering to machine coordinates).
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from cncc.ir import (
    Arc,
    Aux,
    Command,
    Comment,
    Coolant,
    CoolantState,
    Dwell,
    FeedRate,
    Frame,
    Linear,
    Message,
    PathMode,
    Plane,
    Rapid,
    SelectTool,
    SetMode,
    Spindle,
    SpindleSpeed,
    SpindleState,
    Stop,
    StopKind,
    ToolChange,
    Units,
    Vec6,
    Wait,
)

PREFIX = " N..... "
_PLANES = {Plane.XY: "CANON_PLANE_XY", Plane.YZ: "CANON_PLANE_YZ", Plane.ZX: "CANON_PLANE_XZ"}
_UNITS = {Units.MM: "CANON_UNITS_MM", Units.INCH: "CANON_UNITS_INCHES"}


def _f(x: float) -> str:
    s = f"{x:.4f}"
    return "0.0000" if s == "-0.0000" else s


def _pos(p: Vec6, frame: Frame) -> list[float]:
    k = frame.units.mm_per_unit
    return [p[0] / k, p[1] / k, p[2] / k, p[3], p[4], p[5]]


def _offsets(frame: Frame) -> tuple[str, str]:
    k = frame.units.mm_per_unit
    w = frame.work_offset_mm
    g = [frame.local_offset_mm[i] + frame.g92_offset_mm[i] for i in range(6)]
    g5x = f"SET_G5X_OFFSET({frame.work_index}, " + ", ".join(
        _f(w[i] / k if i < 3 else w[i]) for i in range(6)) + ")"
    g92 = "SET_G92_OFFSET(" + ", ".join(_f(g[i] / k if i < 3 else g[i]) for i in range(6)) + ")"
    return g5x, g92


def canon_lines(cmds: Iterable[Command], *, initial_frame: Frame | None = None) -> Iterator[str]:
    """Yield the trace lines (without newlines) for ``cmds``."""
    frame0 = initial_frame or Frame()
    g5x, g92 = _offsets(frame0)
    yield PREFIX + f"USE_LENGTH_UNITS({_UNITS[frame0.units]})"
    yield PREFIX + g5x
    yield PREFIX + g92
    yield PREFIX + "SET_XY_ROTATION(0.0000)"
    yield PREFIX + "SET_FEED_REFERENCE(CANON_XYZ)"
    yield PREFIX + "ON_RESET()"
    last_g5x, last_g92 = g5x, g92
    for c in cmds:
        frame = c.frame
        if not isinstance(c, SetMode):
            g5x, g92 = _offsets(frame)
            if g5x != last_g5x:
                yield PREFIX + g5x
                last_g5x = g5x
            if g92 != last_g92:
                yield PREFIX + g92
                last_g92 = g92
        match c:
            case Rapid():
                yield PREFIX + "STRAIGHT_TRAVERSE(" + ", ".join(map(_f, _pos(c.end, frame))) + ")"
            case Linear():
                yield PREFIX + "STRAIGHT_FEED(" + ", ".join(map(_f, _pos(c.end, frame))) + ")"
            case Arc():
                yield PREFIX + _arc(c)
            case Dwell():
                yield PREFIX + f"DWELL({_f(c.seconds)})"
            case FeedRate():
                yield PREFIX + f"SET_FEED_RATE({_f(c.feed)})"
            case SpindleSpeed():
                yield PREFIX + f"SET_SPINDLE_SPEED({_f(c.rpm)})"
            case Spindle():
                yield PREFIX + {
                    SpindleState.CW: "START_SPINDLE_CLOCKWISE()",
                    SpindleState.CCW: "START_SPINDLE_COUNTERCLOCKWISE()",
                    SpindleState.OFF: "STOP_SPINDLE_TURNING()",
                    SpindleState.ORIENT: "ORIENT_SPINDLE(0.0000, 0)",
                }[c.state]
            case Coolant():
                yield PREFIX + {CoolantState.FLOOD: "FLOOD_ON()", CoolantState.MIST: "MIST_ON()",
                                CoolantState.OFF: "FLOOD_OFF()"}[c.state]
                if c.state is CoolantState.OFF:
                    yield PREFIX + "MIST_OFF()"
            case SelectTool():
                yield PREFIX + f"SELECT_TOOL({c.tool})"
            case ToolChange():
                yield PREFIX + "CHANGE_TOOL()"
            case Stop():
                yield PREFIX + {
                    StopKind.PROGRAM_STOP: "PROGRAM_STOP()",
                    StopKind.OPTIONAL_STOP: "OPTIONAL_PROGRAM_STOP()",
                    StopKind.PROGRAM_END: "PROGRAM_END()",
                    StopKind.END_REWIND: "PROGRAM_END()",
                }[c.kind]
            case Comment():
                yield PREFIX + f'COMMENT("{c.text}")'
            case Message():
                yield PREFIX + f'MESSAGE("{c.text}")'
            case SetMode():
                yield from _set_mode(c, last_g5x, last_g92)
                last_g5x, last_g92 = _offsets(frame)
            case Aux() | Wait():
                pass


def _set_mode(c: SetMode, last_g5x: str, last_g92: str) -> Iterator[str]:
    frame = c.frame
    if c.name == "plane":
        yield PREFIX + f"SELECT_PLANE({_PLANES[frame.plane]})"
    elif c.name == "units":
        yield PREFIX + f"USE_LENGTH_UNITS({_UNITS[frame.units]})"
    elif c.name in ("g5x_offset", "g92_offset", "g52_offset"):
        g5x, g92 = _offsets(frame)
        if c.name == "g5x_offset" or g5x != last_g5x:
            yield PREFIX + g5x
        if g92 != last_g92 or c.name != "g5x_offset":
            yield PREFIX + g92
    elif c.name == "tool_length_offset":
        z = frame.tool_length_mm / frame.units.mm_per_unit
        rest = ", ".join(["0.0000"] * 6)
        yield PREFIX + f"USE_TOOL_LENGTH_OFFSET(0.0000, 0.0000, {_f(z)}, {rest})"
    elif c.name == "path_mode":  # value: a PathMode, or (mode, P tolerance mm, Q naive-CAM mm | None) (G64 P Q)
        mode_v, tol_mm, naive_mm = c.value if isinstance(c.value, tuple) else (c.value, 0.0, None)
        mode = {PathMode.EXACT_STOP: "CANON_EXACT_STOP", PathMode.EXACT_PATH: "CANON_EXACT_PATH"}.get(
            mode_v, "CANON_CONTINUOUS")
        k = frame.units.mm_per_unit
        yield PREFIX + f"SET_MOTION_CONTROL_MODE({mode}, {_f(tol_mm / k)})"
        if naive_mm is not None:
            yield PREFIX + f"SET_NAIVECAM_TOLERANCE({_f(naive_mm / k)})"
    elif c.name == "feed_mode":
        yield PREFIX + f"SET_FEED_MODE({1 if c.value == 'per_rev' else 0})"


def _arc(c: Arc) -> str:
    frame = c.frame
    k = frame.units.mm_per_unit
    p = c.plane
    e1, e2, en = c.end[p.first] / k, c.end[p.second] / k, c.end[p.normal] / k
    c1, c2 = c.center[p.first] / k, c.center[p.second] / k
    args = [_f(e1), _f(e2), _f(c1), _f(c2), str(c.turns), _f(en), _f(c.end[3]), _f(c.end[4]), _f(c.end[5])]
    return "ARC_FEED(" + ", ".join(args) + ")"


def emit_canon(cmds: Iterable[Command], initial_frame: Frame | None = None) -> Iterator[str]:
    """Lines with newlines, for writers."""
    for line in canon_lines(cmds, initial_frame=initial_frame):
        yield line + "\n"
