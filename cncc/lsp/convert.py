"""The LSP edge: cncc diagnostics, offsets and edits as ``lsprotocol`` objects."""

from __future__ import annotations

from collections.abc import Iterable

from lsprotocol import types as lsp

from cncc import diagnostics as dg
from cncc.diagnostics import Diagnostic, Severity
from cncc.lsp.positions import LineIndex

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


def diagnostic(index: LineIndex, uri: str, d: Diagnostic) -> lsp.Diagnostic:
    span = d.span
    if span.source_id != 0:  # no place in this document: the first character
        rng = span_range(index, 0, 0)
    else:
        end = span.end if span.end > span.start else span.start + 1
        rng = span_range(index, span.start, end)
    related = [
        lsp.DiagnosticRelatedInformation(
            location=lsp.Location(uri=uri, range=span_range(index, r.span.start, max(r.span.end, r.span.start))),
            message=r.message,
        )
        for r in d.related
        if r.span.source_id == 0
    ]
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


def diagnostics(index: LineIndex, uri: str, items: Iterable[Diagnostic], limit: int) -> list[lsp.Diagnostic]:
    out: list[lsp.Diagnostic] = []
    for d in items:
        if len(out) >= limit:
            break
        out.append(diagnostic(index, uri, d))
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
