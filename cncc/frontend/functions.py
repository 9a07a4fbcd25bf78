"""The macro functions and word operators of each flavour, as tables.

One :class:`Flavour` per macro language: Fanuc macro B (SYNTEC, Fanuc, Haas), SZGH
and LinuxCNC.  :mod:`cncc.frontend.evaluate` is the one evaluator; it reads every
flavour-dependent rule from here.  What the manuals say, and cncc follows:

* Fanuc macro B: angles in degrees; ``ROUND`` half away from zero, ``FIX`` toward
  zero, ``FUP`` away from zero; ``ATAN[y]/[x]`` and ``ATAN[y,x]`` give 0-360;
  ``MOD`` keeps the dividend's sign; ``AND OR XOR`` are bitwise on integers;
  ``BIN``/``BCD`` convert between binary and BCD; ``EQ`` tells vacant from 0.
* SZGH-CNC990MDb (spec section 3.8): the functions ``SIN ASIN COS ACOS TAN ATAN SQRT
  ABS ROUND FIX FUP LN EXP``, arithmetic ``+ - * /`` and bitwise ``OR XOR AND``;
  no ``MOD``, ``POW``, ``BIN`` or ``BCD``.  Otherwise Fanuc's rules.
* LinuxCNC (rs274ngc): ``FIX`` rounds down, ``FUP`` up, ``ROUND`` half away from
  zero; ``ATAN[y]/[x]`` is -180..180; ``MOD`` is never negative (``[-7 MOD 3]`` = 2);
  ``AND OR XOR`` are logical; ``**`` is the power; ``EQ`` compares within 0.0001;
  parameters are never vacant; ``EXISTS[#<name>]``.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass

from cncc import diagnostics as dg

Function = Callable[[list[float]], float]
Operator = Callable[[float, float], float]
COMPARISONS = frozenset({"EQ", "NE", "GT", "GE", "LT", "LE"})


class DomainError(Exception):
    """A function or operator refused its arguments (the evaluator adds the span)."""

    def __init__(self, code: str, message: str, detail: str = "") -> None:
        super().__init__(message)
        self.code, self.message, self.detail = code, message, detail


@dataclass(frozen=True, slots=True)
class Flavour:
    name: str
    functions: Mapping[str, Function]  # NAME[args]
    operators: Mapping[str, Operator]  # + - * / and the word operators, not the comparisons
    same: Callable[[float, float], bool]  # what EQ means for two numbers
    vacant_compare: bool  # EQ/NE tell a vacant variable from 0 (Fanuc macro B)
    atan_slash: bool  # ATAN[y]/[x] is parsed as ATAN[y] divided by [x] and means atan2
    finite_results: bool  # a non-finite operator result is an error (E0322)
    exists: bool  # EXISTS[#<name>]
    condition_eps: float  # a condition is true when |value| > this (0: when the value is not 0)
    unknown: str  # the message for a function the flavour has not; {name} and {n} (argument count)


def _degrees_in(f: Callable[[float], float]) -> Callable[[float], float]:
    return lambda x: f(math.radians(x))


def unary(name: str, f: Callable[[float], float]) -> Function:
    def call(args: list[float]) -> float:
        if len(args) != 1:
            raise DomainError(dg.MACRO_NOT_SUPPORTED, f"function {name} with {len(args)} argument(s) is not supported")
        return f(args[0])

    return call


def _domain(ok: bool, name: str, x: float) -> None:
    if not ok:
        raise DomainError(dg.MACRO_DOMAIN, f"{name}[{x:g}] is outside the function's domain")


# ---- Fanuc macro B -----------------------------------------------------------------------------
_EPS = 1e-9


def round_half_away(x: float) -> float:
    return float(math.floor(abs(x) + 0.5)) * (1.0 if x >= 0 else -1.0)


def _fup_away(x: float) -> float:
    return float(math.ceil(x) if x >= 0 else math.floor(x))


def _asin(x: float) -> float:
    _domain(-1.0 - _EPS <= x <= 1.0 + _EPS, "ASIN", x)
    return math.degrees(math.asin(max(-1.0, min(1.0, x))))


def _acos(x: float) -> float:
    _domain(-1.0 - _EPS <= x <= 1.0 + _EPS, "ACOS", x)
    return math.degrees(math.acos(max(-1.0, min(1.0, x))))


def _sqrt(x: float) -> float:
    _domain(x >= 0.0, "SQRT", x)
    return math.sqrt(x)


def _ln(x: float) -> float:
    _domain(x > 0.0, "LN", x)
    return math.log(x)


def _exp(x: float) -> float:
    _domain(x < 700.0, "EXP", x)
    return math.exp(x)


def _tan(x: float) -> float:
    _domain(abs(math.cos(math.radians(x))) > 1e-12, "TAN", x)
    return math.tan(math.radians(x))


def _bin(x: float) -> float:
    """BCD -> binary: the nibbles of ``x`` are decimal digits (BIN[24] = 18: 24 is 0001 1000)."""
    _domain(x >= 0, "BIN", x)
    nibbles = format(int(x), "x")
    _domain(nibbles.isdigit(), "BIN", x)  # a nibble above 9 is no BCD digit
    return float(int(nibbles))


def _bcd(x: float) -> float:
    """Binary -> BCD: each decimal digit of ``x`` in a nibble (BCD[18] = 24: 0001 1000)."""
    _domain(x >= 0, "BCD", x)
    return float(int(str(int(x)), 16))


def atan_fanuc(args: list[float]) -> float:
    if len(args) == 2:
        return math.degrees(math.atan2(args[0], args[1])) % 360.0
    if len(args) != 1:
        raise DomainError(dg.MACRO_NOT_SUPPORTED, f"function ATAN with {len(args)} argument(s) is not supported")
    return math.degrees(math.atan(args[0]))


def _pow(args: list[float]) -> float:
    if len(args) != 2:
        raise DomainError(dg.MACRO_DOMAIN, "POW takes two arguments")
    try:
        return float(math.pow(args[0], args[1]))
    except (ValueError, OverflowError):
        raise DomainError(dg.MACRO_DOMAIN, f"POW[{args[0]:g},{args[1]:g}] is outside the function's domain") from None


def _mod_fanuc(a: float, b: float) -> float:
    if b == 0.0:
        raise DomainError(dg.MACRO_DIV_ZERO, "MOD by zero")
    return math.fmod(a, b)


def _mod_function(args: list[float]) -> float:
    if len(args) != 2:
        raise DomainError(dg.MACRO_NOT_SUPPORTED, f"function MOD with {len(args)} argument(s) is not supported")
    return _mod_fanuc(args[0], args[1])


def _divide(a: float, b: float) -> float:
    if b == 0.0:
        raise DomainError(dg.MACRO_DIV_ZERO, "division by zero")
    return a / b


def _bitwise(f: Callable[[int, int], int]) -> Operator:
    return lambda a, b: float(f(round(a), round(b)))


_ARITHMETIC: dict[str, Operator] = {"+": lambda a, b: a + b, "-": lambda a, b: a - b, "*": lambda a, b: a * b,
                                    "/": _divide}
_FANUC_FUNCTIONS: dict[str, Function] = {
    "SIN": unary("SIN", _degrees_in(math.sin)), "COS": unary("COS", _degrees_in(math.cos)), "TAN": unary("TAN", _tan),
    "ASIN": unary("ASIN", _asin), "ACOS": unary("ACOS", _acos), "ATAN": atan_fanuc, "SQRT": unary("SQRT", _sqrt),
    "ABS": unary("ABS", abs), "ROUND": unary("ROUND", round_half_away),
    "FIX": unary("FIX", lambda x: float(math.trunc(x))), "FUP": unary("FUP", _fup_away),
    "LN": unary("LN", _ln), "EXP": unary("EXP", _exp), "BIN": unary("BIN", _bin), "BCD": unary("BCD", _bcd),
    "POW": _pow, "MOD": _mod_function,
}
_FANUC_OPERATORS: dict[str, Operator] = {
    **_ARITHMETIC, "MOD": _mod_fanuc,
    "AND": _bitwise(lambda a, b: a & b), "OR": _bitwise(lambda a, b: a | b), "XOR": _bitwise(lambda a, b: a ^ b),
}


def _same_fanuc(a: float, b: float) -> bool:
    return abs(a - b) < _EPS * max(1.0, abs(a), abs(b))


FANUC = Flavour("fanuc", _FANUC_FUNCTIONS, _FANUC_OPERATORS, _same_fanuc, vacant_compare=True, atan_slash=True,
                finite_results=True, exists=False, condition_eps=_EPS,
                unknown="function {name} with {n} argument(s) is not supported")

SZGH_FUNCTIONS = ("SIN", "ASIN", "COS", "ACOS", "TAN", "ATAN", "SQRT", "ABS", "ROUND", "FIX", "FUP", "LN", "EXP")
SZGH = Flavour("szgh", {k: _FANUC_FUNCTIONS[k] for k in SZGH_FUNCTIONS},
               {k: v for k, v in _FANUC_OPERATORS.items() if k != "MOD"}, _same_fanuc, vacant_compare=True,
               atan_slash=True, finite_results=True, exists=False, condition_eps=_EPS,
               unknown="{name} is not a function of the SZGH macro language (SIN ASIN COS ACOS TAN ATAN SQRT ABS "
                       "ROUND FIX FUP LN EXP)")


# ---- LinuxCNC ----------------------------------------------------------------------------------
TOLERANCE_EQUAL = 0.0001  # rs274ngc's TOLERANCE_EQUAL: EQ and NE compare reals within it


def _check(ok: bool, message: str, detail: str = "") -> None:
    if not ok:
        raise DomainError(dg.MACRO_DOMAIN, message, detail)


def _l_sqrt(x: float) -> float:
    _check(x >= 0, "square root of a negative number", "sqrt")
    return math.sqrt(x)


def _l_arc(name: str, f: Callable[[float], float]) -> Callable[[float], float]:
    def call(x: float) -> float:
        _check(abs(x) <= 1, f"{name} of {x:g} (outside -1..1)")
        return math.degrees(f(x))

    return call


def _l_ln(x: float) -> float:
    _check(x > 0, f"LN of {x:g} (not positive)")
    return math.log(x)


def _l_atan(args: list[float]) -> float:
    if len(args) != 2:
        raise DomainError(dg.MACRO_NOT_SUPPORTED, "ATAN is written ATAN[y]/[x] in LinuxCNC")
    return math.degrees(math.atan2(args[0], args[1]))


def _l_mod(a: float, b: float) -> float:
    if b == 0:
        raise DomainError(dg.MACRO_DIV_ZERO, "division by zero")
    r = math.fmod(a, b)
    return r + (abs(b) if r < 0 else 0.0)  # [7 MOD -3] = 1, [-7 MOD 3] = 2


def _l_power(a: float, b: float) -> float:
    if a < 0 and b != int(b):
        return math.nan
    try:
        return float(a ** b)
    except (OverflowError, ZeroDivisionError):
        return math.inf


_LINUXCNC_FUNCTIONS: dict[str, Function] = {
    "ATAN": _l_atan, "SQRT": unary("SQRT", _l_sqrt), "ASIN": unary("ASIN", _l_arc("ASIN", math.asin)),
    "ACOS": unary("ACOS", _l_arc("ACOS", math.acos)), "LN": unary("LN", _l_ln), "ABS": unary("ABS", abs),
    "FIX": unary("FIX", lambda x: float(math.floor(x))), "FUP": unary("FUP", lambda x: float(math.ceil(x))),
    "ROUND": unary("ROUND", round_half_away), "EXP": unary("EXP", math.exp),
    "SIN": unary("SIN", _degrees_in(math.sin)), "COS": unary("COS", _degrees_in(math.cos)),
    "TAN": unary("TAN", _degrees_in(math.tan)),
}
_LINUXCNC_OPERATORS: dict[str, Operator] = {
    **_ARITHMETIC, "MOD": _l_mod, "**": _l_power,
    "AND": lambda a, b: float(a != 0 and b != 0), "OR": lambda a, b: float(a != 0 or b != 0),
    "XOR": lambda a, b: float((a != 0) != (b != 0)),
}
LINUXCNC = Flavour("linuxcnc", _LINUXCNC_FUNCTIONS, _LINUXCNC_OPERATORS, lambda a, b: abs(a - b) < TOLERANCE_EQUAL,
                   vacant_compare=False, atan_slash=False, finite_results=False, exists=True, condition_eps=0.0,
                   unknown="{name} is not a LinuxCNC function")

FLAVOURS: dict[str, Flavour] = {f.name: f for f in (FANUC, SZGH, LINUXCNC)}
"""Macro flavour (a dialect's ``macro_flavour``) -> its tables."""
