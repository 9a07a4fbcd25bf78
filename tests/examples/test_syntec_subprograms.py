"""SYNTEC subprogram and macro-call examples: E000-38 (G65), E000-39 (G66/G67) of
shared/spec/syntec-mill-v8.20.md and the same-file M98 H calls of
shared/spec/syntec-900m.md (E004-30)."""

from __future__ import annotations

from tests.helpers import compile_text, moves

O0010 = "O0010\n#100=#100+1.\nG91 G00 X#24 Y#25\nM99\n"


def xyz(text: str, **opts: object) -> list[tuple[float, ...]]:
    return [m[1][:3] for m in moves(text, "syntec", **opts)]


def test_e000_38_g65_calls_twenty_times_with_x_y_arguments() -> None:
    text = "#100=0.\nG65 P10 L20 X10.0 Y10.0\nG90 G00 Z#100\nM30\n" + O0010
    pts = xyz(text)
    assert pts[-1] == (200.0, 200.0, 20.0)  # 20 calls, each +10 +10; #100 counts them
    assert len(pts) == 21


def test_e000_38_integer_arguments_follow_the_liu_rule() -> None:
    # SYNTEC reads X10 without a point as 10 um; as an argument it is 0.01 mm
    text = "G65 P10 X10 Y10.\nM30\n" + O0010.replace("#100=#100+1.\n", "")
    assert xyz(text) == [(0.01, 10.0, 0.0)]


def test_e000_39_g66_calls_after_each_move() -> None:
    text = ("#100=0.\nG91\nG66 P10 L2 X10.0 Y10.0\nX20.0\nY20.0\nG67\nX1.0\nG90 G00 Z#100\nM30\n" + O0010)
    pts = xyz(text)
    # G66 arms the call; X20 then two calls (+10,+10 each); Y20 then two calls; G67 stops it
    assert pts[:6] == [(20, 0, 0), (30, 10, 0), (40, 20, 0), (40, 40, 0), (50, 50, 0), (60, 60, 0)]
    assert pts[6] == (61, 60, 0)
    assert pts[-1] == (61, 60, 4)  # four executions of O0010


E004_30 = """N001 T1 S1000 M03;//use tool NO. 1
N002 M98 H100;//execute sub-program
N003 G51.1 X60.0;
N004 M98 H100;
N005 G50.1;
N009 M05;
N010 M30;
N100;//sub-program list
G00 X60.0 Y55.0;
G01 Y75.0 F500.;
X80.0;
X120.0;
Y105.0;
X80.0 Y95.0;
Y75.0;
M99;
"""


def test_e004_30_m98_h_runs_the_label_after_m30_twice() -> None:
    r = compile_text(E004_30)
    assert r.ok, [d.message for d in r.sink]
    pts = [p[:2] for p in xyz(E004_30)]
    first = [(60, 55), (60, 75), (80, 75), (120, 75), (120, 105), (80, 95), (80, 75)]
    assert pts[:7] == first
    assert len(pts) == 14  # the label body runs once per M98 H100 and never after M30
    # second pass mirrored about X = 60: x' = 120 - x
    assert pts[7:] == [(120 - x, y) for x, y in first]


def test_m99_in_the_main_program_ends_it_or_loops_on_request() -> None:
    r = compile_text("G00 X1.\nM99\n")
    assert r.ok and "PROGRAM_END" in r.output
    loop = compile_text("G00 X1.\nM99\n", dialect_options={"m99_in_main": "loop"}, max_steps=50)
    assert any(d.code == "E0301" for d in loop.sink)
