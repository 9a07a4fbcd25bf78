"""LinuxCNC's rs274ngc language: O-word control flow and named parameters (in progress)."""

from __future__ import annotations

from collections.abc import Iterator

from cncc.diagnostics import DiagnosticSink
from cncc.dialects import Dialect
from cncc.frontend.interp import Interpreter
from cncc.frontend.parser import Parser
from cncc.ir import Command
from cncc.source import SourceFile


def run_linuxcnc(src: SourceFile, dialect: Dialect, sink: DiagnosticSink, interp: Interpreter, parser: Parser,
                 macro: object = None) -> Iterator[Command]:
    return interp.run(parser.blocks(src))
