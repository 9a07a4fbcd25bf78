"""Macro libraries and subprogram files linted without a caller.

A file whose programs end in ``M99`` and never in ``M02``/``M30`` is meant to be
called (``G65 P9010 X.. R..``, ``M98 P1000``).  Run on its own, its arguments are not
*vacant*, they are *unknown*: the caller gives them, and its modal state (F, the work
system ...) too.  Running it once with vacant arguments and no feed would report the
argument checks (``#3000`` alarms), moves from vacant words and "no feed rate" as
errors, which a controller never shows for a correct call.

So such a file is run twice, with private diagnostics: once as it stands (vacant
arguments, no modal state), once as a typical caller would leave it (every argument
letter set to a distinct number, a feed in force).  A problem both runs report is a
problem *whatever the arguments* and keeps its severity; a problem only one run
reports depends on the arguments and becomes a note (N0371) that says which run saw
it.  The commands are those of the run as it stands.

When another input of the same run calls one of the file's programs, the caller's
run checks it with the caller's arguments (the other inputs are on the search path
of :class:`~cncc.frontend.macro.program.ProgramLibrary`), and the file's own run
only notes that.
"""

from __future__ import annotations

import copy
import os
import re
from collections.abc import Callable, Iterator

from cncc import diagnostics as dg
from cncc.diagnostics import Diagnostic, DiagnosticSink, Severity
from cncc.dialects import Dialect
from cncc.frontend.interp import InterpOptions, Interpreter
from cncc.frontend.macro.executor import Executor, MacroOptions
from cncc.frontend.syntax import Block
from cncc.ir import Command
from cncc.source import SourceFile, Span

_PAREN = re.compile(r"\([^)\n]*\)?")
_RETURN = re.compile(r"(?<![A-Z\d.])M0*99(?![\d.])", re.I)
_END = re.compile(r"(?<![A-Z\d.])M0*(2|30)(?![\d.])", re.I)
_O_NUMBER = re.compile(r"^\s*[O:]\s*0*(\d{1,5})(?!\d)", re.I | re.M)
_CALL = re.compile(r"(?:G0*6[56]|M0*98)(?![\d.])[^\n(;]*?P\s*0*(\d{1,5})(?!\d)", re.I)
TYPICAL_FEED = 100.0
"""The feed in force in the "typical caller" run (program units per minute)."""


def is_library(text: str) -> bool:
    """Programs that return (M99) and never end (M02/M30): meant to be called."""
    code = _PAREN.sub(" ", text)
    return _RETURN.search(code) is not None and _END.search(code) is None


def program_numbers(text: str) -> set[int]:
    return {int(m.group(1)) for m in _O_NUMBER.finditer(_PAREN.sub(" ", text))}


def caller_in_run(src: SourceFile, run_files: tuple[str, ...]) -> str | None:
    """The first other input of the run that calls one of ``src``'s programs, or None."""
    mine = program_numbers(src.text)
    if not mine:
        return None
    here = os.path.realpath(src.name) if os.path.exists(src.name) else src.name
    for path in run_files:
        if path == "-" or not os.path.isfile(path) or os.path.realpath(path) == here:
            continue
        try:
            with open(path, encoding="utf-8", errors="replace") as fh:
                text = fh.read(2_000_000)
        except OSError:
            continue
        called = {int(m.group(1)) for m in _CALL.finditer(_PAREN.sub(" ", text))}
        if called & mine:
            return path
    return None


def typical_arguments(ex: Executor) -> dict[int, float]:
    """Every argument letter's variable set to a distinct value (A = 1, B = 2 ...)."""
    return {n: float(k + 1) for k, n in enumerate(sorted(set(ex.vars.layout.arguments.values())))}


def run_library(src: SourceFile, dialect: Dialect, sink: DiagnosticSink, options: InterpOptions,
                macro: MacroOptions, parse_with: Callable[[DiagnosticSink], Callable[[SourceFile], list[Block]]]
                ) -> Iterator[Command]:
    """Run the library ``src`` with unknown inputs (see the module text)."""
    caller = caller_in_run(src, macro.run_files)
    if caller is not None:
        sink.emit(dg.DEPENDS_ON_ARGUMENTS, Span(src.source_id, 0, 0),
                  f"the programs of this file are called from {caller} in this run and checked there with its "
                  f"arguments")
        return iter(())
    runs: list[tuple[list[Command], list[Diagnostic]]] = []
    for typical in (False, True):
        private = DiagnosticSink(werror=sink.werror)
        interp = Interpreter(dialect, private, src.source_id, copy.deepcopy(options))
        mopts = copy.copy(macro)
        if typical:  # the editor's variable trace shows the program as it stands, not invented arguments
            mopts.trace = None
        ex = Executor(dialect, private, interp, mopts, parse_with(private))
        if typical:
            for n, v in typical_arguments(ex).items():
                ex.vars.write(n, v)
            interp.modal = interp.modal.with_(feed=TYPICAL_FEED)
        runs.append((list(ex.run(src)), list(private.items)))
    _merge(sink, runs[0][1], runs[1][1])
    return iter(runs[0][0])


def _key(d: Diagnostic) -> tuple[str, int, int, int]:
    return d.code, d.span.source_id, d.span.start, d.span.end


def _merge(sink: DiagnosticSink, as_is: list[Diagnostic], typical: list[Diagnostic]) -> None:
    both = {_key(d) for d in as_is} & {_key(d) for d in typical}
    done: set[tuple[str, int, int, int]] = set()
    for items, how in ((as_is, "with vacant arguments and no modal state from a caller"),
                       (typical, "with every argument given")):
        for d in items:
            k = _key(d)
            if k in done:
                continue
            done.add(k)
            if k in both or d.severity is Severity.NOTE:
                sink.emit(d.code, d.span, d.message, d.related, d.severity)
            else:
                sink.emit(dg.DEPENDS_ON_ARGUMENTS, d.span,
                          f"depends on the caller: {how}, {d.message} [{d.code}]", d.related)


__all__ = ["TYPICAL_FEED", "caller_in_run", "is_library", "program_numbers", "run_library", "typical_arguments"]
