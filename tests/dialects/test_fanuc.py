"""Fanuc 0i (macro B): the SYNTEC tables with Fanuc's units codes and without SYNTEC-only codes."""

from __future__ import annotations

from cncc.dialects import load_dialect
from tests.helpers import canon, codes, moves


def test_units_are_g20_g21() -> None:
    got = moves("G20 G90\nG0 X1. Y2.\nG21\nG0 X10. Y20.\n", "fanuc")
    # canon positions are in program units: 1 inch and 2 inch, then 10 mm and 20 mm.
    assert [m[1][:2] for m in got] == [(1.0, 2.0), (10.0, 20.0)]
    _, r = canon("G70\n", "fanuc")
    assert codes(r) == ["E0201"]  # G70 is a turning cycle number on a Fanuc mill, not a units code


def test_syntec_only_codes_are_absent() -> None:
    d = load_dialect("fanuc")
    for name in ("G134", "G135", "G136", "G137.1", "G37.1", "G06.2", "G70", "G71", "G59.1"):
        letter, number = name[0], name[1:]
        from cncc.dialects import code_tenths

        assert d.code(letter, code_tenths(number)) is None, name
    assert d.code("G", 200) is not None and d.code("G", 210) is not None


def test_liu_rule_and_no_default_feed() -> None:
    got = moves("G90 G00 X5500 Y1.\n", "fanuc")
    assert got[0][1][:2] == (5.5, 1.0)  # X5500 = 5.5 mm (IS-B, no decimal point)
    _, r = canon("G01 X1.\n", "fanuc")
    assert "E0211" in codes(r)  # no default feed on a Fanuc


def test_macro_b_runs() -> None:
    got = moves("#1=2.\nWHILE[#1 LT 6.]DO1\nG01 X#1 F100.\n#1=#1+2.\nEND1\nM30\n", "fanuc")
    assert [m[1][0] for m in got] == [2.0, 4.0]
