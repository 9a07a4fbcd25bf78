"""Macro languages: Fanuc macro B and SZGH, with subprograms and calls.

``run_program(src, dialect, sink, interp_options, macro_options)`` is the entry the
front end uses for dialects whose ``macro_flavour`` is ``fanuc`` or ``szgh``: it
parses the program, runs it with :class:`~cncc.frontend.macro.executor.Executor`
and yields IR commands.  ``needs_executor`` tells whether a program text uses any
macro, call or jump feature at all (if not, the plain interpreter is enough).
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterator

from cncc.diagnostics import DiagnosticSink
from cncc.dialects import Dialect
from cncc.frontend.interp import InterpOptions, Interpreter
from cncc.frontend.macro.executor import EXEC_OPS, Executor, MacroOptions
from cncc.frontend.macro.remap import remaps_cycles
from cncc.frontend.parser import ParseOptions, Parser
from cncc.frontend.syntax import Block
from cncc.ir import Command
from cncc.source import SourceFile

MACRO_FLAVOURS = frozenset({"fanuc", "szgh"})


def _code_pattern(dialect: Dialect) -> re.Pattern[str]:
    return dialect.derived("macro.code_pattern", _build_code_pattern)


def _hints(dialect: Dialect) -> re.Pattern[str]:
    """Variables, expressions, assignments, or one of the dialect's ``executor_marks``."""
    return dialect.derived("macro.hints", _build_hints)


def _build_hints(dialect: Dialect) -> re.Pattern[str]:
    marks = [re.escape(m) for m in dialect.lexicon.executor_marks]
    return re.compile("|".join([r"#", r"\[", "=", *marks]), re.IGNORECASE)


def _build_code_pattern(dialect: Dialect) -> re.Pattern[str]:
    alts = []
    for c in dialect.codes.values():
        if c.op in EXEC_OPS:
            whole, frac = divmod(c.tenths, 10)
            num = f"0*{whole}" + (rf"\.{frac}" if frac else r"(?![\d.])")
            alts.append(f"{c.letter}[ \t]*{num}")
    if dialect.macro_flavour == "szgh":
        alts.append(r"M[ \t]*[12]8\d\d")
    return re.compile("|".join(alts) or "$^", re.IGNORECASE)


def needs_executor(text: str, dialect: Dialect) -> bool:
    """Whether ``text`` uses macro statements, calls, jumps or loops."""
    if dialect.macro_flavour not in MACRO_FLAVOURS:
        return False
    if remaps_cycles(dialect):
        return True  # User P500-P504: cycle codes call programs
    return _hints(dialect).search(text) is not None or _code_pattern(dialect).search(text) is not None


def run_program(src: SourceFile, dialect: Dialect, sink: DiagnosticSink, options: InterpOptions,
                macro: MacroOptions | None = None) -> Iterator[Command]:
    """Run ``src`` with the macro executor; yield IR commands in execution order."""
    from cncc.frontend.macro.library import is_library, run_library

    def parse_with(into: DiagnosticSink) -> Callable[[SourceFile], list[Block]]:
        parser = Parser(dialect, into, ParseOptions(strict=options.strict))
        if dialect.raw.get("tape_end"):  # called program files end at their closing '%' too
            from cncc.frontend.tape import before_tape_end

            return lambda source: list(parser.blocks(before_tape_end(source)))
        return lambda source: list(parser.blocks(source))

    if dialect.macro_flavour == "fanuc" and is_library(src.text):  # called programs: unknown arguments
        return run_library(src, dialect, sink, options, macro or MacroOptions(), parse_with)
    interp = Interpreter(dialect, sink, src.source_id, options)
    ex = Executor(dialect, sink, interp, macro or MacroOptions(), parse_with(sink))
    return ex.run(src)


__all__ = ["MACRO_FLAVOURS", "MacroOptions", "needs_executor", "run_program"]
