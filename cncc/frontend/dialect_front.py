"""Front ends of the dialects that need more than the Fanuc-family path.

``lower_checked`` is what :func:`cncc.frontend.lower` calls for a dialect with a
``checker`` (grbl: every block is checked as the controller would before it runs;
series8: the SERIES 8 block semantics of :mod:`cncc.frontend.series8`) or with the
``linuxcnc`` macro flavour (O-word control flow and named parameters,
run by :mod:`cncc.frontend.linuxcnc`).
"""

from __future__ import annotations

from collections.abc import Iterator

from cncc.diagnostics import DiagnosticSink
from cncc.dialects import Dialect
from cncc.frontend.interp import InterpOptions, Interpreter
from cncc.frontend.parser import ParseOptions, Parser
from cncc.ir import Command
from cncc.source import SourceFile


def lower_checked(src: SourceFile, dialect: Dialect, sink: DiagnosticSink, options: InterpOptions,
                  macro: object = None) -> Iterator[Command]:
    if dialect.raw.get("checker") == "series8":
        from cncc.frontend.series8.front import lower_series8

        return lower_series8(src, dialect, sink, options)
    parser = Parser(dialect, sink, ParseOptions(strict=options.strict))
    interp = Interpreter(dialect, sink, src.source_id, options)
    if dialect.macro_flavour == "linuxcnc":
        from cncc.frontend.linuxcnc.executor import run_linuxcnc

        return run_linuxcnc(src, dialect, sink, interp, parser, macro)
    blocks = parser.blocks(src)
    if dialect.raw.get("checker") == "grbl":
        from cncc.frontend.grbl import GrblChecker

        blocks = GrblChecker(interp, src).filter(blocks)
    return interp.run(blocks)
