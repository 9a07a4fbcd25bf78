"""The plain-block fast path must lower exactly like the grammar + interpreter."""

from __future__ import annotations

import sys
from pathlib import Path

from hypothesis import given, settings
from hypothesis import strategies as st

from cncc.diagnostics import DiagnosticSink
from cncc.dialects import load_dialect
from cncc.frontend.fastpath import CAM_LINE, is_straight_line, lower_straight
from cncc.frontend.interp import InterpOptions, Interpreter
from cncc.frontend.parser import ParseOptions, Parser
from cncc.source import SourceMap

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench"))
from gen import cam_program  # noqa: E402

Lowered = tuple[list[object], list[object]]


def both(text: str, dialect: str = "syntec") -> tuple[Lowered, Lowered]:
    d = load_dialect(dialect)
    sm = SourceMap()
    src = sm.add("t.nc", text)
    s1, s2 = DiagnosticSink(), DiagnosticSink()
    fast = list(lower_straight(src, d, s1, InterpOptions()))
    it = Interpreter(d, s2, src.source_id, InterpOptions())
    slow = list(it.run(Parser(d, s2, ParseOptions()).blocks(src)))
    return (fast, list(s1)), (slow, list(s2))


def test_cam_program_agrees() -> None:
    text = cam_program(3000, seed=7)
    assert is_straight_line(text, load_dialect("syntec"))
    (fast, d1), (slow, d2) = both(text)
    assert len(fast) > 2900
    assert fast == slow
    assert d1 == d2


def test_examples_agree() -> None:
    for path in sorted((ROOT / "examples").glob("*.nc")):
        text = path.read_text()
        if is_straight_line(text, load_dialect("syntec")):
            (fast, d1), (slow, d2) = both(text)
            assert fast == slow, path
            assert d1 == d2, path


def test_regex_rejects_what_it_cannot_lower() -> None:
    for line in ["G01 X1 Y2 Z3 A4", "G17 G01 X1", "X1 G01", "G01 X1 (c)", "G1X-", "G04 X1", "G12 X1"]:
        assert CAM_LINE.fullmatch(line) is None, line
    # the number pattern is loose; float() rejects these and the line takes the general path
    for bad in ["G01 X1.2.3 F10", "G01 X. F10", "G01 X1 F1..", "G02 X1 Y1 I1.1.1 J0 F10", "G01 X80.793. F5"]:
        (fast, d1), (slow, d2) = both(bad + "\n")
        assert fast == slow and d1 == d2 and d1, bad
    for line in ["X1", "N10 G1 X1. Y-2 Z.5 F300", "G0 Z5.", "G01 X1;", "G02 X1 Y1 I1 J0 F10"]:
        assert CAM_LINE.fullmatch(line) is not None, line


num = st.one_of(
    st.integers(-99999, 99999).map(str),
    st.decimals(-999, 999, places=3, allow_nan=False, allow_infinity=False).map(lambda d: f"{d}"),
    st.integers(0, 999).map(lambda i: f"{i}."),
)
line = st.one_of(
    st.tuples(st.sampled_from(["", "G0 ", "G1 ", "G00 ", "G01 ", "G90 ", "G91 ", "G70 ", "G71 "]),
              st.lists(st.tuples(st.sampled_from("XYZ"), num), min_size=0, max_size=3, unique_by=lambda t: t[0]),
              st.sampled_from(["", " F100", " F2500.", " F0.5"]),
              st.sampled_from(["", ";", " ;", " // note", " (c)"])).map(
        lambda t: t[0] + " ".join(a + v for a, v in t[1]) + t[2] + t[3]),
    st.sampled_from(["G02 X1. Y1. I0.5 J0.5 F200", "G03 X0 Y0 I-1. J0", "G04 X1.5", "M03 S1000", "G17", "G18",
                     "N10", "T1 M06", "G94", "M30", "G01 X1 Y2 Z3 A4 F5", "G92 X0 Y0"]),
)


@settings(max_examples=150, deadline=None)
@given(st.lists(line, min_size=1, max_size=25))
def test_generated_programs_agree(lines: list[str]) -> None:
    text = "\n".join(lines) + "\n"
    (fast, d1), (slow, d2) = both(text)
    assert fast == slow
    assert d1 == d2
