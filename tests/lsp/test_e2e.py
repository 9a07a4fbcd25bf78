"""End to end: ``cncc lsp`` as a subprocess, driven by a real LSP client."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
from lsprotocol import types as lsp
from pytest_lsp import LanguageClient

from cncc.dialects import load_dialect
from tests.lsp.lsp_client import (
    actions_for,
    apply,
    diags,
    edit,
    edits_of,
    hover_text,
    next_version,
    open_doc,
    pos,
    replace_all,
    utf16_col,
)

pytestmark = pytest.mark.asyncio(loop_scope="module")


# ---- diagnostics -----------------------------------------------------------------
async def test_diagnostic_range_counts_utf16_after_non_ascii_comment(client: LanguageClient) -> None:
    line = "N10 (tête 😀 fräsen) G01 X10. F100. G00"
    uri, v = await open_doc(client, "utf16.nc", "G90\n" + line + "\nM30\n")
    found = [d for d in await diags(client, uri, v) if d.code == "E0203"]
    assert len(found) == 1
    col = line.index("G00")
    assert found[0].range.start == pos(1, utf16_col(line, col))
    assert found[0].range.end == pos(1, utf16_col(line, col + 3))
    assert utf16_col(line, col) == col + 1  # the emoji is two UTF-16 units: the test means something
    assert found[0].severity == lsp.DiagnosticSeverity.Error


async def test_change_updates_diagnostics(client: LanguageClient) -> None:
    uri, v = await open_doc(client, "change.nc", "G90 G01 X10. F100. G00\nM30\n")
    assert any(d.code == "E0203" for d in await diags(client, uri, v))
    v2 = await edit(client, uri, lsp.Range(start=pos(0, 18), end=pos(0, 22)), "")
    assert not any(d.code == "E0203" for d in await diags(client, uri, v2))


# ---- hover -----------------------------------------------------------------------
async def test_hover_code_word_and_variable(client: LanguageClient) -> None:
    text = "G83 X1. Y2. Z-5. R1. Q1. F100.\nG00 X5500\n#1=5\n#2=#1*2+1\nG01 X#2\n"
    uri, v = await open_doc(client, "hover.nc", text)
    await diags(client, uri, v)
    g83 = load_dialect("syntec").code("G", 830)
    assert g83 is not None
    body = await hover_text(client, uri, 0, 1)
    assert g83.summary in body and "group 09" in body
    assert "5.5 mm" in await hover_text(client, uri, 1, 6)  # X5500 read in least input units
    assert "= 11" in await hover_text(client, uri, 4, 6)  # #2 = 5 * 2 + 1


# ---- completion ------------------------------------------------------------------
async def test_completion_offers_arc_words_and_skips_conflicting_codes(client: LanguageClient) -> None:
    text = "G90 G17\nG02 X10. Y0 \nG01 X5. G0\n"
    uri, v = await open_doc(client, "complete.nc", text)
    await diags(client, uri, v)
    words = await client.text_document_completion_async(lsp.CompletionParams(
        text_document=lsp.TextDocumentIdentifier(uri=uri), position=pos(1, 12)))
    assert words is not None
    labels = {i.label for i in (words.items if isinstance(words, lsp.CompletionList) else words)}
    assert {"I", "J", "R", "F"} <= labels and "X" not in labels
    codes = await client.text_document_completion_async(lsp.CompletionParams(
        text_document=lsp.TextDocumentIdentifier(uri=uri), position=pos(2, 10)))
    assert codes is not None
    code_labels = {i.label for i in (codes.items if isinstance(codes, lsp.CompletionList) else codes)}
    assert "G17" in code_labels and "G04" in code_labels
    assert not {"G00", "G02", "G03"} & code_labels  # the block already has a motion code


# ---- navigation --------------------------------------------------------------------
NAV = """O0001
T1 M06
G65 P10 L2 X1.
M98 H100
M98 H100
M30
N100
G01 X1. F100.
M99
O0010
G00 X0
M99
"""


async def test_definition_references_and_symbols(client: LanguageClient) -> None:
    uri, v = await open_doc(client, "nav.nc", NAV)
    await diags(client, uri, v)
    doc = lsp.TextDocumentIdentifier(uri=uri)
    where = await client.text_document_definition_async(lsp.DefinitionParams(text_document=doc,
                                                                               position=pos(3, 5)))
    assert isinstance(where, list) and [w.range.start.line for w in where] == [6]  # M98 H100 -> N100
    where = await client.text_document_definition_async(lsp.DefinitionParams(text_document=doc,
                                                                               position=pos(2, 5)))
    assert isinstance(where, list) and [w.range.start.line for w in where] == [9]  # G65 P10 -> O0010
    refs = await client.text_document_references_async(lsp.ReferenceParams(
        text_document=doc, position=pos(6, 1), context=lsp.ReferenceContext(include_declaration=False)))
    assert refs is not None and sorted(r.range.start.line for r in refs) == [3, 4]
    syms = await client.text_document_document_symbol_async(lsp.DocumentSymbolParams(text_document=doc))
    assert syms is not None
    names = [(s.name, s.range.start.line) for s in syms]  # type: ignore[union-attr]
    assert ("O1", 0) in names and ("O10", 9) in names and ("N100", 6) in names
    assert ("T1 tool change", 1) in names


async def test_definition_in_another_file(client: LanguageClient) -> None:
    root: Path = client.root  # type: ignore[attr-defined]
    (root / "O0042.nc").write_text("O0042\nG00 X0\nM99\n", encoding="utf-8")
    uri, v = await open_doc(client, "caller.nc", "M98 P42\nM30\n")
    await diags(client, uri, v)
    where = await client.text_document_definition_async(lsp.DefinitionParams(
        text_document=lsp.TextDocumentIdentifier(uri=uri), position=pos(0, 5)))
    assert isinstance(where, list) and [w.uri for w in where] == [(root / "O0042.nc").as_uri()]


# ---- inlay hints -----------------------------------------------------------------------
async def test_inlay_hint_is_the_block_time(client: LanguageClient) -> None:
    uri, v = await open_doc(client, "hints.nc", "G90 G00 X0 Y0\nG01 X100. F600.\nM30\n")
    await diags(client, uri, v)
    hints = await client.text_document_inlay_hint_async(lsp.InlayHintParams(
        text_document=lsp.TextDocumentIdentifier(uri=uri), range=lsp.Range(start=pos(0, 0), end=pos(3, 0))))
    assert hints is not None
    by_line = {h.position.line: h.label for h in hints}
    expected_s = 100.0 / (600.0 / 60.0)  # 100 mm at 600 mm/min
    assert by_line[1] == f"{expected_s:.1f} s"
    assert hints[[h.position.line for h in hints].index(1)].position.character == len("G01 X100. F600.")


# ---- code actions ------------------------------------------------------------------------
async def test_insert_missing_feed(client: LanguageClient) -> None:
    text = "G90 G00 X0 Y0\nG01 X10. (cut) ;\nM30\n"
    uri, v = await open_doc(client, "feed.nc", text)
    found = [d for d in await diags(client, uri, v) if d.code in ("N0212", "E0211")]
    assert found
    acts = await actions_for(client, uri, found[0].range, found)
    feed = [a for a in acts if a.title.startswith("Insert feed")]
    assert len(feed) == 1
    new = apply(text, edits_of(feed[0], uri))
    assert new.split("\n")[1] == "G01 X10. F1000. (cut) ;"  # syntec's default feed (1000 mm/min)
    v2 = await replace_all(client, uri, text, new)
    assert not any(d.code in ("N0212", "E0211") for d in await diags(client, uri, v2))


async def test_repair_arc_centre(client: LanguageClient) -> None:
    # start (0,0), end (8,0), programmed centre (3,4): radius 5 at the start, sqrt(41) at the end.
    text = "G90 G17 G00 X0 Y0\nG02 X8. Y0 I3. J4. F100.\nM30\n"
    uri, v = await open_doc(client, "arc.nc", text)
    found = [d for d in await diags(client, uri, v) if d.code == "E0208"]
    assert len(found) == 1
    acts = [a for a in await actions_for(client, uri, found[0].range, found) if "arc" in a.title]
    assert len(acts) == 1
    new = apply(text, edits_of(acts[0], uri))
    # On the chord's bisector x = 4, keeping radius 5 from the start, same side: (4, 3).
    assert new.split("\n")[1] == "G02 X8. Y0 I4. J3. F100."
    v2 = await replace_all(client, uri, text, new)
    assert not any(d.code == "E0208" for d in await diags(client, uri, v2))


async def test_convert_selection_and_target_check(client: LanguageClient) -> None:
    root: Path = client.root  # type: ignore[attr-defined]
    mini = Path(__file__).parent / "data" / "mini.toml"
    (root / "conv").mkdir(exist_ok=True)
    (root / "conv" / "cncc.toml").write_text(f'target = "{mini}"\n', encoding="utf-8")
    text = "G90 G00 X0 Y0\nG01 X10. Y5. F300.\nG81 X1. Y1. Z-2. R1. F100.\nM30\n"
    uri, v = await open_doc(client, "conv/prog.nc", text)
    found = await diags(client, uri, v)
    unsupported = [d for d in found if d.code == "W0890"]
    assert [d.range.start for d in unsupported] == [pos(2, 0)]
    assert "mini cannot run G81" in unsupported[0].message
    acts = await actions_for(client, uri, lsp.Range(start=pos(1, 0), end=pos(1, 18)), [])
    conv = [a for a in acts if a.title.startswith("Convert selection to mini")]
    assert len(conv) == 1
    (e,) = edits_of(conv[0], uri)
    assert e.range == lsp.Range(start=pos(1, 0), end=pos(1, 18))
    assert "G1 X10. Y5. F300." in e.new_text.split("\n")


# ---- adversarial documents ----------------------------------------------------------------
async def still_answers(client: LanguageClient) -> None:
    uri, v = await open_doc(client, f"probe{next_version()}.nc", "G01 X1. F100.\n")
    assert "G01" in await hover_text(client, uri, 0, 1)
    await diags(client, uri, v)


async def test_binary_document(client: LanguageClient) -> None:
    data = bytes(range(256)) * 64
    uri, v = await open_doc(client, "binary.nc", data.decode("latin-1"))
    found = await diags(client, uri, v)
    assert any(d.severity == lsp.DiagnosticSeverity.Error for d in found)
    await still_answers(client)


async def test_endless_macro_loop(client: LanguageClient) -> None:
    text = "#1=0\nWHILE[1 EQ 1] DO1\n#1=#1+1\nG91 G01 X1. F1000.\nEND1\nM30\n"
    uri, v = await open_doc(client, "loop.nc", text)
    await diags(client, uri, v)
    await still_answers(client)


async def test_fifty_megabyte_document(client: LanguageClient) -> None:
    line = "G01 X12.345 Y67.89 F1000. (a long CAM file)\n"
    text = line * (50_000_000 // len(line))
    uri, v = await open_doc(client, "huge.nc", text)
    await still_answers(client)  # answered while the huge analysis runs
    found: list[Any] = await diags(client, uri, v)
    assert any(d.code == "N0990" for d in found)  # stopped at its budget, and said so
