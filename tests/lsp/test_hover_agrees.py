"""The hover's value of a macro variable is the compiler's value.

For every function of each macro flavour (Fanuc/SYNTEC, SZGH, LinuxCNC) over a table
of arguments, ``#1 = FUNC[v]`` is compiled (the value is read back as the X of a
rapid move) and hovered without a run trace (the static fallback); both give the
same number, or the compiler reports an error and the hover says the value is unknown.
"""

from __future__ import annotations

import pytest

from cncc.api import compile_commands
from cncc.dialects import load_dialect
from cncc.ir import Rapid
from cncc.lsp.positions import LineIndex
from cncc.lsp.variables import variable_value

ARGS = (-2.5, -1.5, -1.2, -1.0, -0.5, 0.0, 0.3, 0.5, 1.0, 1.2, 1.5, 2.5, 30.0, 90.0, 123.0)
# The functions each flavour's manual lists (one argument, then the two-argument forms).
FANUC = ("SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN", "SQRT", "ABS", "ROUND", "FIX", "FUP", "LN", "EXP",
         "BIN", "BCD")
LINUXCNC = ("SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN", "SQRT", "ABS", "ROUND", "FIX", "FUP", "LN", "EXP")
CASES: list[tuple[str, str, tuple[str, ...]]] = [("syntec", f, FANUC) for f in FANUC]
CASES += [("fanuc", f, FANUC) for f in ("ROUND", "FIX", "FUP", "ATAN")] + [("szgh", f, FANUC) for f in FANUC]
CASES += [("linuxcnc", f, LINUXCNC) for f in LINUXCNC]


def _texts(dialect: str, expr: str) -> tuple[str, str]:
    """(program for the compiler, program for the hover) assigning ``expr`` to #1."""
    if dialect == "linuxcnc":
        return f"G21 G90\n#1 = [{expr}]\nG00 X#1\nM2\n", f"#1 = [{expr}]\nG00 X#1\n"
    return f"G90\n#1 = {expr}\nG00 X#1\nM30\n", f"#1 = {expr}\nG00 X#1\n"


TOO_BIG_FOR_A_WORD = "E0322"  # the value is fine, but X cannot carry it (EXP[30])
SCALE = 1e12


def _compiled(dialect: str, expr: str) -> float | None:
    """The compiler's value of ``expr`` (None when it reports an error)."""
    text, _ = _texts(dialect, expr)
    cmds, r = compile_commands(text, dialect=dialect)
    scale = 1.0
    if TOO_BIG_FOR_A_WORD in [d.code for d in r.sink]:  # read it back scaled down in the program itself
        cmds, r = compile_commands(text.replace("X#1", "X[#1/1000000/1000000]"), dialect=dialect)
        scale = SCALE
    if not r.ok:
        return None
    rapids = [c for c in cmds if isinstance(c, Rapid)]
    return rapids[-1].end[0] * scale if rapids else 0.0


def _hovered(dialect: str, expr: str) -> str:
    _, text = _texts(dialect, expr)
    site = text.index("#1", text.index("\n"))
    return variable_value(text, LineIndex(text), load_dialect(dialect), 1, site)


def _agree(dialect: str, expr: str) -> None:
    compiled = _compiled(dialect, expr)
    hover = _hovered(dialect, expr)
    if compiled is None:  # the compiler reports an error: no value to show (or the line does not parse)
        assert "not known" in hover or "no assignment" in hover, (dialect, expr, hover)
    else:
        assert hover.startswith(f"**#1** = {compiled:g}"), (dialect, expr, compiled, hover)


@pytest.mark.parametrize(("dialect", "func", "_table"), CASES, ids=[f"{d}-{f}" for d, f, _ in CASES])
def test_hover_agrees_with_compiler(dialect: str, func: str, _table: tuple[str, ...]) -> None:
    for v in ARGS:
        if func in ("BIN", "BCD") and (v < 0 or v != int(v)):
            continue  # defined on non-negative integers only
        if func == "EXP" and v > 30:
            continue  # e^90 does not fit an axis word even scaled down, so the compiler's value is not observable
        _agree(dialect, f"{func}[{v:g}]")


@pytest.mark.parametrize("dialect", ["syntec", "szgh", "linuxcnc"])
def test_two_argument_forms_and_operators_agree(dialect: str) -> None:
    exprs = ["ATAN[1]/[-1]", "ATAN[-1]/[-1]", "[7 MOD 3]", "[-7 MOD 3]", "[2.5 * 4 - 1]", "[1/0]", "[3 GT 2]"]
    if dialect != "linuxcnc":
        exprs += ["ATAN[1,-1]", "POW[2,10]", "[5 AND 3]", "[5 OR 3]", "[5 XOR 3]", "[1 EQ 1]"]
    else:
        exprs += ["[2 ** 10]", "[1 EQ 1]", "[1 AND 0]"]
    for e in exprs:
        _agree(dialect, e)


def test_the_known_disagreements_are_gone() -> None:
    # the compiler's values (Fanuc rules: ROUND half away from zero, FIX toward zero, FUP away from zero)
    assert _compiled("syntec", "ROUND[2.5]") == 3.0 and _hovered("syntec", "ROUND[2.5]").startswith("**#1** = 3")
    assert _compiled("syntec", "FIX[-1.5]") == -1.0 and _hovered("syntec", "FIX[-1.5]").startswith("**#1** = -1")
    assert _compiled("syntec", "FUP[-1.2]") == -2.0 and _hovered("syntec", "FUP[-1.2]").startswith("**#1** = -2")
