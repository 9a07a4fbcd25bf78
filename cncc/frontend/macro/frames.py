"""Call frames and the modal (G66) call record of the macro executor."""

from __future__ import annotations

from dataclasses import dataclass, field

from cncc.frontend.macro.program import Unit
from cncc.source import Span


@dataclass(slots=True)
class CallFrame:
    """One level of the call stack: a program section being run."""

    unit: Unit
    first: int  # section range [first, last) of block indexes
    last: int
    entry: int  # where a repetition starts again
    pc: int  # the next block to run
    kind: str  # "main", "M98", "G65", "G66", "user"
    call_span: Span | None  # the calling block (None for the main program)
    name: str = ""
    repeats_left: int = 0
    scoped: bool = False  # pushed a local-variable scope (G65, G66, user macros)
    args: dict[int, float] = field(default_factory=dict)
    block_loops: list[list[int]] = field(default_factory=list)  # SZGH G22: [G22 index, passes left]
    in_modal: bool = False  # inside a G66 call: moves do not call again


@dataclass(frozen=True, slots=True)
class ModalCall:
    """The G66 call in force."""

    unit: Unit
    index: int
    name: str
    repeats: int
    args: dict[int, float]
    span: Span
