"""The macro functions of each flavour give the manuals' values, in the compiler and the hover.

The expected values are the manuals': Fanuc custom macro B (ROUND half away from
zero; the FIX/FUP example #1 = 1.2, #2 = -1.2 -> FIX 1 / -1, FUP 2 / -2; ATAN[y]/[x]
in 0-360; AND OR XOR on the bits), the SZGH-CNC990MDb manual section 3.30.5 (seed 002:
its function list has no MOD, POW, BIN or BCD), and LinuxCNC's G-code documentation
(FIX rounds down, FUP up; MOD is never negative; AND OR XOR are logical; EQ within
0.0001), the LinuxCNC values also checked against rs274 itself when the oracle is
installed.  Each expression is compiled and hovered (tests/lsp/test_hover_agrees.py).
"""

from __future__ import annotations

import re

import pytest

from cncc.api import compile_commands
from tests.lsp.test_hover_agrees import _compiled, _hovered
from tests.oracle.harness import rs274_path, run_rs274

FANUC = [
    ("ROUND[2.5]", 3), ("ROUND[-2.5]", -3), ("ROUND[1.4]", 1), ("ROUND[-1.5]", -2), ("ROUND[0.5]", 1),
    ("FIX[1.2]", 1), ("FIX[-1.2]", -1), ("FIX[-1.5]", -1), ("FUP[1.2]", 2), ("FUP[-1.2]", -2), ("FUP[2]", 2),
    ("ABS[-2.5]", 2.5), ("SQRT[2.25]", 1.5), ("SIN[30]", 0.5), ("COS[60]", 0.5), ("TAN[45]", 1),
    ("ASIN[0.5]", 30), ("ACOS[0.5]", 60), ("ATAN[1]/[1]", 45), ("ATAN[1]/[-1]", 135), ("ATAN[-1]/[-1]", 225),
    ("ATAN[-1]/[1]", 315), ("LN[1]", 0), ("EXP[0]", 1),
    ("[5 AND 3]", 1), ("[5 OR 3]", 7), ("[5 XOR 3]", 6), ("[7 / 2]", 3.5),
]
FANUC_ONLY = [("BIN[24]", 18), ("BCD[18]", 24), ("BIN[BCD[59]]", 59), ("POW[2,10]", 1024), ("MOD[7,3]", 1),
              ("[7 MOD 3]", 1)]
LINUXCNC = [
    ("ROUND[2.5]", 3), ("ROUND[-2.5]", -3), ("ROUND[1.4]", 1), ("ROUND[-1.5]", -2),
    ("FIX[1.5]", 1), ("FIX[-1.5]", -2), ("FIX[-1.2]", -2), ("FUP[1.2]", 2), ("FUP[-1.2]", -1), ("FUP[-1.5]", -1),
    ("ABS[-2.5]", 2.5), ("SQRT[2.25]", 1.5), ("SIN[30]", 0.5), ("COS[60]", 0.5), ("TAN[45]", 1),
    ("ASIN[0.5]", 30), ("ACOS[0.5]", 60), ("ATAN[1]/[1]", 45), ("ATAN[1]/[-1]", 135), ("ATAN[-1]/[-1]", -135),
    ("LN[1]", 0), ("EXP[0]", 1),
    ("[-7 MOD 3]", 2), ("[7 MOD -3]", 1), ("[7 MOD 3]", 1), ("[5 AND 3]", 1), ("[1 AND 0]", 0), ("[5 OR 0]", 1),
    ("[5 XOR 3]", 0), ("[5 XOR 0]", 1), ("[2 ** 10]", 1024), ("[1 EQ 1.00001]", 1), ("[1 EQ 1.001]", 0),
    ("[1 NE 1.00001]", 0), ("[3 GT 2]", 1), ("[2 LE 1]", 0),
]


def _check(dialect: str, expr: str, want: float) -> None:
    got = _compiled(dialect, expr)
    assert got is not None and abs(got - want) < 1e-3, (dialect, expr, got, want)
    hover = _hovered(dialect, expr)
    m = re.match(r"\*\*#1\*\* = (\S+)", hover)
    assert m is not None and abs(float(m.group(1)) - want) < 1e-3, (dialect, expr, hover, want)


@pytest.mark.parametrize("dialect", ["syntec", "fanuc", "szgh"])
@pytest.mark.parametrize(("expr", "want"), FANUC, ids=[e for e, _ in FANUC])
def test_fanuc_family_values(dialect: str, expr: str, want: float) -> None:
    _check(dialect, expr, want)


@pytest.mark.parametrize("dialect", ["syntec", "fanuc"])
@pytest.mark.parametrize(("expr", "want"), FANUC_ONLY, ids=[e for e, _ in FANUC_ONLY])
def test_macro_b_functions_szgh_has_not(dialect: str, expr: str, want: float) -> None:
    _check(dialect, expr, want)


@pytest.mark.parametrize(("expr", "_want"), FANUC_ONLY, ids=[e for e, _ in FANUC_ONLY])
def test_szgh_refuses_what_its_manual_does_not_list(expr: str, _want: float) -> None:
    _, r = compile_commands(f"G90\n#1 = {expr}\nG00 X#1\nM30\n", dialect="szgh")
    assert "E0325" in [d.code for d in r.sink], expr
    assert "not known" in _hovered("szgh", expr)  # and the hover shows no value


@pytest.mark.parametrize(("expr", "want"), LINUXCNC, ids=[e for e, _ in LINUXCNC])
def test_linuxcnc_values(expr: str, want: float) -> None:
    _check("linuxcnc", expr, want)


@pytest.mark.skipif(rs274_path() is None, reason="the LinuxCNC oracle is not installed (scripts/ensure-rs274.sh)")
def test_linuxcnc_values_are_rs274s() -> None:
    lines = ["G20 G90"] + [f"G0 X[{expr}]" for expr, _ in LINUXCNC] + ["M2"]
    run = run_rs274("\n".join(lines) + "\n")
    assert run.ok, run.error
    xs = [float(args[0]) for name, args in run.calls if name == "STRAIGHT_TRAVERSE"]
    assert len(xs) == len(LINUXCNC)
    for (expr, want), x in zip(LINUXCNC, xs, strict=True):
        assert abs(x - want) < 1e-4, (expr, x, want)


def test_linuxcnc_exp_overflow_is_a_diagnostic() -> None:
    # rs274 stops with "Calculation resulted in 'infinity'"; cncc used to raise OverflowError
    _, r = compile_commands("G21\n#1 = [EXP[1000]]\nG0 X1\nM2\n", dialect="linuxcnc")
    assert "E0305" in [d.code for d in r.sink]
