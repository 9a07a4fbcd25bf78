"""The front ends registered in :mod:`cncc.frontend.plugins`, one function each.

``lower_fanuc`` is the Fanuc family's path (the straight-line fast path, the macro
executor, the modal interpreter); ``lower_grbl`` checks every block as grbl would
before it runs; ``lower_linuxcnc`` runs O-word control flow and named parameters
(:mod:`cncc.frontend.linuxcnc`); ``lower_series8`` the SERIES 8 block semantics of
:mod:`cncc.frontend.series8`.  Each has the signature of
:data:`cncc.frontend.plugins.LowerFn`.
"""

from __future__ import annotations

from collections.abc import Iterator

from cncc.diagnostics import DiagnosticSink
from cncc.dialects import Dialect
from cncc.frontend.interp import InterpOptions, Interpreter
from cncc.frontend.parser import ParseOptions, Parser
from cncc.ir import Command
from cncc.source import SourceFile


def lower_fanuc(src: SourceFile, dialect: Dialect, sink: DiagnosticSink, options: InterpOptions,
                macro: object = None) -> Iterator[Command]:
    from cncc.frontend.fastpath import is_straight_line, lower_straight
    from cncc.frontend.macro import MacroOptions, needs_executor, run_program
    from cncc.frontend.macro.remap import remaps_cycles

    if is_straight_line(src.text, dialect) and not remaps_cycles(dialect):
        if options.batches:  # runs of plain moves as arrays (numpy, imported only here)
            from cncc.frontend.fastbatch import lower_batched

            return lower_batched(src, dialect, sink, options)  # type: ignore[return-value]
        return lower_straight(src, dialect, sink, options)
    if needs_executor(src.text, dialect):
        return run_program(src, dialect, sink, options, macro if isinstance(macro, MacroOptions) else None)
    parser = Parser(dialect, sink, ParseOptions(strict=options.strict))
    interp = Interpreter(dialect, sink, src.source_id, options)
    return interp.run(parser.blocks(src))


def lower_grbl(src: SourceFile, dialect: Dialect, sink: DiagnosticSink, options: InterpOptions,
               macro: object = None) -> Iterator[Command]:
    from cncc.frontend.grbl import GrblChecker

    parser = Parser(dialect, sink, ParseOptions(strict=options.strict))
    interp = Interpreter(dialect, sink, src.source_id, options)
    return interp.run(GrblChecker(interp, src).filter(parser.blocks(src)))


def lower_linuxcnc(src: SourceFile, dialect: Dialect, sink: DiagnosticSink, options: InterpOptions,
                   macro: object = None) -> Iterator[Command]:
    from cncc.frontend.linuxcnc.executor import run_linuxcnc

    parser = Parser(dialect, sink, ParseOptions(strict=options.strict))
    interp = Interpreter(dialect, sink, src.source_id, options)
    return run_linuxcnc(src, dialect, sink, interp, parser, macro)


def lower_series8(src: SourceFile, dialect: Dialect, sink: DiagnosticSink, options: InterpOptions,
                  macro: object = None) -> Iterator[Command]:
    from cncc.frontend.series8.front import lower_series8 as run

    return run(src, dialect, sink, options)
