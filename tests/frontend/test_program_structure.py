"""Tape marks and program numbers around a program, with and without macros."""

from __future__ import annotations

import pytest

from tests.helpers import calls, canon


@pytest.mark.parametrize("body", ["G01 X1. F100", "#1=1.\nG01 X#1 F100"])
@pytest.mark.parametrize("head", ["%\nO1000\n", "%\nO1000 (x=1)\n", "%\n(header)\nO1000\n", "O1000\n", ""])
def test_percent_and_o_number_before_the_main_program(head: str, body: str) -> None:
    lines, r = canon(head + body + "\nM30\n%\n")
    assert r.ok, [(d.code, d.message) for d in r.sink]
    assert calls(lines, "STRAIGHT_FEED") == [("STRAIGHT_FEED", [1.0, 0.0, 0.0, 0.0, 0.0, 0.0])]
