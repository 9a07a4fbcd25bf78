"""Per-dialect wording of the canon trace: call templates as data.

The canon backend writes most calls the same way for every dialect.  Where a
controller's interpreter words a call differently (LinuxCNC 2.9 passes a spindle
number, prints ``CHANGE_TOOL(pocket)``, groups the nine tool offsets in threes ...),
the dialect's ``[canon]`` table overrides the template here.  A template is a string
or a list of strings (several lines; an empty list prints nothing) in
:meth:`str.format` syntax; numbers are passed as :class:`Num`, which prints ``%.4f``
by default and never ``-0.0000``.

Besides templates, ``[canon]`` may hold ``tool_table_units`` ("mm" or "inch"): the
units of ``SET_TOOL_TABLE_ENTRY`` (LinuxCNC prints the tool table in its internal
units, which are inches in the stand-alone ``rs274``), and ``feed_in_program_units``
(``SET_FEED_RATE`` in program units per minute, as LinuxCNC prints it and like every
position in the trace; ``false`` prints mm/min).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

DEFAULTS: dict[str, str | list[str]] = {
    "spindle_speed": "SET_SPINDLE_SPEED({rpm})",
    "spindle_cw": "START_SPINDLE_CLOCKWISE()",
    "spindle_ccw": "START_SPINDLE_COUNTERCLOCKWISE()",
    "spindle_off": "STOP_SPINDLE_TURNING()",
    "spindle_orient": "ORIENT_SPINDLE(0.0000, 0)",
    "select_tool": "SELECT_TOOL({tool})",
    "tool_change": "CHANGE_TOOL()",
    "flood_on": "FLOOD_ON()",
    "mist_on": "MIST_ON()",
    "mist_off": [],  # a dialect that turns off only the coolants that are on at a program end words these two
    "flood_off": [],
    "coolant_off": ["FLOOD_OFF()", "MIST_OFF()"],
    "tool_length_offset": "USE_TOOL_LENGTH_OFFSET(0.0000, 0.0000, {z}, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000, "
                          "0.0000)",
    "motion_continuous": "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, {tol})",
    "motion_exact_path": "SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH, {tol})",
    "motion_exact_stop": "SET_MOTION_CONTROL_MODE(CANON_EXACT_STOP, {tol})",
    "naivecam_tolerance": "SET_NAIVECAM_TOLERANCE({tol})",
    "feed_mode": "SET_FEED_MODE({mode})",
    "program_stop": "PROGRAM_STOP()",
    "optional_stop": "OPTIONAL_PROGRAM_STOP()",
    "program_end": "PROGRAM_END()",
    "program_end_rewind": "PROGRAM_END()",
    # Calls only some dialects print (empty: the IR marker prints nothing and the
    # primitive moves after it are written as usual).
    "tool_table_entry": [],  # G10 L1: {tool} {x} {z} {diameter} {front} {back} {orientation}
    "spindle_sync_on": [],  # G33 / G33.1 / tapping: {pitch} in program units per revolution
    "spindle_sync_off": [],
    "rigid_tap": [],  # G33.1 as one call {x} {y} {z}; the moves after the marker are not written
    "probe": "STRAIGHT_PROBE({x}, {y}, {z}, {a}, {b}, {c})",  # G38.x: the probe move (and back-off) after the marker
    "tool_number": [],  # M61 Q: {tool}
    "nurbs_feed": [],  # G5 / G5.1 / G5.2 as one call {points} {order}; its segments are not written
    "spindle_mode": [],
    "xy_rotation": [],  # after a work-system change: {deg}  # the spindle mode reset at a program end: {css_max}
    "overrides_on": [],  # M48, and after LinuxCNC's G84
    "overrides_off": [],  # M49, and during LinuxCNC's G84
    "feed_override_on": [],  # after a synchronised pass of LinuxCNC's G76
    "feed_override_off": [],  # before it
    "end_of_trace": [],  # lines after the last command (the stand-alone interpreter's resets)
}


class Num(float):
    """A float that formats as ``%.4f`` unless told otherwise, without a negative zero."""

    def __format__(self, spec: str) -> str:
        s = format(float(self), spec or ".4f")
        return s[1:] if s.startswith("-") and not s.strip("-0.") else s


class CanonFormat:
    """The templates in force: :data:`DEFAULTS` overridden by a dialect's ``[canon]``."""

    def __init__(self, table: Mapping[str, Any] | None = None) -> None:
        table = table or {}
        self.templates: dict[str, list[str]] = {}
        for key, value in {**DEFAULTS, **{k: v for k, v in table.items() if k in DEFAULTS}}.items():
            self.templates[key] = [value] if isinstance(value, str) else [str(v) for v in value]
        self.tool_table_inch = str(table.get("tool_table_units", "mm")) == "inch"
        self.feed_in_program_units = bool(table.get("feed_in_program_units", True))
        # [canon.comments]: the interpreter's COMMENT texts, by the key of an IR InterpreterReport
        self.comments: dict[str, str] = {str(k): str(v) for k, v in dict(table.get("comments", {})).items()}

    def has(self, key: str) -> bool:
        return bool(self.templates.get(key))

    def lines(self, key: str, **fields: Any) -> list[str]:
        """The lines of ``key`` with ``fields`` filled in (floats print as :class:`Num`)."""
        values = {k: Num(v) if isinstance(v, float) else v for k, v in fields.items()}
        return [t.format(**values) for t in self.templates.get(key, [])]
