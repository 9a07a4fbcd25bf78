"""LinuxCNC expression semantics: numbered and named parameters, functions, operators.

Numbered parameters read 0 until set; ``#1``-``#30`` are local to a subroutine call.
Named parameters are local to the call unless the name starts with ``_``; reading
one that was never set is an error (``E0352``), ``EXISTS[#<name>]`` tests for it.
A few read-only ``#<_name>`` parameters report the interpreter's state.  The functions
and operators are LinuxCNC's table (:data:`cncc.frontend.functions.LINUXCNC`), evaluated
by :class:`cncc.frontend.evaluate.Evaluator`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from cncc import diagnostics as dg
from cncc.frontend import evaluate
from cncc.frontend.evaluate import ExprError
from cncc.frontend.functions import LINUXCNC
from cncc.frontend.syntax import Var


class EvalError(ExprError):
    """A LinuxCNC expression error (code, message, span, detail)."""


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
    read_refused: Callable[[int], str | None] = lambda n: None  # rs274's text when an expression may not read #n
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


class Evaluator(evaluate.Evaluator):
    """:class:`cncc.frontend.evaluate.Evaluator` with LinuxCNC's tables over one parameter store."""

    def __init__(self, params: Parameters) -> None:
        super().__init__(LINUXCNC, self._read, EvalError, self._exists)
        self.p = params

    def _exists(self, v: Var) -> bool:
        return v.index is not None or self.p.lookup(v.name) is not None

    def _read(self, v: Var) -> float:
        if v.index is None:
            got = self.p.lookup(v.name)
            if got is None:
                raise EvalError(dg.NAMED_UNDEFINED, f"#<{v.name}> is read before it was set", v.start, v.end, v.name)
            return got
        n = self.var_number(v)
        refused = self.p.read_refused(n)
        if refused is not None:
            raise EvalError(dg.COMP_REFUSES, refused, v.start, v.end)
        return self.p.read_number(n)

    def var_number(self, v: Var) -> int:
        assert v.index is not None
        n = self.number(v.index)
        k = round(n)
        if abs(n - k) > 1e-4 or k < 1 or k > 5601:
            raise EvalError(dg.MACRO_BAD_VARIABLE, f"parameter number #{n:g} out of range (1-5601)", v.start, v.end)
        return k
