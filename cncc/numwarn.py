"""Numerical warnings (numpy's overflow, invalid value, divide by zero; any RuntimeWarning) as diagnostics.

numpy reports floating-point trouble with :class:`RuntimeWarning`, which a pipeline would
see only on standard error, without a position.  :func:`warnings_to` records them during a
compile and :func:`to_diagnostics` turns each distinct one into a ``W0909`` diagnostic naming the Python place
that raised it.
"""

from __future__ import annotations

import contextlib
import warnings
from collections.abc import Iterator

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink
from cncc.source import NO_SPAN


@contextlib.contextmanager
def recorded() -> Iterator[list[warnings.WarningMessage]]:
    """Record the warnings raised inside the block (the RuntimeWarnings every time they occur)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", RuntimeWarning)
        yield caught


def to_diagnostics(caught: list[warnings.WarningMessage], sink: DiagnosticSink) -> None:
    """Each distinct RuntimeWarning as a W0909 diagnostic; other warnings are raised again."""
    seen: set[tuple[str, str, int]] = set()
    for w in caught:
        if not issubclass(w.category, RuntimeWarning):
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)  # not numerical: pass it on
            continue
        key = (str(w.message), w.filename, w.lineno)
        if key in seen:
            continue
        seen.add(key)
        sink.emit(dg.NUMPY_WARNING, NO_SPAN, f"numerical warning: {w.message} (raised at {w.filename}:{w.lineno}); "
                  "the results may be inaccurate")
