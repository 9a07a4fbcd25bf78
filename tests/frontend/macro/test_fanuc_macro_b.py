"""A Fanuc macro B test set written for cncc (run with the syntec dialect, whose
macro flavour is Fanuc): bolt circle with WHILE, a family of parts driven by -D,
nested calls with local scopes, vacant-variable arithmetic, #3000 alarms, GOTO
into and out of loops.  Expected coordinates are computed here independently."""

from __future__ import annotations

import math

import pytest

from tests.helpers import calls, canon, codes, compile_text, moves


def xyz(text: str, **opts: object) -> list[tuple[float, ...]]:
    return [m[1][:3] for m in moves(text, "syntec", **opts)]


def pos6(text: str) -> list[list[float]]:
    lines, _ = canon(text)
    return [args[:6] for _, args in calls(lines, "STRAIGHT_TRAVERSE", "STRAIGHT_FEED")]


BOLT_CIRCLE = """(BOLT CIRCLE: #1 HOLES ON RADIUS #2 ABOUT #3,#4 FROM ANGLE #5)
#1=6. #2=25. #3=100. #4=50. #5=15.
#10=0.
WHILE [#10 LT #1] DO 1
#11=#5+#10*360./#1
G00 X[#3+#2*COS[#11]] Y[#4+#2*SIN[#11]]
G01 Z-5. F200.
G00 Z2.
#10=#10+1.
END 1
M30
"""


def test_bolt_circle_with_while() -> None:
    pts = [p for p in xyz(BOLT_CIRCLE) if p[2] == -5.0]
    assert len(pts) == 6
    for k, (x, y, _) in enumerate(pts):
        a = math.radians(15.0 + 60.0 * k)
        assert x == pytest.approx(100.0 + 25.0 * math.cos(a), abs=1e-4)
        assert y == pytest.approx(50.0 + 25.0 * math.sin(a), abs=1e-4)


FAMILY = """(FAMILY OF PARTS: POCKET #100 BY #101 DEEP #102)
IF [#100 EQ #0] THEN #100=40.
IF [#101 EQ #0] THEN #101=20.
IF [#102 EQ #0] THEN #102=3.
G00 X0. Y0. Z2.
G01 Z-#102 F100.
X#100
Y#101
X0.
Y0.
M30
"""


def test_family_of_parts_defaults_and_presets() -> None:
    default = xyz(FAMILY)
    assert default[-4:] == [(40, 0, -3), (40, 20, -3), (0, 20, -3), (0, 0, -3)]
    preset = xyz(FAMILY, defines={100: 65.0, 102: 1.5})
    assert preset[-4:] == [(65, 0, -1.5), (65, 20, -1.5), (0, 20, -1.5), (0, 0, -1.5)]


NESTED = """#1=100.
G65 P100 A1. B2.
G00 X#1 Y#2
M30
O100
(LEVEL 1: #1=A, #2=B)
G65 P200 A[#1*10.]
G00 X#1 Y#2
M99
O200
(LEVEL 2: ONLY A GIVEN; B IS VACANT HERE)
#2=#2+5.
G00 X#1 Y#2
M99
"""


def test_nested_calls_keep_local_scopes() -> None:
    # level 2: #1 = 10, #2 vacant + 5 = 5; level 1 keeps #1 = 1, #2 = 2;
    # the main program's #1 = 100 and #2 (vacant: Y word left out, Y stays 2)
    assert xyz(NESTED) == [(10, 5, 0), (1, 2, 0), (100, 2, 0)]


def test_m98_shares_the_callers_locals() -> None:
    text = "#1=3.\nM98 P300\nG00 X#1\nM30\nO300\n#1=#1+1.\nM99\n"
    assert xyz(text) == [(4, 0, 0)]


VACANT = """#1=#0
#2=#1
#3=#1+#1
#4=#1*5.
#5=[#1 EQ #0]
#6=[#3 EQ #0]
#7=[#1 LT 1.]
G00 X#3 Y#4 Z[#5*10.+#6]
IF [#2 NE #0] GOTO 10
G00 A7.
N10 G00 B#7
M30
"""


def test_vacant_variable_arithmetic_and_comparisons() -> None:
    m = pos6(VACANT)
    # #3 = #4 = 0 (vacant counts as 0 in arithmetic); #1 EQ #0 true, #3 EQ #0 false (#3 is 0)
    assert m[0][:3] == [0.0, 0.0, 10.0]
    # #2 = #1 stays vacant, so the GOTO is not taken; vacant < 1 is true
    assert m[1][3] == 7.0
    assert m[2][4] == 1.0


def test_vacant_word_is_left_out() -> None:
    assert xyz("G00 X5. Y6.\nG00 X#1 Y1.\nM30\n") == [(5, 6, 0), (5, 1, 0)]


def test_alarm_3000_stops_with_its_message() -> None:
    text = "#1=2.\nIF [#1 GT 1.] GOTO 99\nG00 X1.\nN99 #3000=12 (TOOL TOO LONG)\nG00 X2.\nM30\n"
    lines, r = canon(text)
    d = next(d for d in r.sink if d.code == "E0311")
    assert "3012" in d.message and "TOOL TOO LONG" in d.message
    assert not any("STRAIGHT_TRAVERSE" in ln for ln in lines)


def test_alarm_inside_a_macro_carries_the_call_chain() -> None:
    text = "G65 P500\nM30\nO500\nM98 P600\nM99\nO600\n#3000=1 (DEEP)\nM99\n"
    r = compile_text(text)
    d = next(d for d in r.sink if d.code == "E0311")
    assert len(d.related) == 2
    assert [rel.span.start for rel in d.related] == [text.index("M98 P600"), 0]


GOTO_OUT = """#1=0.
WHILE [#1 LT 10.] DO 1
#1=#1+1.
IF [#1 EQ 3.] GOTO 50
G00 X#1
END 1
N50 G00 Y#1
M30
"""


def test_goto_out_of_a_loop() -> None:
    assert xyz(GOTO_OUT) == [(1, 0, 0), (2, 0, 0), (2, 3, 0)]


def test_goto_into_a_loop_is_an_error() -> None:
    text = "GOTO 20\nWHILE [#1 LT 3.] DO 1\nN20 #1=#1+1.\nEND 1\nM30\n"
    assert "E0313" in codes(compile_text(text))


def test_loop_structure_errors() -> None:
    assert "E0307" in codes(compile_text("#1=1.\nEND 1\nM30\n"))
    crossing = "WHILE [1 EQ 1] DO 1\nWHILE [1 EQ 1] DO 2\nEND 1\nEND 2\nM30\n"
    assert "E0308" in codes(compile_text(crossing, max_steps=100))
    assert "E0308" in codes(compile_text("WHILE [1 EQ 0] DO 4\nEND 4\nM30\n"))


def test_functions_and_precedence() -> None:
    text = ("#1=2.+3.*4.\n#2=[2.+3.]*4.\n#3=SQRT[16.]+ABS[-2.]\n#4=ROUND[2.5]+FIX[-2.7]+FUP[2.1]\n"
            "#5=ATAN[1.]/[1.]\n#6=ACOS[0.]\nG00 X#1 Y#2 Z#3 A#4 B#5 C#6\nM30\n")
    assert pos6(text)[0] == [14.0, 20.0, 6.0, 3.0 - 2.0 + 3.0, 45.0, 90.0]


def test_indirect_variables_and_modal_system_variables() -> None:
    text = "#10=3.\n#[#10]=7.\nG91\n#20=#4003\nG90\nG00 X#3 Y#20 Z#5001\nM30\n"
    assert xyz(text) == [(7, 91, 0)]


def test_division_by_zero_and_domain_errors() -> None:
    assert "E0304" in codes(compile_text("#1=1./0\nM30\n"))
    assert "E0305" in codes(compile_text("#1=SQRT[-1.]\nM30\n"))
    assert "E0303" in codes(compile_text("#0=1.\nM30\n"))
    assert "E0306" in codes(compile_text("GOTO 77\nM30\n"))
