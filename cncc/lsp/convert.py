"""The LSP edge: cncc diagnostics, offsets and edits as ``lsprotocol`` objects."""

from __future__ import annotations

from collections.abc import Callable, Iterable

from lsprotocol import types as lsp

from cncc import diagnostics as dg
from cncc.diagnostics import Diagnostic, Severity
from cncc.lsp.positions import LineIndex
from cncc.source import Span

SEVERITY = {
    Severity.ERROR: lsp.DiagnosticSeverity.Error,
    Severity.WARNING: lsp.DiagnosticSeverity.Warning,
    Severity.NOTE: lsp.DiagnosticSeverity.Information,
}


def position(index: LineIndex, offset: int) -> lsp.Position:
    line, col = index.position(offset)
    return lsp.Position(line=line, character=col)


def span_range(index: LineIndex, start: int, end: int) -> lsp.Range:
    return lsp.Range(start=position(index, start), end=position(index, max(end, start)))


def offset(index: LineIndex, pos: lsp.Position) -> int:
    return index.offset(pos.line, pos.character)


Files = Callable[[int], "tuple[str, LineIndex] | None"]
"""Source id of a called program -> its URI and line index (None when unknown)."""


def _no_files(source_id: int) -> tuple[str, LineIndex] | None:
    return None


def _location(index: LineIndex, uri: str, span: Span, files: Files) -> lsp.Location | None:
    if span.source_id == 0:
        return lsp.Location(uri=uri, range=span_range(index, span.start, max(span.end, span.start)))
    where = files(span.source_id) if span.source_id > 0 else None
    if where is None:
        return None
    other_uri, other = where
    return lsp.Location(uri=other_uri, range=span_range(other, span.start, max(span.end, span.start)))


def diagnostic(index: LineIndex, uri: str, d: Diagnostic, files: Files = _no_files) -> lsp.Diagnostic:
    """One diagnostic.  One that lies in a called program's file is shown on the call in this
    document that led there (the innermost one), with its own place as related information."""
    span = d.span
    related = []
    for r in d.related:
        loc = _location(index, uri, r.span, files)
        if loc is not None:
            related.append(lsp.DiagnosticRelatedInformation(location=loc, message=r.message))
    if span.source_id != 0:
        call = next((r.span for r in d.related if r.span.source_id == 0), None)
        rng = span_range(index, call.start, max(call.end, call.start)) if call is not None else span_range(index, 0, 0)
        here = _location(index, uri, span, files)
        if here is not None:
            related.insert(0, lsp.DiagnosticRelatedInformation(location=here, message=f"here: {d.message}"))
    else:
        end = span.end if span.end > span.start else span.start + 1
        rng = span_range(index, span.start, end)
    info = dg.CODES.get(d.code)
    tags = [lsp.DiagnosticTag.Unnecessary] if d.code == dg.AFTER_END else None
    return lsp.Diagnostic(
        range=rng,
        message=d.message,
        severity=SEVERITY.get(d.severity, lsp.DiagnosticSeverity.Error),
        code=d.code,
        source="cncc",
        related_information=related or None,
        tags=tags,
        data={"summary": info.summary} if info is not None else None,
    )


def diagnostics(index: LineIndex, uri: str, items: Iterable[Diagnostic], limit: int,
                files: Files = _no_files) -> list[lsp.Diagnostic]:
    out: list[lsp.Diagnostic] = []
    for d in items:
        if len(out) >= limit:
            break
        out.append(diagnostic(index, uri, d, files))
    return out


def workspace_edit(index: LineIndex, uri: str, edits: Iterable[tuple[int, int, str]]) -> lsp.WorkspaceEdit:
    return lsp.WorkspaceEdit(changes={uri: [lsp.TextEdit(range=span_range(index, a, b), new_text=t)
                                            for a, b, t in edits]})


def duration_text(t_s: float) -> str:
    if t_s >= 60.0:
        minutes, seconds = divmod(t_s, 60.0)
        return f"{int(minutes)} min {seconds:.1f} s"
    if t_s >= 10.0:
        return f"{t_s:.1f} s"
    return f"{t_s:.2f} s" if t_s >= 0.01 else f"{t_s * 1000:.1f} ms"
