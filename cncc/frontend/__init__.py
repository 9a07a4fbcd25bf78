"""Front end: program text -> syntax blocks -> IR commands.

``lower(src, dialect, sink, options)`` is the one entry point the driver uses: it
parses ``src`` with the dialect's grammar and lowers the blocks with the modal
interpreter, streaming commands.
"""

from __future__ import annotations

from collections.abc import Iterator

from cncc.diagnostics import DiagnosticSink
from cncc.dialects import Dialect
from cncc.frontend.interp import InterpOptions, Interpreter
from cncc.frontend.macro import MacroOptions
from cncc.frontend.parser import ParseOptions, Parser
from cncc.frontend.plugins import front_end
from cncc.frontend.tape import before_tape_end
from cncc.ir import Command
from cncc.source import SourceFile

__all__ = ["InterpOptions", "Interpreter", "MacroOptions", "ParseOptions", "Parser", "before_tape_end", "lower"]


def lower(src: SourceFile, dialect: Dialect, sink: DiagnosticSink,
          options: InterpOptions | None = None, macro: MacroOptions | None = None) -> Iterator[Command]:
    """Parse and interpret ``src``; yield IR commands in program order.

    The front end the dialect names (``frontend =``, :mod:`cncc.frontend.plugins`) does
    the work.  On the ``fanuc`` one, programs that use variables, calls, jumps or loops
    run on the macro executor (``macro`` holds its
    command-line options: ``-D`` presets, ``-I`` folders, the step budget ...).
    """
    opts = options or InterpOptions()
    if dialect.raw.get("tape_end"):
        src = before_tape_end(src)
    return front_end(dialect).lower(src, dialect, sink, opts, macro)
