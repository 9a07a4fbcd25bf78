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

import re

from cncc.diagnostics import DiagnosticSink
from cncc.dialects import Dialect
from cncc.frontend.linuxcnc.evaluate import EvalError, Parameters
from cncc.frontend.linuxcnc.evaluate import Evaluator as LinuxcncEvaluator
from cncc.frontend.macro.evaluate import Evaluator as MacroEvaluator
from cncc.frontend.macro.executor import layout_for
from cncc.frontend.macro.values import MacroError, Value, Variables
from cncc.frontend.syntax import Assign, BinOp, Call, Neg, Num, Var
from cncc.lsp.positions import LineIndex
from cncc.lsp.trace import Seen, VariableTrace
from cncc.source import SourceFile

_ASSIGN_RE = re.compile(r"#\s*\d+\s*=")
_FLOW_RE = re.compile(r"\b(GOTO|WHILE|IF)\b|M\s*98|G\s*6[56]\b", re.IGNORECASE)
MAX_LINES = 50_000


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

    upto = index.line_of(offset)
    values: dict[int, float] = {}
    last_line = -1
    flow = False
    parser = Parser(dialect, DiagnosticSink(max_count=10))
    evaluate = _Eval(dialect, values)
    for line in range(max(0, upto - MAX_LINES), upto):
        body = index.line_text(line)
        if _FLOW_RE.search(body):
            flow = True
        if not _ASSIGN_RE.search(body):
            continue
        for block in parser.blocks(SourceFile(0, "", body)):
            for st in block.statements:
                if isinstance(st, Assign) and st.target.index is not None and not st.target.name:
                    target = evaluate(st.target.index)
                    if target is None:
                        continue
                    value = evaluate(st.expr)
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


class _Unknown(Exception):
    """A variable with no assignment above the point: the value is not known statically."""


class _KnownMacroVariables(Variables):
    """Fanuc/SZGH variables: only those assigned above the point are known."""

    __slots__ = ("known",)

    def __init__(self, dialect: Dialect, known: dict[int, float]) -> None:
        super().__init__(layout_for(dialect))
        self.known = known

    def read(self, n: int, start: int = -1, end: int = -1) -> Value:
        if n not in self.known:
            raise _Unknown
        return self.known[n]


class _KnownParameters(Parameters):
    """LinuxCNC parameters: only those assigned above the point are known."""

    __slots__ = ("known",)

    def __init__(self, known: dict[int, float]) -> None:
        super().__init__()
        self.known = known

    def read_number(self, n: int) -> float:
        if n not in self.known:
            raise _Unknown
        return self.known[n]

    def lookup(self, name: str) -> float | None:
        raise _Unknown


class _Eval:
    """``expr`` through the compiler's own evaluator (:class:`cncc.frontend.evaluate.Evaluator`
    with the flavour's tables, bound to a variable store by :mod:`cncc.frontend.macro.evaluate`
    or :mod:`cncc.frontend.linuxcnc.evaluate` as in the compiler), with the variables assigned
    above; None when an operand is unknown or the compiler would report an error (domain,
    division by zero ...)."""

    def __init__(self, dialect: Dialect, values: dict[int, float]) -> None:
        self._linuxcnc = LinuxcncEvaluator(_KnownParameters(values)) if dialect.macro_flavour == "linuxcnc" else None
        self._macro = MacroEvaluator(_KnownMacroVariables(dialect, values))

    def __call__(self, expr: object) -> float | None:
        if not isinstance(expr, Num | Var | Neg | BinOp | Call):
            return None
        try:
            if self._linuxcnc is not None:
                return self._linuxcnc.number(expr)
            return self._macro.value(expr)
        except (_Unknown, MacroError, EvalError, ArithmeticError, ValueError):
            return None
