"""Fixtures: a real ``cncc lsp`` subprocess driven by a pytest-lsp client."""

from __future__ import annotations

import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest_lsp
from lsprotocol import types as lsp
from pytest_lsp import ClientServerConfig, LanguageClient

DATA = Path(__file__).parent / "data"
SERVER = [sys.executable, "-m", "cncc", "lsp"]


def init_params(root: Path, options: dict[str, object] | None = None) -> lsp.InitializeParams:
    return lsp.InitializeParams(
        capabilities=lsp.ClientCapabilities(),
        root_uri=root.as_uri(),
        initialization_options=options or {},
    )


@pytest_lsp.fixture(config=ClientServerConfig(server_command=SERVER), scope="module")
async def client(lsp_client: LanguageClient, tmp_path_factory):  # type: ignore[no-untyped-def]
    root = tmp_path_factory.mktemp("ws")
    lsp_client.root = root  # type: ignore[attr-defined]
    lsp_client.published = Published(lsp_client)  # type: ignore[attr-defined]
    await lsp_client.initialize_session(init_params(root, {"debounce_ms": 10, "budget_s": 2.0}))
    yield
    await lsp_client.shutdown_session()


class Published:
    """Records every publishDiagnostics notification (none is lost between waits)."""

    def __init__(self, client: LanguageClient) -> None:
        import asyncio

        self.client = client
        self.items: list[lsp.PublishDiagnosticsParams] = []
        self.event = asyncio.Event()
        self._arm()

    def _arm(self) -> None:
        future = self.client.protocol.wait_for_notification(lsp.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
        future.add_done_callback(self._got)

    def _got(self, future: Any) -> None:
        if future.exception() is not None:  # the server went away (end of the module)
            return
        self.items.append(future.result())
        self._arm()
        self.event.set()

    async def wait(self, uri: str, version: int, timeout_s: float = 30.0,
                   until: Callable[[list[lsp.Diagnostic]], bool] | None = None) -> list[lsp.Diagnostic]:
        """The first diagnostics published for ``version`` (that satisfy ``until``, when given)."""
        import asyncio

        async def found() -> list[lsp.Diagnostic]:
            while True:
                for p in self.items:
                    if p.uri == uri and p.version == version and (until is None or until(list(p.diagnostics))):
                        return list(p.diagnostics)
                self.event.clear()
                await self.event.wait()

        return await asyncio.wait_for(found(), timeout_s)

    def all(self, uri: str, version: int) -> list[list[lsp.Diagnostic]]:
        """Every publication for ``version`` so far, in order."""
        return [list(p.diagnostics) for p in self.items if p.uri == uri and p.version == version]
