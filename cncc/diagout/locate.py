"""Spans to file, line and column (1-based, columns in characters) for the structured formats."""

from __future__ import annotations

from dataclasses import dataclass

from cncc.source import SourceMap, Span


@dataclass(frozen=True, slots=True)
class Place:
    file: str | None
    line: int | None = None
    column: int | None = None
    end_line: int | None = None  # the position just after the span (exclusive end)
    end_column: int | None = None


def place(sources: SourceMap, span: Span) -> Place:
    src = sources.get(span.source_id)
    if src is None:
        return Place(None)
    n = len(src.text)
    start = src.position(min(span.start, n))
    end = src.position(min(max(span.end, span.start), n))
    return Place(src.name, start.line, start.column, end.line, end.column)
