"""The one macro expression evaluator: syntax-tree expressions -> values, for every flavour.

Consumes :mod:`cncc.frontend.syntax` expression nodes (``Num Var Neg BinOp Call``), a
:class:`~cncc.frontend.functions.Flavour` (the function and operator tables and the
flavour's rules) and a ``read`` callback for variables; produces a ``float``, or
``None`` (vacant) for a lone vacant variable.  The Fanuc/SZGH macro executor
(:mod:`cncc.frontend.macro.evaluate`), the LinuxCNC executor
(:mod:`cncc.frontend.linuxcnc.evaluate`) and the editor's hover
(:mod:`cncc.lsp.variables`, through those two) all evaluate here.

Rules common to the flavours: a vacant value counts as 0 in arithmetic and functions;
a condition is true when its value is not 0.  Errors are raised as the caller's
:class:`ExprError` subclass with the span of the node that failed.
"""

from __future__ import annotations

import math
from collections.abc import Callable

from cncc import diagnostics as dg
from cncc.frontend.functions import COMPARISONS, DomainError, Flavour, round_half_away
from cncc.frontend.syntax import BinOp, Call, Expr, Neg, Num, Var

Value = float | None


class ExprError(Exception):
    """An expression that cannot be evaluated: diagnostic code, message, span, detail."""

    def __init__(self, code: str, message: str, start: int = -1, end: int = -1, detail: str = "") -> None:
        super().__init__(message)
        self.code, self.message, self.start, self.end, self.detail = code, message, start, end, detail


class Evaluator:
    """Evaluates expressions of one flavour; ``read(var)`` gives a variable's value (None: vacant),
    ``exists(var)`` whether a named parameter is set (``EXISTS[#<name>]``)."""

    def __init__(self, flavour: Flavour, read: Callable[[Var], Value], error: type[ExprError] = ExprError,
                 exists: Callable[[Var], bool] | None = None) -> None:
        self.flavour = flavour
        self.read = read
        self.error = error
        self.exists = exists
        # ROUND inside an NC address rounds to the address's least input increment (Fanuc macro B:
        # ``X[ROUND[#1]]`` with #1 = 12.4567 is X12.457 in mm); elsewhere it rounds to an integer.
        self.round_step: float | None = None

    def value(self, e: Expr) -> Value:
        """The value of ``e``; vacant only for a lone vacant variable."""
        if isinstance(e, Num):
            return e.value
        if isinstance(e, Var):
            return self.read(e)
        try:
            return self._number(e)
        except ExprError as exc:
            if exc.start < 0:
                exc.start, exc.end = e.start, e.end
            raise

    def number(self, e: Expr) -> float:
        """The value of ``e`` with vacant read as 0."""
        v = self.value(e)
        return 0.0 if v is None else v

    def condition(self, e: Expr) -> bool:
        if isinstance(e, BinOp) and e.op in COMPARISONS:
            return self._compare(e)
        x = self.number(e)
        eps = self.flavour.condition_eps
        return abs(x) > eps if eps else x != 0.0

    # ---- internals
    def _fail(self, code: str, message: str, e: Expr, detail: str = "") -> ExprError:
        return self.error(code, message, e.start, e.end, detail)

    def _number(self, e: Expr) -> float:
        match e:
            case Num():
                return e.value
            case Var():
                v = self.read(e)
                return 0.0 if v is None else v
            case Neg():
                return -self._number(e.operand)
            case BinOp():
                if e.op in COMPARISONS:
                    return 1.0 if self._compare(e) else 0.0
                return self._binary(e)
            case Call():
                return self._call(e)
        raise self._fail(dg.MACRO_NOT_SUPPORTED, "unknown expression", e)  # pragma: no cover - closed union

    def _binary(self, e: BinOp) -> float:
        fl = self.flavour
        if fl.atan_slash and e.op == "/" and isinstance(e.left, Call) and e.left.func == "ATAN" \
                and len(e.left.args) == 1:  # Fanuc's two-argument arc tangent is written ATAN[y]/[x]
            return self._apply(e, fl.functions["ATAN"], [self._number(e.left.args[0]), self._number(e.right)])
        a = self._number(e.left)
        b = self._number(e.right)
        op = fl.operators.get(e.op)
        if op is None:
            raise self._fail(dg.MACRO_NOT_SUPPORTED, f"operator {e.op} is not supported", e)
        try:
            r = op(a, b)
        except DomainError as exc:
            raise self._fail(exc.code, exc.message, e, exc.detail) from None
        if fl.finite_results and not math.isfinite(r):
            raise self._fail(dg.MACRO_BAD_VALUE, "the result is not a finite number", e)
        return r

    def _compare(self, e: BinOp) -> bool:
        op = e.op
        if op in ("EQ", "NE"):
            if self.flavour.vacant_compare:
                a, b = self.value(e.left), self.value(e.right)
                same = a is None and b is None if a is None or b is None else self.flavour.same(a, b)
            else:
                same = self.flavour.same(self._number(e.left), self._number(e.right))
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
        fl = self.flavour
        if e.func == "EXISTS" and fl.exists:
            arg = e.args[0]
            return float(self.exists(arg)) if isinstance(arg, Var) and self.exists is not None else 1.0
        args = [self._number(a) for a in e.args]
        if e.func == "ROUND" and len(args) == 1 and self.round_step:
            step = self.round_step
            return round_half_away(args[0] / step) * step
        fn = fl.functions.get(e.func)
        if fn is None:
            raise self._fail(dg.MACRO_NOT_SUPPORTED, fl.unknown.format(name=e.func, n=len(args)), e)
        return self._apply(e, fn, args)

    def _apply(self, e: Expr, fn: Callable[[list[float]], float], args: list[float]) -> float:
        try:
            return fn(args)
        except DomainError as exc:
            raise self._fail(exc.code, exc.message, e, exc.detail) from None
        except (ValueError, OverflowError):
            name = e.func if isinstance(e, Call) else "ATAN"
            shown = ",".join(f"{a:g}" for a in args)
            raise self._fail(dg.MACRO_DOMAIN, f"{name}[{shown}] is outside the function's domain", e) from None
