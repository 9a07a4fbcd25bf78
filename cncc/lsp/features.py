"""Registration of the server's LSP features, without importing the compiler.

pygls needs every feature (and its options) registered before it answers
``initialize``; the work itself is in :mod:`cncc.lsp.handlers`, imported on the first
request that needs it -- or earlier, by the warm-up thread started once the client has
said ``initialized`` (:func:`cncc.lsp.server.CnccServer.warm_up`).
"""

from __future__ import annotations

from types import ModuleType
from typing import TYPE_CHECKING, Any

from lsprotocol import types as lsp

if TYPE_CHECKING:
    from cncc.lsp.server import CnccServer


def _h() -> ModuleType:
    from cncc.lsp import handlers

    return handlers


def register(ls: CnccServer) -> None:
    _register_lifecycle(ls)
    _register_documents(ls)
    _register_queries(ls)


def _register_lifecycle(ls: CnccServer) -> None:
    @ls.feature(lsp.INITIALIZE)
    def initialize(ls: CnccServer, params: lsp.InitializeParams) -> None:  # light: the handshake
        if isinstance(params.initialization_options, dict):
            sub = params.initialization_options.get("cncc")
            ls.client_settings = dict(sub) if isinstance(sub, dict) else dict(params.initialization_options)
        if params.root_uri:
            ls.root = ls.doc_path(params.root_uri) or None
        elif isinstance(params.root_path, str):
            ls.root = params.root_path

    @ls.feature(lsp.INITIALIZED)
    def initialized(ls: CnccServer, params: lsp.InitializedParams) -> None:
        ls.warm_up()

    @ls.feature(lsp.WORKSPACE_DID_CHANGE_CONFIGURATION)
    def did_change_configuration(ls: CnccServer, params: lsp.DidChangeConfigurationParams) -> Any:
        return _h().did_change_configuration(ls, params)


def _register_documents(ls: CnccServer) -> None:
    @ls.feature(lsp.TEXT_DOCUMENT_DID_OPEN)
    def did_open(ls: CnccServer, params: lsp.DidOpenTextDocumentParams) -> Any:
        return _h().did_open(ls, params)

    @ls.feature(lsp.TEXT_DOCUMENT_DID_CHANGE)
    def did_change(ls: CnccServer, params: lsp.DidChangeTextDocumentParams) -> Any:
        return _h().did_change(ls, params)

    @ls.feature(lsp.TEXT_DOCUMENT_DID_SAVE)
    def did_save(ls: CnccServer, params: lsp.DidSaveTextDocumentParams) -> Any:
        return _h().did_save(ls, params)

    @ls.feature(lsp.TEXT_DOCUMENT_DID_CLOSE)
    def did_close(ls: CnccServer, params: lsp.DidCloseTextDocumentParams) -> Any:
        return _h().did_close(ls, params)


def _register_queries(ls: CnccServer) -> None:
    @ls.feature(lsp.TEXT_DOCUMENT_HOVER)
    def hover(ls: CnccServer, params: lsp.HoverParams) -> Any:
        return _h().hover(ls, params)

    @ls.feature(lsp.TEXT_DOCUMENT_COMPLETION, lsp.CompletionOptions(trigger_characters=["G", "M", "g", "m"]))
    def completion(ls: CnccServer, params: lsp.CompletionParams) -> Any:
        return _h().completion(ls, params)

    @ls.feature(lsp.TEXT_DOCUMENT_DEFINITION)
    async def definition(ls: CnccServer, params: lsp.DefinitionParams) -> Any:
        return await _h().definition(ls, params)

    @ls.feature(lsp.TEXT_DOCUMENT_REFERENCES)
    async def references(ls: CnccServer, params: lsp.ReferenceParams) -> Any:
        return await _h().references(ls, params)

    @ls.feature(lsp.TEXT_DOCUMENT_DOCUMENT_SYMBOL)
    async def symbols(ls: CnccServer, params: lsp.DocumentSymbolParams) -> Any:
        return await _h().symbols(ls, params)

    @ls.feature(lsp.TEXT_DOCUMENT_INLAY_HINT)
    async def inlay_hints(ls: CnccServer, params: lsp.InlayHintParams) -> Any:
        return await _h().inlay_hints(ls, params)

    @ls.feature(lsp.TEXT_DOCUMENT_CODE_ACTION, lsp.CodeActionOptions(
        code_action_kinds=[lsp.CodeActionKind.QuickFix, lsp.CodeActionKind.RefactorRewrite]))
    async def code_action(ls: CnccServer, params: lsp.CodeActionParams) -> Any:
        return await _h().code_action(ls, params)
