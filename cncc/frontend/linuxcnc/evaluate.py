"""LinuxCNC expression semantics: numbered and named parameters, functions, operators.

Numbered parameters read 0 until set; ``#1``-``#30`` are local to a subroutine call.
Named parameters are local to the call unless the name starts with ``_``; reading
one that was never set is an error (``E0352``), ``EXISTS[#<name>]`` tests for it.
A few read-only ``#<_name>`` parameters report the interpreter's state.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

from cncc import diagnostics as dg
from cncc.frontend.syntax import BinOp, Call, Expr, Neg, Num, Var

_EPS = 0.0001  # LinuxCNC's TOLERANCE_EQUAL: EQ and NE compare reals within it


class EvalError(Exception):
    def __init__(self, code: str, message: str, start: int, end: int, detail: str = "") -> None:
        super().__init__(message)
        self.code, self.message, self.start, self.end, self.detail = code, message, start, end, detail


@dataclass(slots=True)
class Scope:
    """One call level: local numbered #1-#30 and local named parameters."""

    numbered: dict[int, float] = field(default_factory=dict)
    named: dict[str, float] = field(default_factory=dict)


@dataclass(slots=True)
class Parameters:
    globals_numbered: dict[int, float] = field(default_factory=dict)
    globals_named: dict[str, float] = field(default_factory=dict)
    scopes: list[Scope] = field(default_factory=lambda: [Scope()])
    system: Callable[[str], float | None] = lambda name: None  # #<_x> ... from the interpreter
    system_number: Callable[[int], float | None] = lambda n: None  # #5161 ... #5428 from the interpreter
    system_write: Callable[[int, float], bool] = lambda n, v: False  # ... and into its tables
    # a system parameter the program wrote: (its value, the interpreter's value then)
    system_written: dict[int, tuple[float, float]] = field(default_factory=dict)

    def read_number(self, n: int) -> float:
        if 1 <= n <= 30:
            return self.scopes[-1].numbered.get(n, 0.0)
        if n > 5160:
            got = self.system_number(n)
            if got is not None:
                user = self.system_written.get(n)
                return user[0] if user is not None and user[1] == got else got
        return self.globals_numbered.get(n, 0.0)

    def write_number(self, n: int, value: float) -> None:
        if 1 <= n <= 30:
            self.scopes[-1].numbered[n] = value
            return
        if n > 5160 and self.system_write(n, value):
            return
        got = self.system_number(n) if n > 5160 else None
        if got is not None:
            self.system_written[n] = (value, got)
        else:
            self.globals_numbered[n] = value

    def lookup(self, name: str) -> float | None:
        if name.startswith("_"):
            got = self.globals_named.get(name)
            return got if got is not None else self.system(name)
        return self.scopes[-1].named.get(name)

    def write_name(self, name: str, value: float) -> None:
        (self.globals_named if name.startswith("_") else self.scopes[-1].named)[name] = value


_FUNCS: dict[str, Callable[[float], float]] = {
    "ABS": abs, "FIX": lambda x: float(math.floor(x)), "FUP": lambda x: float(math.ceil(x)),
    "ROUND": lambda x: float(math.floor(x + 0.5)) if x >= 0 else -float(math.floor(-x + 0.5)),
    "EXP": math.exp, "SIN": lambda x: math.sin(math.radians(x)), "COS": lambda x: math.cos(math.radians(x)),
    "TAN": lambda x: math.tan(math.radians(x)),
}


def _power(a: float, b: float) -> float:
    if a < 0 and b != int(b):
        return math.nan
    try:
        return float(a ** b)
    except (OverflowError, ZeroDivisionError):
        return math.inf


_BINARY: dict[str, Callable[[float, float], float]] = {
    "+": lambda a, b: a + b, "-": lambda a, b: a - b, "*": lambda a, b: a * b, "/": lambda a, b: a / b,
    "MOD": lambda a, b: math.fmod(a, b) + (abs(b) if math.fmod(a, b) < 0 else 0.0), "**": _power,  # [7 MOD -3] = 1
    "EQ": lambda a, b: float(abs(a - b) < _EPS), "NE": lambda a, b: float(abs(a - b) >= _EPS),
    "GT": lambda a, b: float(a > b), "GE": lambda a, b: float(a >= b),
    "LT": lambda a, b: float(a < b), "LE": lambda a, b: float(a <= b),
    "AND": lambda a, b: float(a != 0 and b != 0), "OR": lambda a, b: float(a != 0 or b != 0),
    "XOR": lambda a, b: float((a != 0) != (b != 0)),
}


class Evaluator:
    def __init__(self, params: Parameters) -> None:
        self.p = params

    def number(self, e: Expr) -> float:
        match e:
            case Num():
                return e.value
            case Var():
                return self.read(e)
            case Neg():
                return -self.number(e.operand)
            case BinOp():
                return self._binary(e)
            case Call():
                return self._call(e)
        raise EvalError(dg.SYNTAX, "bad expression", 0, 0)  # pragma: no cover - closed union

    def read(self, v: Var) -> float:
        if v.index is None:
            got = self.p.lookup(v.name)
            if got is None:
                raise EvalError(dg.NAMED_UNDEFINED, f"#<{v.name}> is read before it was set", v.start, v.end, v.name)
            return got
        return self.p.read_number(self.var_number(v))

    def var_number(self, v: Var) -> int:
        assert v.index is not None
        n = self.number(v.index)
        k = round(n)
        if abs(n - k) > 1e-4 or k < 1 or k > 5601:
            raise EvalError(dg.MACRO_BAD_VARIABLE, f"parameter number #{n:g} out of range (1-5601)", v.start, v.end)
        return k

    def _binary(self, e: BinOp) -> float:
        a, b = self.number(e.left), self.number(e.right)
        op = e.op
        if op in ("/", "MOD") and b == 0:
            raise EvalError(dg.MACRO_DIV_ZERO, "division by zero", e.start, e.end)
        fn = _BINARY.get(op)
        if fn is None:
            raise EvalError(dg.SYNTAX, f"unknown operator {op}", e.start, e.end)  # pragma: no cover
        return fn(a, b)

    def _call(self, e: Call) -> float:
        name = e.func
        if name == "EXISTS":
            arg = e.args[0]
            if isinstance(arg, Var) and arg.index is None:
                return float(self.p.lookup(arg.name) is not None)
            return 1.0
        if name == "ATAN" and len(e.args) == 2:
            return math.degrees(math.atan2(self.number(e.args[0]), self.number(e.args[1])))
        x = self.number(e.args[0])
        if name == "SQRT":
            if x < 0:
                raise EvalError(dg.MACRO_DOMAIN, "square root of a negative number", e.start, e.end, "sqrt")
            return math.sqrt(x)
        if name in ("ASIN", "ACOS"):
            if abs(x) > 1:
                raise EvalError(dg.MACRO_DOMAIN, f"{name} of {x:g} (outside -1..1)", e.start, e.end)
            return math.degrees(math.asin(x) if name == "ASIN" else math.acos(x))
        if name == "LN":
            if x <= 0:
                raise EvalError(dg.MACRO_DOMAIN, f"LN of {x:g} (not positive)", e.start, e.end)
            return math.log(x)
        fn = _FUNCS.get(name)
        if fn is None:
            raise EvalError(dg.MACRO_NOT_SUPPORTED, f"{name} is not a LinuxCNC function", e.start, e.end)
        return fn(x)

    def condition(self, e: Expr) -> bool:
        return self.number(e) != 0.0
