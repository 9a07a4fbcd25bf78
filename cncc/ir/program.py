"""Program: the commands of one compilation plus where they came from."""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field

from cncc.ir.commands import Command
from cncc.ir.frame import ZERO6, Vec6
from cncc.source import SourceMap


@dataclass(slots=True)
class Program:
    """An IR program.

    ``commands`` may be a list (materialised) or any iterable (streamed); passes
    that need the whole program call :meth:`materialize`.
    """

    sources: SourceMap
    commands: Iterable[Command]
    dialect: str = "syntec"
    start_position_mm: Vec6 = ZERO6
    metadata: dict[str, object] = field(default_factory=dict)

    def materialize(self) -> list[Command]:
        if not isinstance(self.commands, list):
            self.commands = list(self.commands)
        return self.commands

    def __iter__(self) -> Iterator[Command]:
        return iter(self.commands)
