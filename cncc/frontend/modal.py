"""Modal state: a frozen snapshot of the modes in force, replaced when one changes."""

from __future__ import annotations

from dataclasses import dataclass, field

from cncc.ir import Motion, Vec6, ZERO6


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
    codes: tuple[tuple[str, str], ...] = ()  # (group, code name) in force, for #4001.. and hover
    cycle_return_initial: bool = True
    css: bool = False
    spindle_clamp_rpm: float = 0.0  # G92 S
    default_feed_noted: bool = False


@dataclass(frozen=True, slots=True)
class Reference:
    """Stored G28/G30 intermediate point (program coordinates, mm)."""

    point: Vec6 = ZERO6
    axes: tuple[bool, ...] = (False,) * 6
