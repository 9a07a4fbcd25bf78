"""LinuxCNC's arc radius tolerance (ArcCheck.for_dialect with the linuxcnc options).

The limits are those measured on rs274 2.9 (LinuxCNC's stand-alone interpreter): a centre
arc is refused when its end radius differs from the start radius by more than 100 absolute
tolerances, or by more than both the absolute tolerance (0.0283 mm; 0.00283 inch in G20
programs) and 0.1 % of the radius.  An R arc whose chord is 2R in inch words is fine.
"""

from __future__ import annotations

import pytest

from tests.helpers import codes, compile_text


def _arc(units: str, r: float, end_y: float) -> list[str]:
    text = f"{units} F100\nG0 X{r} Y0\nG3 X0 Y{end_y} I-{r} J0\nM2\n"
    return codes(compile_text(text, dialect="linuxcnc"))


@pytest.mark.parametrize("units, r, end_y, refused", [
    ("G21", 10, 10.028, False), ("G21", 10, 10.029, True),              # absolute, mm
    ("G20", 1, 1.00282, False), ("G20", 1, 1.00283, True),              # absolute, inch programs
    ("G21", 1000, 1001, False), ("G21", 1000, 1001.5, True),            # 0.1 % of the radius
    ("G21", 5000, 5002.8, False), ("G21", 5000, 5002.9, True),          # 100 x 0.0283 mm at any radius
    ("G20", 1000, 1000.28, False), ("G20", 1000, 1000.29, True),        # 100 x 0.00283 in
])
def test_centre_arc_limits_are_rs274s(units: str, r: float, end_y: float, refused: bool) -> None:
    assert ("E0208" in _arc(units, r, end_y)) is refused


def test_r_arc_with_a_chord_of_exactly_2r_in_inches() -> None:
    # 2.8999 / 2 - 1.4499 = 0.00005 in: at the limit rs274 2.9 accepts (the words become mm first)
    r = compile_text("G20 F10\nG0 X0.0001 Y0\nG2 X2.9 Y0 R1.4499\nG2 X0.0001 Y0 R1.44995\nM2\n", dialect="linuxcnc")
    assert r.ok, codes(r)
