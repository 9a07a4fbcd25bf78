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

from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass
from typing import Any

from cncc.backends.canon_format import CanonFormat
from cncc.ir import (
    MODE_TYPES,
    Arc,
    Aux,
    Command,
    Comment,
    Coolant,
    CoolantState,
    Dwell,
    FeedMode,
    FeedRate,
    Frame,
    InterpreterReport,
    Linear,
    Message,
    ModeCommand,
    NurbsFeed,
    PathMode,
    Plane,
    Probe,
    Rapid,
    RigidTap,
    SelectTool,
    SetFeedMode,
    SetFeedOverride,
    SetG92Offset,
    SetLocalOffset,
    SetOverrides,
    SetPathMode,
    SetPlane,
    SetSpindleMode,
    SetToolLength,
    SetToolNumber,
    SetUnits,
    SetWorkSystem,
    SetXyRotation,
    Spindle,
    SpindleSpeed,
    SpindleState,
    SpindleSync,
    Stop,
    StopKind,
    ToolChange,
    Units,
    Vec6,
    Wait,
    WriteToolTable,
)
from cncc.ir.batch import Item, MoveBatch

PREFIX = " N..... "
_PLANES = {Plane.XY: "CANON_PLANE_XY", Plane.YZ: "CANON_PLANE_YZ", Plane.ZX: "CANON_PLANE_XZ"}
_UNITS = {Units.MM: "CANON_UNITS_MM", Units.INCH: "CANON_UNITS_INCHES"}
_FOLDED: dict[type[RigidTap | NurbsFeed | Probe], str] = {  # [canon] keys
    RigidTap: "rigid_tap", NurbsFeed: "nurbs_feed", Probe: "probe"}


def _f(x: float) -> str:
    s = f"{x:.4f}"
    return "0.0000" if s == "-0.0000" else s


_POS6 = "%.4f, %.4f, %.4f, %.4f, %.4f, %.4f"


def _pos_text(p: Vec6, frame: Frame) -> str:
    """The six coordinates as ``_f`` writes them, joined (one format call per move)."""
    k = frame.units.mm_per_unit
    s = _POS6 % (p[0] / k, p[1] / k, p[2] / k, p[3], p[4], p[5])
    # '-' only starts a number, and every number has four decimals: a '-0.0000' is a whole one
    return s.replace("-0.0000", "0.0000") if "-0.0000" in s else s


def _offsets(frame: Frame) -> tuple[str, str]:
    k = frame.units.mm_per_unit
    w = frame.work_offset_mm
    g = [frame.local_offset_mm[i] + frame.g92_offset_mm[i] for i in range(6)]
    g5x = f"SET_G5X_OFFSET({frame.work_index}, " + ", ".join(
        _f(w[i] / k if i < 3 else w[i]) for i in range(6)) + ")"
    g92 = "SET_G92_OFFSET(" + ", ".join(_f(g[i] / k if i < 3 else g[i]) for i in range(6)) + ")"
    return g5x, g92


def canon_lines(cmds: Iterable[Item], *, initial_frame: Frame | None = None,
                fmt: CanonFormat | None = None) -> Iterator[str]:
    """Yield the trace lines (without newlines) for ``cmds``; ``fmt`` words the calls (default: cncc's)."""
    fmt = fmt or CanonFormat()
    frame0 = initial_frame or Frame()
    g5x, g92 = _offsets(frame0)
    yield PREFIX + f"USE_LENGTH_UNITS({_UNITS[frame0.units]})"
    yield PREFIX + g5x
    yield PREFIX + g92
    yield PREFIX + "SET_XY_ROTATION(0.0000)"
    yield PREFIX + "SET_FEED_REFERENCE(CANON_XYZ)"
    yield PREFIX + "ON_RESET()"
    last_g5x, last_g92 = g5x, g92
    skip = [0]  # commands folded into one call (RIGID_TAP, NURBS_FEED) that are not written
    offsets: dict[int, tuple[Frame, tuple[str, str]]] = {}  # frames are shared: format once each
    coolant = _CoolantTrace(fmt)
    for c in _texts(cmds, fmt, skip):
        if skip[0]:
            skip[0] -= 1
            continue
        if coolant.active:
            yield from coolant.before(c)
            if coolant.hold(c):
                continue
        frame = c.frame
        if not isinstance(c, MODE_TYPES):
            entry = offsets.get(id(frame))
            if entry is None or entry[0] is not frame:
                entry = offsets[id(frame)] = (frame, _offsets(frame))
            g5x, g92 = entry[1]
            if g5x != last_g5x:
                yield PREFIX + g5x
                last_g5x = g5x
            if g92 != last_g92:
                yield PREFIX + g92
                last_g92 = g92
        if isinstance(c, _Text):
            yield c.text
            continue
        line = _one_line(c, fmt)
        if line is not None:
            yield PREFIX + line
            continue
        match c:
            case InterpreterReport():
                yield from _report(c, fmt)
            case RigidTap() | NurbsFeed() | Probe() if fmt.has(_FOLDED[type(c)]):
                skip[0] = c.folded
                yield from _lines(fmt, _FOLDED[type(c)], **_folded_fields(c))
            case _ if isinstance(c, MODE_TYPES):
                yield from _set_mode(c, last_g5x, last_g92, fmt)
                last_g5x, last_g92 = _offsets(frame)
            case Aux() | Wait():
                pass
            case _:
                key, fields = _other(c)
                yield from _lines(fmt, key, **fields)
    yield from coolant.before(None)
    yield from _lines(fmt, "end_of_trace")


class _CoolantTrace:
    """Where the dialect words them (``mist_off``/``flood_off`` in ``[canon]``), the coolant-off of a
    program end prints only the coolants that are on, as LinuxCNC's M2/M30 does (M9 prints both):
    a coolant off just before the program end is held until that end is seen."""

    def __init__(self, fmt: CanonFormat) -> None:
        self.fmt = fmt
        self.active = fmt.has("mist_off") and fmt.has("flood_off")
        self.mist = self.flood = False
        self.held: Coolant | None = None

    def hold(self, c: object) -> bool:
        if not isinstance(c, Coolant):
            return False
        if c.state is CoolantState.OFF:
            self.held = c
            return True
        self.mist, self.flood = self.mist or c.state is CoolantState.MIST, self.flood or c.state is CoolantState.FLOOD
        return False

    def before(self, c: object) -> Iterator[str]:
        if self.held is None:
            return
        self.held = None
        if isinstance(c, Stop) and c.kind in (StopKind.PROGRAM_END, StopKind.END_REWIND):
            keys = [k for k, on in (("mist_off", self.mist), ("flood_off", self.flood)) if on]
        else:
            keys = ["coolant_off"]
        self.mist = self.flood = False
        for k in keys:
            yield from _lines(self.fmt, k)
@dataclass(frozen=True, slots=True)
class _Text:
    """A batch of moves written by :func:`cncc.backends.canon_batch.batch_text`."""

    frame: Frame
    text: str


def _texts(items: Iterable[Item], fmt: CanonFormat, skip: list[int]) -> Iterator[Command | _Text]:
    """The commands, with each batch of moves as its text (or, when that cannot be made exactly,
    or while folded commands are skipped, as its commands)."""
    for x in items:
        if isinstance(x, MoveBatch):
            text = None
            if not skip[0]:
                from cncc.backends.canon_batch import batch_text

                text = batch_text(x, fmt.feed_in_program_units)
            if text is None:
                yield from x.commands()
            else:
                yield _Text(x.frame, text)
        elif not isinstance(x, MoveBatch):
            yield x


def _report(c: InterpreterReport, fmt: CanonFormat) -> Iterator[str]:
    """An interpreter report, written with its [canon.comments] text (none: not written)."""
    text = fmt.comments.get(c.key)
    if text is not None:
        yield PREFIX + f'COMMENT("{text}")'


def _one_line(c: Command, fmt: CanonFormat) -> str | None:
    """The call of a move, dwell, feed, comment or message (None for the other commands)."""
    match c:
        case Rapid():
            return "STRAIGHT_TRAVERSE(" + _pos_text(c.end, c.frame) + ")"
        case Linear():
            return "STRAIGHT_FEED(" + _pos_text(c.end, c.frame) + ")"
        case Arc():
            return _arc(c)
        case Dwell():
            return f"DWELL({_f(c.seconds)})"
        case FeedRate():
            feed = c.feed / c.frame.units.mm_per_unit if fmt.feed_in_program_units else c.feed
            return f"SET_FEED_RATE({_f(feed)})"
        case Comment():
            return f'COMMENT("{c.text}")'
        case Message():
            return f'MESSAGE("{c.text}")'
    return None


def _lines(fmt: CanonFormat, key: str, **fields: Any) -> Iterator[str]:
    for line in fmt.lines(key, **fields):
        yield PREFIX + line


def _other(c: Command) -> tuple[str, dict[str, Any]]:
    """The template key and fields of a command that is not a move or a mode."""
    match c:
        case SpindleSpeed():
            return "spindle_speed", {"rpm": float(c.rpm)}
        case Spindle():
            return {SpindleState.CW: "spindle_cw", SpindleState.CCW: "spindle_ccw", SpindleState.OFF: "spindle_off",
                    SpindleState.ORIENT: "spindle_orient"}[c.state], {}
        case Coolant():
            return {CoolantState.FLOOD: "flood_on", CoolantState.MIST: "mist_on",
                    CoolantState.OFF: "coolant_off"}[c.state], {}
        case SelectTool():
            return "select_tool", {"tool": c.tool}
        case ToolChange():
            return "tool_change", {"tool": c.tool}
        case Stop():
            return {StopKind.PROGRAM_STOP: "program_stop", StopKind.OPTIONAL_STOP: "optional_stop",
                    StopKind.PROGRAM_END: "program_end", StopKind.END_REWIND: "program_end_rewind"}[c.kind], {}
    return "none", {}


def _folded_fields(c: RigidTap | NurbsFeed | Probe) -> dict[str, Any]:
    if isinstance(c, RigidTap | Probe):
        k = c.frame.units.mm_per_unit
        end = c.end
        return {"x": end[0] / k, "y": end[1] / k, "z": end[2] / k, "a": end[3], "b": end[4], "c": end[5]}
    return {"points": c.points, "order": c.order}


def _offset_lines(c: SetWorkSystem | SetG92Offset | SetLocalOffset, last_g5x: str, last_g92: str) -> Iterator[str]:
    g5x, g92 = _offsets(c.frame)
    work = isinstance(c, SetWorkSystem)
    if work or g5x != last_g5x:
        yield PREFIX + g5x
    if g92 != last_g92 or not work:
        yield PREFIX + g92


def _set_mode(c: ModeCommand, last_g5x: str, last_g92: str, fmt: CanonFormat) -> Iterator[str]:
    frame = c.frame
    match c:
        case SetPlane():
            yield PREFIX + f"SELECT_PLANE({_PLANES[frame.plane]})"
        case SetUnits():
            yield PREFIX + f"USE_LENGTH_UNITS({_UNITS[frame.units]})"
        case SetWorkSystem() | SetG92Offset() | SetLocalOffset():
            yield from _offset_lines(c, last_g5x, last_g92)
        case SetToolLength():
            yield from _lines(fmt, "tool_length_offset", z=frame.tool_length_mm / frame.units.mm_per_unit)
        case SetXyRotation():
            yield from _lines(fmt, "xy_rotation", deg=float(c.angle_deg))
        case SetPathMode():
            yield from _path_mode(c, fmt)
        case _:
            yield from _machine_mode(c, fmt)


def _path_mode(c: SetPathMode, fmt: CanonFormat) -> Iterator[str]:
    k = c.frame.units.mm_per_unit
    key = {PathMode.EXACT_STOP: "motion_exact_stop", PathMode.EXACT_PATH: "motion_exact_path"}.get(
        c.mode, "motion_continuous")
    yield from _lines(fmt, key, tol=c.tolerance_mm / k)
    if c.naive_cam_mm is not None:
        yield from _lines(fmt, "naivecam_tolerance", tol=c.naive_cam_mm / k)


def _machine_mode(c: ModeCommand, fmt: CanonFormat) -> Iterator[str]:
    """Feed mode, spindle synchronisation and mode, tool table and overrides."""
    match c:
        case SetFeedMode():
            yield from _lines(fmt, "feed_mode", mode=1 if c.mode is FeedMode.PER_REV else 0)
        case SpindleSync() if c.pitch_mm:
            yield from _lines(fmt, "spindle_sync_on", pitch=float(c.pitch_mm) / c.frame.units.mm_per_unit)
        case SpindleSync():  # 0: the synchronisation ends
            yield from _lines(fmt, "spindle_sync_off")
        case WriteToolTable():
            u = 25.4 if fmt.tool_table_inch else 1.0
            yield from _lines(fmt, "tool_table_entry", tool=c.tool, x=c.x_mm / u, z=c.length_mm / u,
                              diameter=c.diameter_mm / u, front=float(c.front_angle_deg),
                              back=float(c.back_angle_deg), orientation=c.orientation)
        case SetOverrides():
            yield from _lines(fmt, "overrides_on" if c.enabled else "overrides_off")
        case SetFeedOverride():
            yield from _lines(fmt, "feed_override_on" if c.enabled else "feed_override_off")
        case SetSpindleMode():
            yield from _lines(fmt, "spindle_mode", css_max=float(c.css_max_rpm))
        case SetToolNumber():  # M61 Q
            yield from _lines(fmt, "tool_number", tool=c.tool)


def _arc(c: Arc) -> str:
    frame = c.frame
    k = frame.units.mm_per_unit
    p = c.plane
    e1, e2, en = c.end[p.first] / k, c.end[p.second] / k, c.end[p.normal] / k
    c1, c2 = c.center[p.first] / k, c.center[p.second] / k
    args = [_f(e1), _f(e2), _f(c1), _f(c2), str(c.turns), _f(en), _f(c.end[3]), _f(c.end[4]), _f(c.end[5])]
    return "ARC_FEED(" + ", ".join(args) + ")"


def emit_canon(cmds: Iterable[Item], initial_frame: Frame | None = None,
               table: Mapping[str, Any] | None = None) -> Iterator[str]:
    """Lines with newlines, for writers; ``table`` is the dialect's ``[canon]`` table."""
    for line in canon_lines(cmds, initial_frame=initial_frame, fmt=CanonFormat(table)):
        yield line + "\n"
