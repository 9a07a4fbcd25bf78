"""-fsyntax-only on a fast-path dialect: the front end's sparse stream through the path passes.

:func:`wanted` says whether a compilation may take the fast path (a big enough program, the
default passes, an output that needs nothing the sparse stream leaves out, a dialect that
:mod:`cncc.frontend.syntax_fast` decides with arrays); :func:`check` runs it: plain blocks are
decided with arrays, the rest go through the front end, and the commands go through the path
passes (``run_passes``, built by the driver), so the diagnostics are those of the whole stream.
A program that is not straight-line after all starts again on the front end, its diagnostics
forgotten.

The driver (``cncc/driver.py``) builds the interpreter's and the macro executor's options and
the path passes and hands them in; this module imports nothing above the pipeline.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Mapping
from typing import Any, Protocol

from cncc.diagnostics import DiagnosticSink
from cncc.dialects import Dialect
from cncc.ir import Command
from cncc.source import SourceFile

FAST_SYNTAX_MIN_CHARS = 1 << 16  # a smaller program is checked sooner than numpy is imported
SLOW_EMITS = ("timing", "pulses", "gcode")  # outputs whose passes read what the sparse stream leaves out


class CheckRequest(Protocol):
    """The options :func:`wanted` reads (the driver's ``Options``)."""

    @property
    def expand(self) -> bool: ...
    @property
    def passes(self) -> str: ...
    @property
    def verify_each(self) -> bool: ...
    @property
    def print_after(self) -> tuple[str, ...]: ...
    @property
    def time_passes(self) -> bool: ...
    @property
    def emit(self) -> str: ...


def wanted(src: SourceFile, dialect: Dialect, opts: CheckRequest) -> bool:
    """True when -fsyntax-only on ``src`` may take the fast path (nothing is run or reported)."""
    if (len(src.text) < FAST_SYNTAX_MIN_CHARS or opts.expand or opts.passes or opts.verify_each
            or opts.print_after or opts.time_passes or opts.emit in SLOW_EMITS):
        return False
    from cncc.frontend.syntax_fast import applies

    return applies(dialect)


def check(src: SourceFile, dialect: Dialect, sink: DiagnosticSink, iopts: Any, mopts: Any,
          arc_check: Mapping[str, Any], run_passes: Callable[[Iterator[Command]], None]) -> None:
    """Check ``src`` (:func:`wanted` said yes): ``iopts``/``mopts`` are the interpreter's and the
    macro executor's options, ``arc_check`` the arc-check pass's options, ``run_passes`` runs
    the path passes over a command stream."""
    from cncc.frontend import lower
    from cncc.frontend.syntax_fast import ArcLimits, NotStraight, lower_for_check
    from cncc.frontend.tape import before_tape_end

    a = arc_check
    limits = ArcLimits(a["abs_tol_mm"], a["rel_tol"], a["abs_tol_inch_mm"], a["max_abs_factor"])
    checked = before_tape_end(src) if dialect.raw.get("tape_end") else src
    mark = (len(sink.items), sink.dropped, sink.suppressed, sink.errors_kept, sink.over_limit)
    try:
        run_passes(lower_for_check(checked, dialect, sink, iopts, limits))
    except NotStraight:
        del sink.items[mark[0]:]
        sink.dropped, sink.suppressed, sink.errors_kept, sink.over_limit = mark[1:]
        run_passes(lower(src, dialect, sink, iopts, mopts))
