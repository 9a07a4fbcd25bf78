"""Lexical structure of the Fanuc family (shared/spec/syntec-mill-v8.20.md section 2)."""

from __future__ import annotations

from cncc.diagnostics import DiagnosticSink
from cncc.dialects import load_dialect
from cncc.frontend import syntax as sx
from cncc.frontend.parser import ParseOptions, Parser, grammar_text
from cncc.source import SourceMap


def parse(text: str, strict: bool = False) -> tuple[list[sx.Block], DiagnosticSink]:
    sink = DiagnosticSink()
    src = SourceMap().add("t.nc", text)
    return list(Parser(load_dialect("syntec"), sink, ParseOptions(strict=strict)).blocks(src)), sink


def words(b: sx.Block) -> list[tuple[str, float, bool]]:
    return [(w.letter, w.value, w.point) for w in b.words]


def test_numbers_signs_points_and_spaces() -> None:
    (b,), sink = parse("G1 X -0.005 Y+2 Z.5 A3. F3000.")
    assert words(b) == [("G", 1.0, False), ("X", -0.005, True), ("Y", 2.0, False), ("Z", 0.5, True),
                        ("A", 3.0, True), ("F", 3000.0, True)]
    assert not list(sink)


def test_double_decimal_point_lenient_and_strict() -> None:
    (b,), sink = parse("G01 X10. Y80.793. (c)")
    assert words(b)[2] == ("Y", 80.793, True)
    assert [d.code for d in sink] == ["W0102"]
    _, sink = parse("G01 X10. Y80.793. (c)", strict=True)
    assert [d.code for d in sink] == ["E0102"]


def test_comments_block_end_and_free_text_after_semicolon() -> None:
    blocks, sink = parse("G04 X2.5;//delay\nN100 ; sub-program list\n(alt; block)\nG0 X1 (a) Y2 // b\n")
    assert [c.text for b in blocks for c in b.comments] == ["//delay", "sub-program list", "(alt; block)", "(a)",
                                                            "// b"]
    assert words(blocks[3]) == [("G", 0.0, False), ("X", 1.0, False), ("Y", 2.0, False)]
    assert not list(sink)


def test_two_blocks_on_one_line() -> None:
    blocks, _ = parse("G90 X1; G91 X2;")
    assert [words(b) for b in blocks] == [[("G", 90.0, False), ("X", 1.0, False)],
                                          [("G", 91.0, False), ("X", 2.0, False)]]


def test_program_structure_and_block_delete() -> None:
    blocks, sink = parse("%\nO0010\n/G01 X1\n/2 G01 X2\nN001 G00 X0\n")
    assert blocks[0].percent
    assert words(blocks[1]) == [("O", 10.0, False)]
    assert blocks[2].block_delete == 1 and blocks[3].block_delete == 2
    assert words(blocks[4])[0] == ("N", 1.0, False)
    assert not list(sink)


def test_spans_are_absolute_offsets() -> None:
    text = "G00 X1\nG01 Y2 (c)\n"
    blocks, _ = parse(text)
    w = blocks[1].words[1]
    assert text[w.start:w.end] == "Y2"
    c = blocks[1].comments[0]
    assert text[c.start:c.end] == "(c)"


def test_macro_statements_parse() -> None:
    blocks, sink = parse("#1 = [#2 + 3] * SIN[30]\nIF [#1 GT 2] GOTO 10\nWHILE [#1 LT 5] DO 1\nX#1 Y-[#2/2]\nEND 1\n")
    assert not list(sink)
    assert isinstance(blocks[0].statements[0], sx.Assign)
    assert isinstance(blocks[1].statements[0], sx.If)
    assert isinstance(blocks[2].statements[0], sx.While) and blocks[2].statements[0].loop_id == 1
    assert blocks[3].words[0].expr is not None and isinstance(blocks[3].words[1].expr, sx.Neg)
    assert isinstance(blocks[4].statements[0], sx.EndLoop)


def test_grammar_variants_follow_the_dialect() -> None:
    g = grammar_text("fanuc", ("paren",), "")
    assert "SLASH_COMMENT" not in g and "SEMI_COMMENT" not in g and "BLOCK_END" not in g
    g = grammar_text("fanuc", ("paren", "semi"), "")
    assert "SEMI_COMMENT" in g


def test_fullwidth_punctuation_lenient_and_strict() -> None:
    (b,), sink = parse("G01 X1.（note）；")
    assert words(b) == [("G", 1.0, False), ("X", 1.0, True)]
    assert [c.text for c in b.comments] == ["(note)"]
    assert [d.code for d in sink] == ["W0110"]
    _, sink = parse("G01 X1.；", strict=True)
    assert [d.code for d in sink] == ["E0104"]
