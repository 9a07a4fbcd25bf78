"""Runaway programs stop within the step budget; nesting limits; bad presets."""

from __future__ import annotations

from tests.helpers import codes, compile_text


def test_endless_while_stops_at_the_budget() -> None:
    text = "#1=0.\nWHILE [1 EQ 1] DO 1\n#1=#1+1.\nEND 1\nM30\n"
    r = compile_text(text, max_steps=20_000, emit="none")
    assert codes(r) == ["E0301"]
    d = r.sink.items[0]
    assert "20000" in d.message


def test_endless_while_with_moves_streams_and_stops() -> None:
    text = "WHILE [1 EQ 1] DO 1\nG91 G01 X1. F100.\nEND 1\nM30\n"
    r = compile_text(text, max_steps=3_000, emit="none")
    assert codes(r) == ["E0301"]


def test_self_recursive_m98_hits_the_nesting_limit() -> None:
    r = compile_text("M98 P100\nM30\nO100\nG91 G00 X1.\nM98 P100\nM99\n")
    assert codes(r) == ["E0309"]
    assert len(r.sink.items[0].related) == 4


def test_recursive_g65_has_its_own_limit() -> None:
    r = compile_text("G65 P100\nM30\nO100\nG65 P100\nM99\n", dialect_options={"max_macro_depth": 2})
    assert codes(r) == ["E0309"]
    assert len(r.sink.items[0].related) == 2


def test_endless_m99_loop_in_main_stops_at_the_budget() -> None:
    r = compile_text("M98 P100\nM99\nO100\nM99\n", dialect_options={"m99_in_main": "loop"}, max_steps=1000,
                     emit="none")
    assert codes(r) == ["E0301"]


def test_default_budget_is_a_few_million() -> None:
    from cncc.driver import Options

    assert 1_000_000 <= Options().max_steps <= 10_000_000


def test_bad_preset_is_reported() -> None:
    r = compile_text("G00 X#1\nM30\n", defines={0: 1.0})
    assert "E0904" in codes(r)


def test_missing_subprogram_names_the_search_path(tmp_path: object) -> None:
    r = compile_text("M98 P4321\nM30\n", include_dirs=[str(tmp_path)])
    d = next(d for d in r.sink if d.code == "E0310")
    assert "O4321" in d.message and str(tmp_path) in d.message
