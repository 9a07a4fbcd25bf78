"""Code actions never make a program worse (issue 20): no ``F0``, every explicit word kept,
a selection with an error refused with the reason."""

from __future__ import annotations

from cncc.dialects import load_dialect
from cncc.lsp.actions import convert_selection, insert_feed, refusal
from cncc.lsp.analysis import Request, analyze, new_analysis
from cncc.lsp.config import Settings
from cncc.lsp.positions import LineIndex

SYNTEC, GRBL = load_dialect("syntec"), load_dialect("grbl")


def analysed(text: str):  # type: ignore[no-untyped-def]
    a = new_analysis(Request("file:///p.nc", "/p.nc", 1, text, "syntec", Settings()))
    analyze(a, lambda: None)
    return a


def test_insert_feed_takes_the_last_positive_feed_above() -> None:
    text = "G01 X1. F250.\nG01 X2. F0\nG01 X3.\n"
    index = LineIndex(text)
    got = insert_feed(index, SYNTEC, index.line_start(2))
    assert got is not None
    title, [(at, _, new)] = got
    assert new == " F250." and title == "Insert feed F250."  # F0 above is skipped
    assert at == index.line_end(2)


def test_insert_feed_offers_nothing_when_no_feed_is_known() -> None:
    fanuc = load_dialect("fanuc")
    assert fanuc.default_feed_mm_min == 0.0  # fanuc.toml: no default feed (alarm PS0011)
    text = "G00 X0 Y0\nG01 X3. F0\nG01 X4.\n"
    index = LineIndex(text)
    assert insert_feed(index, fanuc, index.line_start(2)) is None


def test_insert_feed_falls_back_on_a_positive_dialect_default() -> None:
    text = "G00 X0 Y0\nG01 X3.\n"
    index = LineIndex(text)
    got = insert_feed(index, SYNTEC, index.line_start(1))
    assert got is not None and got[1][0][2] == " F1000."  # syntec.toml: default feed 1000 mm/min


def test_conversion_keeps_every_explicit_axis_word() -> None:
    text = "G90 G17\nG00 X0. Y0. Z5.\nG01 X10. Y5. F300.\nG01 X10. F300.\nM30\n"
    a = analysed(text)
    got = convert_selection(a.index, a.commands, 1, 3, SYNTEC, GRBL)
    assert got is not None
    (_lo, _hi, new), = got[1]
    # X0. Y0. equal the start position and X10./F300. the previous block's: all written again
    assert new.split("\n") == ["G00 X0. Y0. Z5.", "G01 X10. Y5. F300.", "G01 X10. F300."]


def test_a_selection_with_an_error_is_refused_with_the_reason() -> None:
    text = "G90 G17\nG00 X0. Y0. Z5.\nG01 X10. Q\nG01 X12. F300.\nM30\n"
    a = analysed(text)
    errors = [(d.span.start, d.message) for d in a.diagnostics if d.severity.name == "ERROR"]
    assert any(d.code == "E0108" for d in a.diagnostics)  # Q without a value: the block is skipped
    why = refusal(errors, a.index.line_start(1), a.index.line_end(3))
    assert why is not None and "Q" in why
    assert refusal(errors, a.index.line_start(3), a.index.line_end(4)) is None  # below the bad line
