"""A running LinuxCNC program or subroutine: the executor's call stack entry.

Apart from :mod:`~cncc.frontend.linuxcnc.executor` so that the O-word and M98 control
flow (:mod:`~cncc.frontend.linuxcnc.control`) can push frames without importing the
executor (no import circle; tests/test_layers.py).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from cncc.frontend.linuxcnc.flow import FlowIndex
from cncc.source import Span


@dataclass(slots=True)
class Frame:
    """One running program or subroutine."""

    index: FlowIndex
    pc: int
    name: str = "main"
    return_pc: int = -1
    caller: Frame | None = None
    call_span: Span | None = None
    repeats: dict[int, int] = field(default_factory=dict)
    m98_count: int = 0
    m98_start: int = 0


__all__ = ["Frame"]
