"""One keyword table per dialect (``Dialect.lexicon``, from cncc/grammar/lexicon.toml).

Must show: the parser's grammar, the macro-word abbreviations, the fast path, the macro
executor's program test and the editor's scanner all take their keywords from that one
table, and the parser and the scanner find the same address words on the whole corpus.
"""

from __future__ import annotations

import tomllib
from importlib import resources
from pathlib import Path

import pytest
from lark import Lark
from lark.exceptions import LarkError

from cncc.diagnostics import DiagnosticSink
from cncc.dialects import DialectError, available, load_dialect, parse_dialect
from cncc.dialects.lexicon import families
from cncc.frontend.fastpath import is_straight_line
from cncc.frontend.macro import needs_executor
from cncc.frontend.parser import Parser, _lark, abbreviations
from cncc.lsp.navigate import O_KEYWORDS
from cncc.lsp.scan import Comments, tokens
from cncc.source import SourceFile

CORPUS = Path(__file__).resolve().parents[1] / "corpus"
TABLE = tomllib.loads(resources.files("cncc.grammar").joinpath("lexicon.toml").read_text(encoding="utf-8"))
EVERY_WORD = sorted({str(w) for t in TABLE.values() for k in ("statements", "functions", "operators") for w in t[k]})
PROBES = ("", "[1]", "[1,2]", "+X1", "(a)", " 1", "2")  # what may follow a keyword in some grammar


def _lexed_as_keyword(parser: Lark, word: str) -> bool:
    """Whether some text starting with ``word`` lexes to a first token that is not an address letter
    and covers the whole word (lark's standard lexer over all the grammar's terminals)."""
    for probe in PROBES:
        try:
            first = next(iter(parser.lex(word + probe)))
        except LarkError:  # the lexer refuses this probe: try the next one
            continue
        text = str(first).upper()
        whole = text == word or (text.startswith(word) and not text[len(word)].isalpha())
        if first.type not in ("LETTER", "NUMBER", "BARE_AXIS") and whole:
            return True
    return False


def _lark_of(name: str) -> Lark:
    d = load_dialect(name)
    parser, _ = _lark(d.grammar, d.comments, d.block_end, (), d.lexicon.functions)
    return parser


@pytest.mark.parametrize("name", available())
def test_the_grammar_reads_exactly_the_lexicons_keywords(name: str) -> None:
    d = load_dialect(name)
    parser = _lark_of(name)
    keywords = d.lexicon.keywords
    assert keywords == {w for t in ("statements", "functions", "operators") for w in TABLE[d.grammar][t]}
    for word in EVERY_WORD:
        assert _lexed_as_keyword(parser, word) == (word in keywords), (name, word)


@pytest.mark.parametrize("name", available())
def test_the_scanner_reads_the_lexicons_keywords(name: str) -> None:
    d = load_dialect(name)
    comments = Comments.of(d)
    assert comments.keywords == d.lexicon.keywords
    for word in EVERY_WORD:
        first = next(tokens(word + " 1", 0, comments))
        assert (first.kind == "keyword") == (word in d.lexicon.keywords), (name, word, first)
        if first.kind == "keyword":
            assert first.text == word and first.end == len(word)


def test_the_other_readers_take_the_same_lists() -> None:
    assert set(TABLE["rs274ngc"]["statements"]) == O_KEYWORDS
    fanuc = load_dialect("fanuc")
    lex = fanuc.lexicon
    # every keyword longer than the two abbreviation letters (no two of Fanuc's share their first two)
    assert {w for w, _ in abbreviations(fanuc)} == {w for w in lex.keywords if len(w) > 2}
    for name in ("syntec", "szgh"):
        d = load_dialect(name)
        for mark in d.lexicon.executor_marks:
            text = f"G01 X1. F100.\n({mark.lower()} in a comment)\n"
            assert not is_straight_line(text, d) and needs_executor(text, d), (name, mark)
    # a word another family uses is no mark here: SZGH's WAT in a SYNTEC comment keeps the fast path
    assert "WAT" not in load_dialect("syntec").lexicon.executor_marks
    assert is_straight_line("G01 X1. F100.\n(WATER ON)\n", load_dialect("syntec"))
    assert not is_straight_line("G01 X1. F100.\n(WATER ON)\n", load_dialect("szgh"))


def test_a_dialect_file_may_replace_a_list() -> None:
    raw = {"name": "x", "grammar": "fanuc", "lexicon": {"functions": ["SIN", "COS"]}}
    d = parse_dialect(raw)
    assert d.lexicon.functions == ("SIN", "COS")
    assert d.lexicon.statements == tuple(TABLE["fanuc"]["statements"])  # the rest from the family
    sink = DiagnosticSink()
    (block,) = list(Parser(d, sink).blocks(SourceFile(0, "t", "#1 = SIN[30] + COS[60]")))
    assert block.statements and not list(sink)
    list(Parser(d, sink).blocks(SourceFile(0, "t", "#1 = TAN[30]")))
    assert {"E0101", "E0108"} & {x.code for x in sink}  # TAN is no function here: T, A, N are letters
    with pytest.raises(DialectError, match="lexicon"):
        parse_dialect({"name": "x", "lexicon": {"function": ["SIN"]}})
    with pytest.raises(DialectError, match="lexicon"):
        parse_dialect({"name": "x", "lexicon": {"functions": ["SIN["]}})


def test_every_grammar_has_a_table() -> None:
    assert {load_dialect(n).grammar for n in available()} <= set(families())


def _corpus() -> list[tuple[str, Path]]:
    return [(d.name, p) for d in sorted(CORPUS.iterdir()) if d.is_dir() for p in sorted(d.iterdir())
            if p.suffix in (".nc", ".ngc", ".gcode", ".tap")]


@pytest.mark.parametrize(("name", "path"), _corpus(), ids=[f"{n}/{p.name}" for n, p in _corpus()])
def test_parser_and_scanner_find_the_same_words_on_the_corpus(name: str, path: Path) -> None:
    d = load_dialect(name)
    text = path.read_text(encoding="utf-8")
    comments = Comments.of(d)
    parser = Parser(d, DiagnosticSink(max_count=100_000))
    src = SourceFile(0, str(path), text)
    pos, checked = 0, 0
    for number, line in enumerate(text.split("\n"), start=1):
        sink = DiagnosticSink()
        parser.sink = sink
        blocks = list(parser.blocks_of_line(src, pos, pos + len(line), number))
        if not list(sink):  # lines the compiler rejects are not compared
            parsed = {(w.letter, w.start) for b in blocks for w in b.words}
            toks = list(tokens(line, pos, comments))
            if len(toks) > 1 and toks[1].kind == "keyword" and toks[1].text in O_KEYWORDS and name == "linuxcnc":
                toks = toks[1:]  # 'o100 sub': the scanner's O word is the label the parser reads with the statement
            scanned = {(t.text, t.start) for t in toks if t.kind == "word"}
            assert parsed == scanned, (number, line)
            checked += len(parsed)
        pos += len(line) + 1
    assert checked > 0
