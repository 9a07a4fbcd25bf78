"""Front end: program text -> syntax blocks -> IR commands.

``lower(src, dialect, sink, options)`` is the one entry point the driver uses: it
parses ``src`` with the dialect's grammar and lowers the blocks with the modal
interpreter, streaming commands.
"""

from __future__ import annotations

from collections.abc import Iterator

from cncc.diagnostics import DiagnosticSink
from cncc.dialects import Dialect
from cncc.frontend.fastpath import is_straight_line, lower_straight
from cncc.frontend.interp import InterpOptions, Interpreter
from cncc.frontend.macro import MacroOptions, needs_executor, run_program
from cncc.frontend.macro.remap import remaps_cycles
from cncc.frontend.parser import ParseOptions, Parser
from cncc.frontend.tape import before_tape_end
from cncc.ir import Command
from cncc.source import SourceFile

__all__ = ["InterpOptions", "Interpreter", "MacroOptions", "ParseOptions", "Parser", "before_tape_end", "lower"]


def lower(src: SourceFile, dialect: Dialect, sink: DiagnosticSink,
          options: InterpOptions | None = None, macro: MacroOptions | None = None) -> Iterator[Command]:
    """Parse and interpret ``src``; yield IR commands in program order.

    Programs of a dialect with a macro flavour (``fanuc``, ``szgh``) that use
    variables, calls, jumps or loops run on the macro executor (``macro`` holds its
    command-line options: ``-D`` presets, ``-I`` folders, the step budget ...).
    """
    opts = options or InterpOptions()
    if dialect.raw.get("tape_end"):
        src = before_tape_end(src)
    if dialect.raw.get("checker") or dialect.macro_flavour == "linuxcnc":  # grbl's checks, LinuxCNC O-words
        from cncc.frontend.dialect_front import lower_checked

        return lower_checked(src, dialect, sink, opts, macro)
    if is_straight_line(src.text, dialect) and not remaps_cycles(dialect):
        return lower_straight(src, dialect, sink, opts)
    if needs_executor(src.text, dialect):
        return run_program(src, dialect, sink, opts, macro)
    parser = Parser(dialect, sink, ParseOptions(strict=opts.strict))
    interp = Interpreter(dialect, sink, src.source_id, opts)
    return interp.run(parser.blocks(src))
