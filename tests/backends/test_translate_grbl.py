"""grbl output contains only what grbl 1.1 accepts (tests/translate/grbl_validator.py)."""

from __future__ import annotations

from pathlib import Path

import pytest

from cncc.dialects import available
from tests.backends.test_translate_roundtrip import PROGRAMS, translate
from tests.translate.grbl_validator import GrblChecker

pytestmark = pytest.mark.skipif("grbl" not in available(), reason="the grbl dialect file has not landed")


@pytest.mark.parametrize(("source", "path"), PROGRAMS, ids=[f"{s}/{p.stem}" for s, p in PROGRAMS])
def test_grbl_output_passes_the_grbl_checker(source: str, path: Path) -> None:
    out = translate(path.read_text(), source, "grbl")
    assert GrblChecker().check(out) == [], out


def test_line_numbered_grbl_output_passes() -> None:
    text = (PROGRAMS[0][1]).read_text()
    out = translate(text, PROGRAMS[0][0], "grbl", line_numbers=True)
    assert out.startswith("N10 ") and GrblChecker().check(out) == []


@pytest.mark.parametrize(("line", "error"), [
    ("G83 X1. Y1. Z-2. R1. Q1. F100.", "error 20"),
    ("G41 D1 G01 X1. F100.", "error 20"),
    ("G00 G01 X1.", "error 21"),
    ("G00 X1. X2.", "error 25"),
    ("G02 Z1. I1. J0. F10.", "error 26"),
    ("M06", "error 20"),
    ("G04 X1.", "error 28"),
    ("G01 X" + "1" * 80 + ".", "error 11"),
    ("T300", "error 38"),
    ("G68 X0. Y0. R30.", "error 20"),
    ("#1 = 5", "error 1"),
])
def test_the_checker_rejects_what_grbl_rejects(line: str, error: str) -> None:
    assert GrblChecker().block(line).startswith(error)


def test_the_checker_needs_a_feed_before_feed_moves() -> None:
    c = GrblChecker()
    assert c.block("G01 X1.").startswith("error 22")
    assert c.block("G01 X1. F100.") == "" and c.block("G02 X2. Y0. I0.5 J0.") == ""
