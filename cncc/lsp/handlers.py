"""What the server does for each LSP request and notification (registered by :mod:`cncc.lsp.features`)."""

from __future__ import annotations

import os
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from lsprotocol import types as lsp

from cncc import diagnostics as dg
from cncc.dialects import DialectError, available
from cncc.ir import Arc
from cncc.lsp import actions, convert
from cncc.lsp.analysis import Request, analyze, new_analysis
from cncc.lsp.complete import complete
from cncc.lsp.config import open_dialect
from cncc.lsp.hover import word_hover
from cncc.lsp.navigate import Outline, Ref, outline, oword_key, program_key, subroutines
from cncc.lsp.scan import Comments, token_at, tokens
from cncc.lsp.subs import named_hover, sub_hover
from cncc.lsp.variables import hover_variable

if TYPE_CHECKING:
    from cncc.lsp.server import CnccServer  # (the server imports this module's registrations)

GCODE_SUFFIXES = (".nc", ".cnc", ".tap", ".ngc", ".gcode", ".mpf", ".ptp", "")


def did_change_configuration(ls: CnccServer, params: lsp.DidChangeConfigurationParams) -> None:
    if isinstance(params.settings, dict):
        ls.client_settings = {**ls.client_settings, **_cncc_section(params.settings)}
    for uri, st in ls.docs.items():
        ls.schedule(uri, st.version)

def did_open(ls: CnccServer, params: lsp.DidOpenTextDocumentParams) -> None:
    from cncc.lsp.documents import speed_up

    speed_up(ls.workspace.get_text_document(params.text_document.uri))
    ls.schedule(params.text_document.uri, params.text_document.version)

def did_change(ls: CnccServer, params: lsp.DidChangeTextDocumentParams) -> None:
    ls.schedule(params.text_document.uri, params.text_document.version)

def did_save(ls: CnccServer, params: lsp.DidSaveTextDocumentParams) -> None:
    if params.text_document.uri.endswith("cncc.toml"):
        for uri, st in ls.docs.items():
            ls.schedule(uri, st.version)

def did_close(ls: CnccServer, params: lsp.DidCloseTextDocumentParams) -> None:
    st = ls.docs.pop(params.text_document.uri, None)
    if st is not None:
        if st.pending is not None:
            st.pending.cancel()
        if st.job is not None:
            st.job.cancel()
        ls.stop_machine_phase(st)
    ls.text_document_publish_diagnostics(lsp.PublishDiagnosticsParams(uri=params.text_document.uri,
                                                                      diagnostics=[]))

def hover(ls: CnccServer, params: lsp.HoverParams) -> lsp.Hover | None:
    uri = params.text_document.uri
    text, index = ls.text_and_index(uri)
    dialect = ls.dialect_of(uri, text)
    at = convert.offset(index, params.position)
    line = index.line_of(at)
    tok = token_at(index.line_text(line), index.line_start(line), at, Comments.of(dialect))
    if tok is None:
        return None
    body: str | None
    toks = list(tokens(index.line_text(line), index.line_start(line), Comments.of(dialect)))
    sub = oword_key(toks) if toks and tok == toks[0] else None
    if sub is not None or tok.kind == "oname":
        key = sub[0] if sub is not None else tok.text
        body = sub_hover(index, dialect, subroutines(text), key, line)
    elif tok.kind == "named":
        st = ls.docs.get(uri)
        a = st.analysis if st is not None else None
        current = a is not None and a.request.text == text
        body = named_hover(tok.text, tok.start, a.trace if a is not None and current else None,
                           changed=a is not None and not current)
    elif tok.kind == "var":
        st = ls.docs.get(uri)
        a = st.analysis if st is not None else None
        trace = a.trace if a is not None and a.request.text == text else None
        body = hover_variable(text, index, dialect, int(tok.text), tok.start, trace)
    elif tok.kind == "word":
        body = word_hover(dialect, tok)
    else:
        return None
    if body is None:
        return None
    return lsp.Hover(contents=lsp.MarkupContent(kind=lsp.MarkupKind.Markdown, value=body),
                     range=convert.span_range(index, tok.start, tok.end))

def completion(ls: CnccServer, params: lsp.CompletionParams) -> lsp.CompletionList:
    uri = params.text_document.uri
    text, index = ls.text_and_index(uri)
    dialect = ls.dialect_of(uri, text)
    at = convert.offset(index, params.position)
    items = []
    for it in complete(index, dialect, at):
        kind = lsp.CompletionItemKind.Keyword if it.kind == "code" else lsp.CompletionItemKind.Field
        items.append(lsp.CompletionItem(
            label=it.label, detail=it.detail, kind=kind, sort_text=it.sort,
            documentation=lsp.MarkupContent(kind=lsp.MarkupKind.Markdown, value=it.doc) if it.doc else None,
            text_edit=lsp.TextEdit(range=convert.span_range(index, it.start, it.end), new_text=it.label)))
    return lsp.CompletionList(is_incomplete=False, items=items)

async def outline_of(ls: CnccServer, uri: str) -> tuple[Outline, Any] | None:
    text, index = ls.text_and_index(uri)
    dialect = ls.dialect_of(uri, text)
    settings, _ = ls.settings_for(uri)
    found = await ls.guarded(lambda check: outline(text, dialect, check), settings.budget_s)
    return (found, index) if found is not None else None

async def _reference_at(ls: CnccServer, uri: str, position: lsp.Position) -> tuple[Outline, Any, Any] | None:
    """(outline, line index, reference under the cursor), or None where there is none."""
    got = await outline_of(ls, uri)
    if got is None:
        return None
    out, index = got
    ref = out.at(convert.offset(index, position))
    return None if ref is None else (out, index, ref)

async def definition(ls: CnccServer, params: lsp.DefinitionParams) -> list[lsp.Location] | None:
    uri = params.text_document.uri
    at = await _reference_at(ls, uri, params.position)
    if at is None:
        return None
    out, index, ref = at
    found = [lsp.Location(uri=uri, range=convert.span_range(index, r.start, r.end)) for r in out.definitions(ref)]
    if not found and ref.kind in ("program", "sub"):
        found = _program_files(ls, uri, ref)
    return found or None

async def references(ls: CnccServer, params: lsp.ReferenceParams) -> list[lsp.Location] | None:
    uri = params.text_document.uri
    at = await _reference_at(ls, uri, params.position)
    if at is None:
        return None
    out, index, ref = at
    refs = out.references(ref, params.context.include_declaration)
    return [lsp.Location(uri=uri, range=convert.span_range(index, r.start, r.end)) for r in refs]

async def symbols(ls: CnccServer, params: lsp.DocumentSymbolParams) -> list[lsp.DocumentSymbol]:
    got = await outline_of(ls, params.text_document.uri)
    if got is None:
        return []
    out, index = got
    return _symbols(out, index)

async def inlay_hints(ls: CnccServer, params: lsp.InlayHintParams) -> list[lsp.InlayHint]:
    a = await ls.current(params.text_document.uri)
    if a is None or not a.request.settings.inlay_hints:
        return []
    first, last = params.range.start.line, params.range.end.line
    hints = []
    for line, t_s in sorted(a.line_time_s.items()):
        if first <= line <= last:
            end = a.index.line_end(line)
            hints.append(lsp.InlayHint(position=convert.position(a.index, end),
                                       label=convert.duration_text(t_s), padding_left=True,
                                       tooltip=f"time of this block at -O{a.request.settings.opt_level} "
                                               f"({a.machine.name if a.machine else 'generic'} machine)"))
    return hints

async def code_action(ls: CnccServer, params: lsp.CodeActionParams) -> list[lsp.CodeAction]:
    return await _code_actions(ls, params)


def _cncc_section(data: dict[str, Any]) -> dict[str, Any]:
    sub = data.get("cncc")
    return dict(sub) if isinstance(sub, dict) else dict(data)


def _symbols(out: Outline, index: Any) -> list[lsp.DocumentSymbol]:
    called = {r.key for r in out.calls if r.kind == "label" and r.what != "GOTO"}
    found = []
    for r in out.programs:
        found.append((r.start, f"O{r.key}", "program", lsp.SymbolKind.Module, r.start, r.end))
    for r in out.subs:
        end = out.sub_ends.get(r.key, r.end)
        name = f"o<{r.key}>" if not r.key.isdigit() else f"o{r.key}"
        found.append((r.start, name, "subroutine", lsp.SymbolKind.Function, r.start, max(end, r.end)))
    for r in out.labels:
        if r.key in called:
            found.append((r.start, f"N{r.key}", "subprogram", lsp.SymbolKind.Function, r.start, r.end))
    for start, end, _tool, text in out.tools:
        found.append((start, text, "tool", lsp.SymbolKind.Event, start, end))
    syms = []
    for start, name, detail, kind, a, b in sorted(found):
        rng = convert.span_range(index, a, b)
        sel = convert.span_range(index, start, min(b, index.line_end(index.line_of(start))))
        syms.append(lsp.DocumentSymbol(name=name, detail=detail, kind=kind, range=rng, selection_range=sel))
    return syms


def _program_files(ls: CnccServer, uri: str, ref: Ref) -> list[lsp.Location]:
    """Other files that hold program ``ref.key`` (by file name), in the document's folder and the root."""
    path = ls.doc_path(uri)
    folders = [os.path.dirname(path)] if path else []
    if ls.root and ls.root not in folders:
        folders.append(ls.root)
    found = []
    for folder in folders:
        try:
            names = sorted(os.listdir(folder))[:5000]
        except OSError:
            continue
        for name in names:
            stem, ext = os.path.splitext(name)
            full = os.path.join(folder, name)
            same = stem.lower() == ref.key if ref.kind == "sub" else program_key(stem) == ref.key
            if ext.lower() in GCODE_SUFFIXES and same and full != path:
                found.append(lsp.Location(uri="file://" + full, range=lsp.Range(
                    start=lsp.Position(line=0, character=0), end=lsp.Position(line=0, character=0))))
    return found


async def _code_actions(ls: CnccServer, params: lsp.CodeActionParams) -> list[lsp.CodeAction]:
    uri = params.text_document.uri
    text, index = ls.text_and_index(uri)
    settings, _ = ls.settings_for(uri)
    dialect_name = ls.dialect_name(uri, text, settings)
    dialect = ls.dialect_of(uri, text)
    out: list[lsp.CodeAction] = []
    for d in params.context.diagnostics:
        start = convert.offset(index, d.range.start)
        if d.code in (dg.NO_FEED, dg.DEFAULT_FEED):
            feed = actions.insert_feed(index, dialect, start)
            if feed is not None:
                out.append(_action(feed[0], lsp.CodeActionKind.QuickFix, uri, index, feed[1], d))
        elif d.code == dg.ARC_RADIUS:
            req = Request(uri, ls.doc_path(uri), None, text, dialect_name, settings, repair_arcs=True,
                          stop_after=index.line_end(index.line_of(start)))
            arc = await _repaired_arc(ls, req, start)
            fixed = actions.repair_arc(index, dialect, arc) if arc is not None else None
            if fixed is not None:
                out.append(_action(fixed[0], lsp.CodeActionKind.QuickFix, uri, index, fixed[1], d))
    rng = params.range
    if (rng.start.line, rng.start.character) != (rng.end.line, rng.end.character):
        cur = await ls.current(uri)
        if cur is not None and cur.request.text == text:
            last = rng.end.line if rng.end.character > 0 or rng.end.line == rng.start.line else rng.end.line - 1
            targets = [settings.target] if settings.target else []
            targets += [n for n in available() if n != dialect.name and n not in targets]
            errors = [(d.span.start, d.message) for d in cur.diagnostics
                      if d.severity is dg.Severity.ERROR and d.span.source_id == 0]
            why = actions.refusal(errors, index.line_start(rng.start.line), index.line_end(last))
            if why is not None:  # refused, with the reason (clients show it greyed out)
                out.append(lsp.CodeAction(title="Convert selection to another dialect",
                                          kind=lsp.CodeActionKind.RefactorRewrite,
                                          disabled=lsp.CodeActionDisabled(reason=why)))
                targets = []
            for name in targets:
                try:
                    target = open_dialect(name, settings)
                except DialectError:
                    continue
                chosen = cur.commands_between(index.line_start(rng.start.line), index.line_end(last))
                conv = actions.convert_selection(index, chosen, rng.start.line, last, dialect, target)
                if conv is not None:
                    out.append(_action(conv[0], lsp.CodeActionKind.RefactorRewrite, uri, index, conv[1], None))
    return out


async def _repaired_arc(ls: CnccServer, req: Request, start: int) -> Arc | None:
    """The arc starting at ``start`` as the arc-check pass repairs it (a guarded compile)."""
    a = new_analysis(req)

    def work(check: Callable[[], None]) -> None:
        analyze(a, check)

    await ls.guarded(work, req.settings.budget_s)
    return next((c for c in a.commands if isinstance(c, Arc) and c.span.start == start), None)


def _action(title: str, kind: str, uri: str, index: Any, edits: list[tuple[int, int, str]],
            diag: lsp.Diagnostic | None) -> lsp.CodeAction:
    return lsp.CodeAction(title=title, kind=kind, diagnostics=[diag] if diag is not None else None,
                          edit=convert.workspace_edit(index, uri, edits), is_preferred=diag is not None)
