"""Modal state: a frozen snapshot of the modes in force, replaced when one changes."""

from __future__ import annotations

from dataclasses import dataclass, field

from cncc.ir import ZERO6, Motion, Vec6


@dataclass(frozen=True, slots=True)
class ModalState:
    motion: str = "rapid"  # op of the motion group (01): rapid, linear, arc_cw, arc_ccw ...
    cycle: str = ""  # canned cycle in force (group 09), "" when cancelled
    incremental: bool = False
    per_rev: bool = False
    feed: float | None = None  # programmed F in program units per minute (or per rev)
    spindle_rpm: float = 0.0
    tool_selected: int = 0
    tool_loaded: int = 0
    path: Motion = field(default_factory=Motion)
    cycle_return_initial: bool = True
    css: bool = False
    spindle_clamp_rpm: float = 0.0  # G92 S
    default_feed_noted: bool = False


    def with_(self, **changes: object) -> ModalState:
        """A copy with ``changes`` (several times faster than ``dataclasses.replace``)."""
        o = object.__new__(ModalState)
        for name, setter in _SETTERS:
            setter(o, changes[name] if name in changes else getattr(self, name))
        return o


_SETTERS = tuple((name, getattr(ModalState, name).__set__) for name in ModalState.__dataclass_fields__)


@dataclass(frozen=True, slots=True)
class Reference:
    """Stored G28/G30 intermediate point (program coordinates, mm)."""

    point: Vec6 = ZERO6
    axes: tuple[bool, ...] = (False,) * 6
