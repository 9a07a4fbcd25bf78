"""Diagnostics as text, gcc style: ``file:line:col: error[E0201]: message``,
the source line and a caret under the span, then related spans as notes."""

from __future__ import annotations

from collections.abc import Iterator

from cncc.diagnostics import Diagnostic
from cncc.source import SourceMap, Span


def _location(sources: SourceMap, span: Span) -> tuple[str, str]:
    src = sources.get(span.source_id)
    if src is None:
        return "cncc", ""
    pos = src.position(min(span.start, len(src.text)))
    line = src.line_text(pos.line)
    shown = line.expandtabs(1)
    if len(shown) > 200:
        lo = max(0, pos.column - 80)
        shown = shown[lo: lo + 160]
        col = pos.column - lo
    else:
        col = pos.column
    width = max(1, min(span.end - span.start, len(shown) - col + 1))
    printable = "".join(ch if ch.isprintable() else "?" for ch in shown)
    caret = " " * (col - 1) + "^" + "~" * (width - 1)
    return f"{src.name}:{pos.line}:{pos.column}", f"  {printable}\n  {caret}\n"


def render(diag: Diagnostic, sources: SourceMap) -> Iterator[str]:
    where, excerpt = _location(sources, diag.span)
    yield f"{where}: {diag.severity.label}[{diag.code}]: {diag.message}\n"
    yield excerpt
    for rel in diag.related:
        rwhere, rexcerpt = _location(sources, rel.span)
        yield f"{rwhere}: note: {rel.message}\n"
        yield rexcerpt
