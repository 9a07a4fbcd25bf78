"""End to end on LinuxCNC programs (issue 20): ``o<name>`` subroutines (definition,
references, symbols, hover with the parameters) and ``#<named>`` parameters (hover with
the value the executor saw)."""

from __future__ import annotations

from pathlib import Path

import pytest
from lsprotocol import types as lsp
from pytest_lsp import LanguageClient

from tests.lsp.conftest import DATA
from tests.lsp.lsp_client import diags, hover_text, open_doc, pos

pytestmark = pytest.mark.asyncio(loop_scope="module")

SQUARE = (DATA / "square.ngc").read_text(encoding="utf-8")
LINES = SQUARE.split("\n")


def line_of(text: str) -> int:
    return next(i for i, ln in enumerate(LINES) if ln.startswith(text))


async def opened(client: LanguageClient, name: str = "subs/square.ngc") -> tuple[str, lsp.TextDocumentIdentifier]:
    uri, v = await open_doc(client, name, SQUARE)
    found = await diags(client, uri, v)
    assert [d for d in found if d.severity == lsp.DiagnosticSeverity.Error] == []
    return uri, lsp.TextDocumentIdentifier(uri=uri)


async def test_definition_of_a_call_is_the_sub(client: LanguageClient) -> None:
    _, doc = await opened(client)
    call = line_of("o<square> call [10]")
    where = await client.text_document_definition_async(lsp.DefinitionParams(text_document=doc,
                                                                               position=pos(call, 3)))
    assert isinstance(where, list) and [w.range.start.line for w in where] == [line_of("o<square> sub")]


async def test_references_of_the_sub_are_its_calls(client: LanguageClient) -> None:
    _, doc = await opened(client)
    refs = await client.text_document_references_async(lsp.ReferenceParams(
        text_document=doc, position=pos(0, 2), context=lsp.ReferenceContext(include_declaration=True)))
    assert refs is not None
    calls = [i for i, ln in enumerate(LINES) if ln.startswith("o<square> call")]
    assert sorted(r.range.start.line for r in refs) == [0, *calls]


async def test_document_symbols_list_the_sub(client: LanguageClient) -> None:
    _, doc = await opened(client)
    syms = await client.text_document_document_symbol_async(lsp.DocumentSymbolParams(text_document=doc))
    assert syms is not None
    subs = [s for s in syms if isinstance(s, lsp.DocumentSymbol) and s.kind == lsp.SymbolKind.Function]
    assert [(s.name, s.range.start.line, s.range.end.line) for s in subs] == [
        ("o<square>", 0, line_of("o<square> endsub"))]


async def test_hover_on_the_sub_name_shows_its_parameters_not_address_letters(client: LanguageClient) -> None:
    uri, _ = await opened(client)
    body = await hover_text(client, uri, line_of("o<square> call [10]"), 4)  # on the 'q' of square
    assert "peck" not in body and "Q" not in body.split("\n")[0]
    assert "o<square>" in body and "subroutine" in body
    # the call passes [10] [1.5]; the body names #1 side and #2 depth
    assert "`#1` → `#<side>` = [10]" in body and "`#2` → `#<depth>` = [1.5]" in body


async def test_hover_on_a_named_parameter_shows_the_executed_value(client: LanguageClient) -> None:
    uri, _ = await opened(client)
    at = line_of("G00 Z#<total>")
    body = await hover_text(client, uri, at, LINES[at].index("#") + 2)
    assert "#<total>" in body and "= 30" in body  # #<total> = [10 + 20]
    inner = line_of("  G01 Z-#<depth>")
    body = await hover_text(client, uri, inner, LINES[inner].index("#") + 2)
    # the sub ran twice, with depth 1.5 and 2: the last value and the range
    assert "= 2 on the last of 2 passes" in body and "from 1.5 to 2" in body


async def test_definition_of_a_sub_in_its_own_file(client: LanguageClient) -> None:
    root: Path = client.root  # type: ignore[attr-defined]
    (root / "lib").mkdir(exist_ok=True)
    (root / "lib" / "pocket.ngc").write_text("o<pocket> sub\nG01 X#1 F100\no<pocket> endsub\nM2\n",
                                             encoding="utf-8")
    uri, v = await open_doc(client, "lib/main.ngc", "G21 G90\no<pocket> call [5]\nM2\n")
    await diags(client, uri, v)
    where = await client.text_document_definition_async(lsp.DefinitionParams(
        text_document=lsp.TextDocumentIdentifier(uri=uri), position=pos(1, 3)))
    assert isinstance(where, list) and [w.uri for w in where] == [(root / "lib" / "pocket.ngc").as_uri()]


async def test_refused_conversion_says_why(client: LanguageClient) -> None:
    from tests.lsp.lsp_client import actions_for

    text = "G90 G17\nG00 X0. Y0. Z5.\nG01 X10. Q\nG01 X12. F300.\nM30\n"
    uri, v = await open_doc(client, "refuse.nc", text)
    await diags(client, uri, v)
    acts = await actions_for(client, uri, lsp.Range(start=pos(1, 0), end=pos(3, 5)), [])
    conv = [a for a in acts if a.title.startswith("Convert selection")]
    assert len(conv) == 1 and conv[0].edit is None
    assert conv[0].disabled is not None and "error" in conv[0].disabled.reason

