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


@pytest.mark.parametrize(("swapped", "on", "off"), [(False, "G51", "G50"), (True, "G50", "G51")])
def test_g50_g51_meaning_follows_the_option(swapped: bool, on: str, off: str) -> None:
    """SYNTEC A-01: the code list swaps G50/G51; the option must not break plain programs."""
    opts = {"dialect_options": {"g50_is_cancel": not swapped}}
    lines, r = canon("G01 X1. F100\n", **opts)
    assert r.ok and calls(lines, "STRAIGHT_FEED")[0][1][:2] == [1.0, 0.0]
    lines, r = canon(f"{on} X0 Y0 P2.\nG01 X1. F100\n{off}\nG01 X1. Y1.\n", **opts)
    assert r.ok, [(d.code, d.message) for d in r.sink]
    assert [a[:2] for _, a in calls(lines, "STRAIGHT_FEED")] == [[2.0, 0.0], [1.0, 1.0]]
