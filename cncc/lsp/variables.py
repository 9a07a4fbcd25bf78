"""Values of macro variables for hover.

The first choice is what the analysis run saw at that very reference
(:mod:`cncc.lsp.trace`: the macro executor's own evaluation, through loops, jumps
and calls).  When the document has changed since, or the program did not run on
the macro executor, the fallback reads the assignments (``#1 = 5``,
``#2 = #1 * 2``) above the point in document order and evaluates them when every
operand is known; jumps, loops and calls are not followed then, and the hover says
so.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable

from cncc.diagnostics import DiagnosticSink
from cncc.dialects import Dialect
from cncc.lsp.positions import LineIndex
from cncc.lsp.trace import Seen, VariableTrace
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


def hover_variable(text: str, index: LineIndex, dialect: Dialect, number: int, site: int,
                   trace: VariableTrace | None) -> str:
    """Markdown for the reference ``#number`` whose ``#`` is at offset ``site``."""
    if trace is not None and trace.ran:
        seen = trace.at(site)
        if seen is not None and seen.passes:
            return traced_text(number, seen)
        return (f"**#{number}** — this reference was not reached when cncc ran the program "
                "(a branch not taken, code after the end, or the run stopped before it).")
    return variable_value(text, index, dialect, number, site)


def traced_text(number: int | str, seen: Seen) -> str:
    """What a reference saw during the run, in words (``number``: 5 for ``#5``, or a
    variable's text such as ``#<depth>``)."""
    head = f"**#{number}**" if isinstance(number, int) else f"**{number}**"
    if seen.values == 0:
        return f"{head} is vacant here" + (f" (on all {seen.passes} passes)" if seen.passes > 1 else "") + "."
    last = "vacant" if seen.last is None else f"{seen.last:g}"
    if seen.passes == 1:
        return f"{head} = {last} when cncc ran this block."
    if seen.lo == seen.hi and seen.vacant == 0:
        return f"{head} = {last} (the same on all {seen.passes} passes through this block)."
    vacant = f", vacant on {seen.vacant}" if seen.vacant else ""
    return (f"{head} = {last} on the last of {seen.passes} passes through this block\n\n"
            f"values from {seen.lo:g} to {seen.hi:g}{vacant}")


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
