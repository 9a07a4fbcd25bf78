"""Front-end plug-ins: what a dialect file's ``frontend = "NAME"`` key selects.

Every dialect runs through one front end: the function that turns its program text
into IR commands.  The registry below names each one and where it lives
(``module:function``, imported on first use, so a dialect that never runs SERIES 8
code never imports it).  A new front end is one more :class:`FrontEnd` entry and a
function with the signature of :data:`LowerFn`; a dialect file selects it by name.

``fanuc`` (the default) is the Fanuc-family path: the straight-line fast path, the
macro executor when a program uses macros, else the modal interpreter.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import cast

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink
from cncc.dialects import Dialect
from cncc.frontend.interp import InterpOptions
from cncc.ir import Command
from cncc.source import SourceFile, Span

LowerFn = Callable[[SourceFile, Dialect, DiagnosticSink, InterpOptions, object], Iterator[Command]]
"""``lower(src, dialect, sink, interp_options, macro_options)`` -> IR commands in program order."""


@dataclass(frozen=True, slots=True)
class FrontEnd:
    name: str
    target: str  # "module:function" of a LowerFn
    summary: str
    fast_path: bool = False  # straight-line programs take cncc.frontend.fastpath (and its LSP checkpoints)

    def function(self) -> LowerFn:
        module, _, attr = self.target.partition(":")
        return cast(LowerFn, getattr(importlib.import_module(module), attr))

    def lower(self, src: SourceFile, dialect: Dialect, sink: DiagnosticSink, options: InterpOptions,
              macro: object = None) -> Iterator[Command]:
        return self.function()(src, dialect, sink, options, macro)


FRONT_ENDS: dict[str, FrontEnd] = {fe.name: fe for fe in (
    FrontEnd("fanuc", "cncc.frontend.dialect_front:lower_fanuc",
             "Fanuc family: fast path, macro executor (macro B, SZGH), modal interpreter", fast_path=True),
    FrontEnd("grbl", "cncc.frontend.dialect_front:lower_grbl",
             "every block checked as grbl 1.1 would before it runs"),
    FrontEnd("linuxcnc", "cncc.frontend.dialect_front:lower_linuxcnc",
             "rs274ngc: O-word control flow, named parameters, subroutines"),
    FrontEnd("series8", "cncc.frontend.dialect_front:lower_series8",
             "SERIES 8 block semantics (bare axis letters, G10 corners, its cycles)"),
)}


def _unknown(name: str) -> FrontEnd:
    return FrontEnd(name, "cncc.frontend.plugins:lower_unknown", "not a registered front end")


def front_end(dialect: Dialect) -> FrontEnd:
    """The front end the dialect file names (one that reports E0940 when the name is unknown)."""
    return FRONT_ENDS.get(dialect.frontend) or _unknown(dialect.frontend)


def lower_unknown(src: SourceFile, dialect: Dialect, sink: DiagnosticSink, options: InterpOptions,
                  macro: object = None) -> Iterator[Command]:
    sink.emit(dg.UNKNOWN_FRONT_END, Span(src.source_id, 0, 0),
              f"dialect {dialect.name!r} names the front end {dialect.frontend!r}, which is not one of "
              f"{', '.join(sorted(FRONT_ENDS))}")
    return iter(())


__all__ = ["FRONT_ENDS", "FrontEnd", "LowerFn", "front_end"]
