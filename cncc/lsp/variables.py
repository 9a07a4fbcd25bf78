"""Values of macro variables for hover: straight-line reading of assignments.

Reads the assignments (``#1 = 5``, ``#2 = #1 * 2``) above a point in document
order with the front end's parser, and evaluates their expressions when every
operand is known.  Jumps, loops and calls are not followed, so when the program
has any, the hover says the value is the last one assigned above, not a proof.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable

from cncc.diagnostics import DiagnosticSink
from cncc.dialects import Dialect
from cncc.lsp.positions import LineIndex
from cncc.source import SourceFile

_ASSIGN_RE = re.compile(r"#\s*\d+\s*=")
_FLOW_RE = re.compile(r"\b(GOTO|WHILE|IF)\b|M\s*98|G\s*6[56]\b", re.IGNORECASE)
MAX_LINES = 50_000
_FUNCS: dict[str, Callable[[float], float]] = {
    "SIN": lambda a: math.sin(math.radians(a)), "COS": lambda a: math.cos(math.radians(a)),
    "TAN": lambda a: math.tan(math.radians(a)), "ASIN": lambda a: math.degrees(math.asin(a)),
    "ACOS": lambda a: math.degrees(math.acos(a)), "ATAN": lambda a: math.degrees(math.atan(a)),
    "SQRT": math.sqrt, "ABS": abs, "ROUND": lambda a: float(round(a)), "FIX": lambda a: float(math.floor(a)),
    "FUP": lambda a: float(math.ceil(a)), "LN": math.log, "EXP": math.exp,
}
_BINOPS: dict[str, Callable[[float, float], float]] = {
    "+": lambda a, b: a + b, "-": lambda a, b: a - b, "*": lambda a, b: a * b, "/": lambda a, b: a / b,
    "MOD": lambda a, b: math.fmod(a, b), "EQ": lambda a, b: float(a == b), "NE": lambda a, b: float(a != b),
    "GT": lambda a, b: float(a > b), "GE": lambda a, b: float(a >= b), "LT": lambda a, b: float(a < b),
    "LE": lambda a, b: float(a <= b),
}


def variable_value(text: str, index: LineIndex, dialect: Dialect, number: int, offset: int) -> str:
    """Markdown for variable ``#number`` as seen at ``offset``."""
    from cncc.frontend.parser import Parser
    from cncc.frontend.syntax import Assign

    upto = index.line_of(offset)
    values: dict[int, float] = {}
    last_line = -1
    flow = False
    parser = Parser(dialect, DiagnosticSink(max_count=10))
    for line in range(max(0, upto - MAX_LINES), upto):
        body = index.line_text(line)
        if _FLOW_RE.search(body):
            flow = True
        if not _ASSIGN_RE.search(body):
            continue
        for block in parser.blocks(SourceFile(0, "", body)):
            for st in block.statements:
                if isinstance(st, Assign) and st.target.index is not None and not st.target.name:
                    target = _eval(st.target.index, values)
                    if target is None:
                        continue
                    value = _eval(st.expr, values)
                    key = int(target)
                    if value is None:
                        values.pop(key, None)
                    else:
                        values[key] = value
                    if key == number:
                        last_line = line
    if number not in values:
        if last_line >= 0:
            return f"**#{number}** — assigned at line {last_line + 1}; its value is not known before run time."
        return f"**#{number}** — no assignment above this point (vacant unless set by a call or the machine)."
    note = " (last assignment above; jumps, loops and calls are not followed)" if flow else ""
    return f"**#{number}** = {values[number]:g}{note}\n\nset at line {last_line + 1}"


def _eval(expr: object, values: dict[int, float]) -> float | None:
    from cncc.frontend import syntax as sx

    try:
        match expr:
            case sx.Num():
                return expr.value
            case sx.Var():
                if expr.index is None:
                    return None
                idx = _eval(expr.index, values)
                return values.get(int(idx)) if idx is not None else None
            case sx.Neg():
                v = _eval(expr.operand, values)
                return -v if v is not None else None
            case sx.BinOp():
                a, b = _eval(expr.left, values), _eval(expr.right, values)
                fn = _BINOPS.get(expr.op)
                return fn(a, b) if a is not None and b is not None and fn is not None else None
            case sx.Call():
                args = [_eval(x, values) for x in expr.args]
                f = _FUNCS.get(expr.func)
                if f is None or len(args) != 1 or args[0] is None:
                    return None
                return float(f(args[0]))
    except (ArithmeticError, ValueError):
        return None
    return None
