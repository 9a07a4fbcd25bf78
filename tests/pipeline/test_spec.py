"""The -p spec: parsing with positions, option types, and the driver's positioned E0991."""

from __future__ import annotations

import pytest

from cncc.api import compile_text
from cncc.pipeline.builder import pass_names, requests
from cncc.pipeline.spec import SpecError, convert, parse
from tests.helpers import codes


def test_names_options_and_columns() -> None:
    spec = "expand-cycles, arc-check{repair=true, abs_tol_mm=0.05},polar"
    got = parse(spec)
    assert [r.name for r in got] == ["expand-cycles", "arc-check", "polar"]
    assert got[1].options == {"repair": "true", "abs_tol_mm": "0.05"}
    assert spec[got[1].start:got[1].end] == "arc-check"
    lo, hi = got[1].option_columns["abs_tol_mm"]
    assert spec[lo:hi] == "abs_tol_mm=0.05"
    assert parse("") == []


@pytest.mark.parametrize(("spec", "bad"), [
    ("a,,b", ","),  # an empty name: points at the second comma
    ("a{x}", "x"),  # an option without a value
    ("a b", "b"),
    ("1a", "1"),
    ("a{x=1,x=2}", "x"),
])
def test_syntax_errors_point_at_the_fault(spec: str, bad: str) -> None:
    with pytest.raises(SpecError) as exc:
        parse(spec)
    assert spec[exc.value.start:exc.value.start + len(bad)] == bad


def test_unclosed_options_and_a_trailing_comma() -> None:
    for spec in ("arc-check{repair=true", "arc-check,"):
        with pytest.raises(SpecError):
            parse(spec)


def test_convert_follows_the_field_type() -> None:
    assert convert("true", "bool") is True and convert("off", "bool") is False
    assert convert("3", "int") == 3 and convert("0.5", "float") == 0.5
    assert convert("none", "float | None") is None and convert("2", "float | None") == 2.0
    with pytest.raises(ValueError):
        convert("maybe", "bool")
    with pytest.raises(ValueError):
        convert("x", "frozenset[str]")


def test_unknown_pass_lists_the_passes_and_suggests_one() -> None:
    spec = "expand-cycles,arc-chek"
    with pytest.raises(SpecError) as exc:
        requests(spec)
    assert spec[exc.value.start:exc.value.end] == "arc-chek"
    assert "did you mean 'arc-check'" in exc.value.message
    for name in pass_names():
        assert name in exc.value.message


def test_unknown_option_lists_the_options() -> None:
    spec = "arc-check{tolerance=1}"
    with pytest.raises(SpecError) as exc:
        requests(spec)
    assert spec[exc.value.start:exc.value.end] == "tolerance=1"
    for option in ("abs_tol_mm", "rel_tol", "repair"):
        assert option in exc.value.message


@pytest.mark.parametrize("spec", [
    "arc-check{repair=maybe}",  # not a bool
    "expand-cycles{keep=G81}",  # a frozenset: not settable from text
    "plan{level=3}",  # -O chooses it
    "blend,expand-cycles",  # a path pass after the plan stage
    "verify",  # verify without plan
    "expand-cycles,verify,plan",
])
def test_bad_specs_are_refused(spec: str) -> None:
    with pytest.raises(SpecError):
        requests(spec)


def test_the_driver_reports_a_positioned_e0991_and_compiles_nothing() -> None:
    r = compile_text("G01 X10. F100\n", passes="expand-cycles,bogus")
    assert codes(r) == ["E0991"]
    (d,) = list(r.sink)
    src = r.sources.get(d.span.source_id)
    assert src is not None and src.text == "expand-cycles,bogus"
    assert src.text[d.span.start:d.span.end] == "bogus"
    assert r.output == ""


def test_print_after_an_unknown_pass_is_e0991() -> None:
    r = compile_text("G01 X10. F100\n", print_after=("arc-chek",))
    assert codes(r) == ["E0991"]
