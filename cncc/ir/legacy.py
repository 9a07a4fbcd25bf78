"""Deprecated: the former ``SetMode(span, frame, name, value)`` as a factory of typed mode commands.

Kept only so that branches written against the stringly-typed IR merge and run; nothing
in cncc calls it.  Convert each use to the typed class (the table below says which) and
delete this module when no caller is left.  An unknown name raises ``ValueError``.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import cast

from cncc.ir import modes as m
from cncc.ir.frame import CompSide, Frame, Mirror, Plane, Rotation, Scaling, Units, Vec6
from cncc.ir.pathmode import PathMode
from cncc.source import Span


def _path(span: Span, frame: Frame, value: object, for_cycle: bool) -> m.SetPathMode:
    if isinstance(value, tuple):
        mode, tol, naive = value
        return m.SetPathMode(span, frame, cast(PathMode, mode), float(tol), None if naive is None else float(naive),
                             for_cycle)
    return m.SetPathMode(span, frame, cast(PathMode, value), for_cycle=for_cycle)


def _tool_entry(span: Span, frame: Frame, value: object) -> m.WriteToolTable:
    v = cast(tuple[object, ...], value)
    tool, length, dia = cast(int, v[0]), cast(float, v[1]), cast(float, v[2])
    if len(v) > 3:
        x, front, back, orient = cast(tuple[float, float, float, int], v[3])
        return m.WriteToolTable(span, frame, tool, length, dia, x, front, back, orient)
    return m.WriteToolTable(span, frame, tool, length, dia)


def _units(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    return m.SetUnits(span, frame, cast(Units, value))


def _plane(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    return m.SetPlane(span, frame, cast(Plane, value))


def _feed_mode(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    return m.SetFeedMode(span, frame, m.FeedMode(value))


def _path_mode(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    return _path(span, frame, value, name == "cycle_path_mode")


def _cutter_comp(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    return m.SetCutterComp(span, frame, cast(CompSide, value))


def _tool_length_offset(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    return m.SetToolLength(span, frame, float(cast(float, value)))


def _g5x_offset(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    return m.SetWorkSystem(span, frame, cast(int, value))


def _g92_offset(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    return m.SetG92Offset(span, frame, cast(Vec6, value))


def _g92_preset(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    return m.PresetG92(span, frame, tuple(cast(tuple[int, ...], value)))


def _g52_offset(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    return m.SetLocalOffset(span, frame, cast(Vec6, value))


def _xy_rotation(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    return m.SetXyRotation(span, frame, float(cast(float, value)))


def _polar(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    return m.SetPolar(span, frame, cast(tuple[float, float] | None, value))


def _scaling(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    return m.SetScaling(span, frame, cast(Scaling | None, value))


def _mirror(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    return m.SetMirror(span, frame, cast(Mirror | None, value))


def _rotation(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    return m.SetRotation(span, frame, cast(Rotation | None, value))


def _tool_table(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    return _tool_entry(span, frame, value)


def _work_table(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    index, old, new = cast(tuple[int, Vec6, Vec6], value)
    return m.WriteWorkTable(span, frame, index, old, new)


def _data_input(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    table, entry, got = cast(tuple[str, int, float], value)
    return m.WriteToolData(span, frame, m.ToolData(table), entry, got)


def _css_reference(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    radius, x = cast(tuple[float, float], value)
    return m.SetCssReference(span, frame, radius, x)


def _spindle_mode(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    return m.SetSpindleMode(span, frame, float(cast(float | None, value) or 0.0))


def _spindle_sync(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    return m.SpindleSync(span, frame, cast(float, value))


def _rigid_tap(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    end, folded = cast(tuple[Vec6, int], value)
    return m.RigidTap(span, frame, end, folded)


def _nurbs_feed(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    points, order, folded = cast(tuple[int, int, int], value)
    return m.NurbsFeed(span, frame, points, order, folded)


def _probe(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    end, op, folded = cast(tuple[Vec6, str, int], value)
    return m.Probe(span, frame, end, op, folded)


def _tool_number(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    return m.SetToolNumber(span, frame, int(cast(int, value)))


def _overrides(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    return m.SetOverrides(span, frame, bool(value))


def _feed_override(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    return m.SetFeedOverride(span, frame, bool(value))


def _held_axes(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    return m.HoldAxes(span, frame, cast(m.Held6, value))


def _call_begin(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    key, called = cast(tuple[str, str], value)
    return m.CallBoundary(span, frame, name == "call_begin", key, called)


def _output(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    signal, on = cast(tuple[str, bool], value)
    return m.SetOutput(span, frame, signal, on)


def _smoothing(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    code, words = cast(tuple[str, tuple[tuple[str, float], ...]], value)
    return m.SetSmoothing(span, frame, code, words)


def _report(span: Span, frame: Frame, name: str, value: object) -> m.ModeCommand:
    return m.InterpreterReport(span, frame, str(value))


_BUILDERS: dict[str, Callable[[Span, Frame, str, object], m.ModeCommand]] = {
    "units": _units,
    "plane": _plane,
    "feed_mode": _feed_mode,
    "path_mode": _path_mode,
    "cycle_path_mode": _path_mode,
    "cutter_comp": _cutter_comp,
    "tool_length_offset": _tool_length_offset,
    "g5x_offset": _g5x_offset,
    "g92_offset": _g92_offset,
    "g92_preset": _g92_preset,
    "g52_offset": _g52_offset,
    "xy_rotation": _xy_rotation,
    "polar": _polar,
    "scaling": _scaling,
    "mirror": _mirror,
    "rotation": _rotation,
    "tool_table": _tool_table,
    "work_table": _work_table,
    "data_input": _data_input,
    "css_reference": _css_reference,
    "spindle_mode": _spindle_mode,
    "spindle_sync": _spindle_sync,
    "rigid_tap": _rigid_tap,
    "nurbs_feed": _nurbs_feed,
    "probe": _probe,
    "tool_number": _tool_number,
    "overrides": _overrides,
    "feed_override": _feed_override,
    "held_axes": _held_axes,
    "call_begin": _call_begin,
    "call_end": _call_begin,
    "output": _output,
    "smoothing": _smoothing,
    "interpreter_report": _report,
}


def set_mode(span: Span, frame: Frame, name: str, value: object = None) -> m.ModeCommand:
    """The typed mode command for a legacy ``(name, value)`` pair."""
    build = _BUILDERS.get(name)
    if build is None:
        raise ValueError(f"SetMode({name!r}): no typed mode command of that name; add one in cncc/ir/modes.py")
    return build(span, frame, name, value)


SetMode = set_mode
"""Deprecated alias, so that ``SetMode(span, frame, name, value)`` written elsewhere still builds a command."""
