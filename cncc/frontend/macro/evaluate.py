"""Macro expressions: syntax-tree expressions -> values, with vacant-variable rules.

Consumes :mod:`cncc.frontend.syntax` expression nodes (``Num Var Neg BinOp Call``)
and a :class:`~cncc.frontend.macro.values.Variables` store; produces a ``float`` or
``None`` (vacant).  Fanuc macro B rules, which the SZGH language follows:

* a vacant variable read on its own stays vacant (``#2 = #1`` keeps ``#2`` vacant);
* in arithmetic and functions a vacant value counts as 0;
* ``EQ``/``NE`` tell vacant from 0 (``#1 EQ #0`` is true only for a vacant ``#1``);
  the ordering comparisons ``GT GE LT LE`` read vacant as 0;
* angles are in degrees; ``ATAN[y]/[x]`` (Fanuc) and ``ATAN[y,x]`` give 0-360;
  ``ROUND`` rounds half away from zero, ``FIX`` toward zero, ``FUP`` away from zero;
* ``AND OR XOR`` are bitwise on integers (and logical on comparison results, which
  are 1 or 0).
"""

from __future__ import annotations

import math
from collections.abc import Callable

from cncc.frontend.macro.values import MacroError, Value, Variables
from cncc.frontend.syntax import BinOp, Call, Expr, Neg, Num, Var

_EPS = 1e-9


def _deg(f: Callable[[float], float]) -> Callable[[float], float]:
    return lambda x: f(math.radians(x))


def _round_half_away(x: float) -> float:
    return float(math.floor(abs(x) + 0.5)) * (1.0 if x >= 0 else -1.0)


def _fup(x: float) -> float:
    return float(math.ceil(x) if x >= 0 else math.floor(x))


def _check(ok: bool, func: str, x: float) -> None:
    if not ok:
        raise MacroError("E0305", f"{func}[{x:g}] is outside the function's domain")


def _asin(x: float) -> float:
    _check(-1.0 - _EPS <= x <= 1.0 + _EPS, "ASIN", x)
    return math.degrees(math.asin(max(-1.0, min(1.0, x))))


def _acos(x: float) -> float:
    _check(-1.0 - _EPS <= x <= 1.0 + _EPS, "ACOS", x)
    return math.degrees(math.acos(max(-1.0, min(1.0, x))))


def _sqrt(x: float) -> float:
    _check(x >= 0.0, "SQRT", x)
    return math.sqrt(x)


def _ln(x: float) -> float:
    _check(x > 0.0, "LN", x)
    return math.log(x)


def _exp(x: float) -> float:
    _check(x < 700.0, "EXP", x)
    return math.exp(x)


def _tan(x: float) -> float:
    _check(abs(math.cos(math.radians(x))) > 1e-12, "TAN", x)
    return math.tan(math.radians(x))


def _bin(x: float) -> float:  # BCD -> binary
    digits = str(int(x))
    return float(int(digits, 16)) if digits.isdigit() else 0.0


def _bcd(x: float) -> float:  # binary -> BCD
    return float(int(str(int(x)), 16))


UNARY: dict[str, Callable[[float], float]] = {
    "SIN": _deg(math.sin), "COS": _deg(math.cos), "TAN": _tan,
    "ASIN": _asin, "ACOS": _acos, "SQRT": _sqrt, "ABS": abs, "ROUND": _round_half_away,
    "FIX": lambda x: float(math.trunc(x)), "FUP": _fup, "LN": _ln, "EXP": _exp,
    "BIN": _bin, "BCD": _bcd,
}


def _atan(args: list[float]) -> float:
    if len(args) == 2:
        return math.degrees(math.atan2(args[0], args[1])) % 360.0
    return math.degrees(math.atan(args[0]))


def _pow(args: list[float]) -> float:
    if len(args) != 2:
        raise MacroError("E0305", "POW takes two arguments")
    try:
        return float(math.pow(args[0], args[1]))
    except (ValueError, OverflowError):
        raise MacroError("E0305", f"POW[{args[0]:g},{args[1]:g}] is outside the function's domain") from None


def _mod(a: float, b: float) -> float:
    if b == 0.0:
        raise MacroError("E0304", "MOD by zero")
    return math.fmod(a, b)


def _int_op(op: str, a: float, b: float) -> float:
    ia, ib = round(a), round(b)
    if op == "AND":
        return float(ia & ib)
    if op == "OR":
        return float(ia | ib)
    return float(ia ^ ib)


class Evaluator:
    """Evaluates expressions against one variable store."""

    def __init__(self, variables: Variables) -> None:
        self.vars = variables
        # ROUND inside an NC address rounds to the address's least input increment (Fanuc macro B:
        # ``X[ROUND[#1]]`` with #1 = 12.4567 is X12.457 in mm); elsewhere it rounds to an integer.
        self.round_step: float | None = None

    def value(self, e: Expr) -> Value:
        """The value of ``e``; vacant only for a lone vacant variable."""
        if isinstance(e, Num):
            return e.value
        if isinstance(e, Var):
            return self.vars.read(self.var_number(e), e.start, e.end)
        try:
            return self._number(e)
        except MacroError as exc:
            if exc.start < 0:
                exc.start, exc.end = e.start, e.end
            raise

    def number(self, e: Expr) -> float:
        """The value of ``e`` with vacant read as 0."""
        v = self.value(e)
        return 0.0 if v is None else v

    def condition(self, e: Expr) -> bool:
        return abs(self.number(e)) > _EPS if not isinstance(e, BinOp) or e.op not in _CMP else self._compare(e)

    def var_number(self, v: Var) -> int:
        if v.index is None:
            raise MacroError("E0302", f"named variable #<{v.name}> is not part of this macro language",
                             v.start, v.end)
        return self.vars.number(self.number(v.index), v.start, v.end)

    # ---- internals
    def _number(self, e: Expr) -> float:
        match e:
            case Num():
                return e.value
            case Var():
                v = self.vars.read(self.var_number(e), e.start, e.end)
                return 0.0 if v is None else v
            case Neg():
                return -self._number(e.operand)
            case BinOp():
                if e.op in _CMP:
                    return 1.0 if self._compare(e) else 0.0
                return self._binary(e)
            case Call():
                return self._call(e)
        raise MacroError("E0325", "unknown expression")  # pragma: no cover - closed union

    def _binary(self, e: BinOp) -> float:
        if e.op == "/" and isinstance(e.left, Call) and e.left.func == "ATAN" and len(e.left.args) == 1:
            # Fanuc's two-argument arc tangent is written ATAN[y]/[x]
            return _atan([self._number(e.left.args[0]), self._number(e.right)])
        a = self._number(e.left)
        b = self._number(e.right)
        op = e.op
        if op == "+":
            r = a + b
        elif op == "-":
            r = a - b
        elif op == "*":
            r = a * b
        elif op == "/":
            if b == 0.0:
                raise MacroError("E0304", "division by zero", e.start, e.end)
            r = a / b
        elif op == "MOD":
            r = _mod(a, b)
        elif op in ("AND", "OR", "XOR"):
            r = _int_op(op, a, b)
        else:
            raise MacroError("E0325", f"operator {op} is not supported", e.start, e.end)
        if not math.isfinite(r):
            raise MacroError("E0322", "the result is not a finite number", e.start, e.end)
        return r

    def _compare(self, e: BinOp) -> bool:
        op = e.op
        if op in ("EQ", "NE"):
            a, b = self.value(e.left), self.value(e.right)
            if a is None or b is None:
                same = a is None and b is None
            else:
                same = abs(a - b) < _EPS * max(1.0, abs(a), abs(b))
            return same if op == "EQ" else not same
        x, y = self._number(e.left), self._number(e.right)
        if op == "GT":
            return x > y
        if op == "GE":
            return x >= y
        if op == "LT":
            return x < y
        return x <= y

    def _call(self, e: Call) -> float:
        args = [self._number(a) for a in e.args]
        if e.func == "ATAN":
            return _atan(args)
        if e.func == "POW":
            return _pow(args)
        if e.func == "MOD" and len(args) == 2:
            return _mod(args[0], args[1])
        if e.func == "ROUND" and len(args) == 1 and self.round_step:
            step = self.round_step
            return _round_half_away(args[0] / step) * step
        fn = UNARY.get(e.func)
        if fn is None or len(args) != 1:
            raise MacroError("E0325", f"function {e.func} with {len(args)} argument(s) is not supported",
                             e.start, e.end)
        try:
            r = fn(args[0])
        except MacroError as exc:
            exc.start, exc.end = e.start, e.end
            raise
        except (ValueError, OverflowError):
            raise MacroError("E0305", f"{e.func}[{args[0]:g}] is outside the function's domain",
                             e.start, e.end) from None
        return r


_CMP = frozenset({"EQ", "NE", "GT", "GE", "LT", "LE"})
