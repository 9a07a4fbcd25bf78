"""Helpers of the end-to-end tests: documents, edits, positions, hovers, code actions."""

from __future__ import annotations

import itertools
from pathlib import Path

from lsprotocol import types as lsp
from pytest_lsp import LanguageClient

_versions = itertools.count(1)


def next_version() -> int:
    return next(_versions)


async def open_doc(client: LanguageClient, name: str, text: str) -> tuple[str, int]:
    root: Path = client.root  # type: ignore[attr-defined]
    path = root / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    uri = path.as_uri()
    version = next_version()
    client.text_document_did_open(lsp.DidOpenTextDocumentParams(
        text_document=lsp.TextDocumentItem(uri=uri, language_id="gcode", version=version, text=text)))
    return uri, version


async def diags(client: LanguageClient, uri: str, version: int) -> list[lsp.Diagnostic]:
    return await client.published.wait(uri, version)  # type: ignore[attr-defined,no-any-return]


async def edit(client: LanguageClient, uri: str, rng: lsp.Range, text: str) -> int:
    version = next_version()
    client.text_document_did_change(lsp.DidChangeTextDocumentParams(
        text_document=lsp.VersionedTextDocumentIdentifier(uri=uri, version=version),
        content_changes=[lsp.TextDocumentContentChangePartial(range=rng, text=text)]))
    return version


def utf16_col(line: str, index: int) -> int:
    """UTF-16 column of character ``index`` of ``line`` (computed by encoding)."""
    return len(line[:index].encode("utf-16-le")) // 2


def pos(line: int, character: int) -> lsp.Position:
    return lsp.Position(line=line, character=character)


def apply(text: str, edits: list[lsp.TextEdit]) -> str:
    """Apply LSP edits (UTF-16 positions) to ``text``, last first."""
    lines = text.split("\n")

    def offset(p: lsp.Position) -> int:
        before = sum(len(x) + 1 for x in lines[:p.line])
        line = lines[p.line] if p.line < len(lines) else ""
        units = 0
        for i, ch in enumerate(line):
            if units >= p.character:
                return before + i
            units += len(ch.encode("utf-16-le")) // 2
        return before + len(line)

    for e in sorted(edits, key=lambda e: (e.range.start.line, e.range.start.character), reverse=True):
        text = text[:offset(e.range.start)] + e.new_text + text[offset(e.range.end):]
    return text


async def hover_text(client: LanguageClient, uri: str, line: int, character: int) -> str:
    h = await client.text_document_hover_async(lsp.HoverParams(
        text_document=lsp.TextDocumentIdentifier(uri=uri), position=pos(line, character)))
    assert h is not None
    assert isinstance(h.contents, lsp.MarkupContent)
    return h.contents.value


async def actions_for(client: LanguageClient, uri: str, rng: lsp.Range,
                      diagnostics: list[lsp.Diagnostic]) -> list[lsp.CodeAction]:
    got = await client.text_document_code_action_async(lsp.CodeActionParams(
        text_document=lsp.TextDocumentIdentifier(uri=uri), range=rng,
        context=lsp.CodeActionContext(diagnostics=diagnostics)))
    return [a for a in got or [] if isinstance(a, lsp.CodeAction)]


def edits_of(action: lsp.CodeAction, uri: str) -> list[lsp.TextEdit]:
    assert action.edit is not None and action.edit.changes is not None
    return list(action.edit.changes[uri])


async def replace_all(client: LanguageClient, uri: str, old: str, new: str) -> int:
    lines = old.split("\n")
    end = pos(len(lines) - 1, len(lines[-1].encode("utf-16-le")) // 2)
    return await edit(client, uri, lsp.Range(start=pos(0, 0), end=end), new)
