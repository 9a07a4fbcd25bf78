"""Source files and spans.

A span is ``(source_id, start, end)`` in characters of one source text; line and
column numbers are computed on demand from a :class:`SourceMap`, so the front end
never pays for them on the hot path.
"""

from __future__ import annotations

import bisect
from dataclasses import dataclass, field


@dataclass(frozen=True, slots=True)
class Span:
    """A half-open character range ``[start, end)`` in source ``source_id``."""

    source_id: int
    start: int
    end: int


NO_SPAN = Span(-1, 0, 0)


@dataclass(frozen=True, slots=True)
class Position:
    """A 1-based line and column (column counted in characters)."""

    line: int
    column: int


@dataclass(slots=True)
class SourceFile:
    """One program text and the index of its line starts."""

    source_id: int
    name: str
    text: str
    _line_starts: list[int] | None = field(default=None, repr=False)

    @property
    def line_starts(self) -> list[int]:
        if self._line_starts is None:
            starts = [0]
            find = self.text.find
            i = find("\n")
            while i >= 0:
                starts.append(i + 1)
                i = find("\n", i + 1)
            self._line_starts = starts
        return self._line_starts

    def position(self, offset: int) -> Position:
        starts = self.line_starts
        line = bisect.bisect_right(starts, offset) - 1
        return Position(line + 1, offset - starts[line] + 1)

    def line_text(self, line: int) -> str:
        starts = self.line_starts
        if line < 1 or line > len(starts):
            return ""
        begin = starts[line - 1]
        end = starts[line] - 1 if line < len(starts) else len(self.text)
        return self.text[begin:end].rstrip("\r")


class SourceMap:
    """All sources of one compilation, addressed by ``source_id``."""

    def __init__(self) -> None:
        self._files: list[SourceFile] = []

    def add(self, name: str, text: str) -> SourceFile:
        src = SourceFile(len(self._files), name, text)
        self._files.append(src)
        return src

    def get(self, source_id: int) -> SourceFile | None:
        if 0 <= source_id < len(self._files):
            return self._files[source_id]
        return None

    def __iter__(self):  # type: ignore[no-untyped-def]
        return iter(self._files)

    def describe(self, span: Span) -> str:
        """``file:line:col`` for a span (or ``<unknown>``)."""
        src = self.get(span.source_id)
        if src is None:
            return "<unknown>"
        pos = src.position(span.start)
        return f"{src.name}:{pos.line}:{pos.column}"
