"""Macro variables: storage, vacant ("null") values and the two flavours' tables.

A value is a ``float`` or ``None`` (vacant).  Fanuc macro B semantics:

* ``#0`` is always vacant and cannot be written (Fanuc flavour only; in SZGH ``#0``
  is the local variable of argument A);
* locals (Fanuc ``#1``-``#33``, SZGH ``#0``-``#20``) belong to a macro call level
  and start vacant; commons/globals are shared by every level;
* system variables (``#1000`` and up) are read and written through a
  :class:`SystemVariables` object supplied by the executor.

:class:`Variables` consumes variable numbers and values; it produces values or
raises :class:`MacroError` (caught by the executor and turned into a diagnostic).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Protocol

from cncc.frontend.evaluate import ExprError

Value = float | None

FANUC_ARGUMENTS_I: dict[str, int] = {
    "A": 1, "B": 2, "C": 3, "I": 4, "J": 5, "K": 6, "D": 7, "E": 8, "F": 9, "H": 11, "M": 13, "Q": 17,
    "R": 18, "S": 19, "T": 20, "U": 21, "V": 22, "W": 23, "X": 24, "Y": 25, "Z": 26,
}
"""Fanuc argument specification I: address -> local variable."""


class MacroError(ExprError):
    """A run-time error of a macro program (diagnostic code and message).

    Raised inside the evaluator and caught by the executor at the statement that
    caused it; never leaves the front end.
    """


class SystemVariables(Protocol):
    def read(self, number: int) -> Value: ...

    def write(self, number: int, value: Value) -> bool:
        """Store a system variable; False when ``number`` is not writable."""
        ...


@dataclass(frozen=True, slots=True)
class VariableLayout:
    """Which numbers are locals, commons and system variables for one flavour."""

    flavour: str  # "fanuc" or "szgh"
    local_first: int
    local_last: int
    common_ranges: tuple[tuple[int, int], ...]
    system_first: int
    arguments: dict[str, int]
    null_zero: bool  # True: #0 is the read-only vacant variable
    reserved: tuple[tuple[int, int], ...] = ()

    @staticmethod
    def fanuc() -> VariableLayout:
        return VariableLayout("fanuc", 1, 33, ((100, 199), (500, 999)), 1000, dict(FANUC_ARGUMENTS_I), True)

    @staticmethod
    def szgh(arguments: dict[str, int] | None = None,
             reserved: Iterable[tuple[int, int]] = ()) -> VariableLayout:
        args = arguments or {c: i for i, c in enumerate("ABCDEFHIJKMQRSTUVWXYZ")}
        return VariableLayout("szgh", 0, 20, ((21, 999),), 1000, dict(args), False, tuple(reserved))

    def kind(self, number: int) -> str:
        """``"null"``, ``"local"``, ``"common"``, ``"system"`` or ``"invalid"``."""
        if number == 0 and self.null_zero:
            return "null"
        if self.local_first <= number <= self.local_last:
            return "local"
        for lo, hi in self.common_ranges:
            if lo <= number <= hi:
                return "common"
        if number >= self.system_first:
            return "system"
        return "invalid"

    def is_reserved(self, number: int) -> bool:
        return any(lo <= number <= hi for lo, hi in self.reserved)


@dataclass(slots=True)
class Variables:
    """The variable store of one program run."""

    layout: VariableLayout
    system: SystemVariables | None = None
    commons: dict[int, float] = field(default_factory=dict)
    _scopes: list[dict[int, float]] = field(default_factory=lambda: [{}])

    # ---- scopes (one per macro call level)
    def push_scope(self, values: dict[int, float]) -> None:
        self._scopes.append(dict(values))

    def pop_scope(self) -> None:
        if len(self._scopes) > 1:
            self._scopes.pop()

    @property
    def depth(self) -> int:
        return len(self._scopes) - 1

    @property
    def locals(self) -> dict[int, float]:
        return self._scopes[-1]

    # ---- access
    def number(self, raw: float, start: int = -1, end: int = -1) -> int:
        """A variable number from an evaluated index (rounded like Fanuc)."""
        n = round(raw)
        if abs(raw - n) > 1e-6 or n < 0:
            raise MacroError("E0302", f"#{raw:g} is not a variable number", start, end)
        return n

    def read(self, n: int, start: int = -1, end: int = -1) -> Value:
        kind = self.layout.kind(n)
        if kind == "local":
            return self._scopes[-1].get(n)
        if kind == "common":
            return self.commons.get(n)
        if kind == "null":
            return None
        if kind == "system" and self.system is not None:
            return self.system.read(n)
        raise MacroError("E0302", f"#{n} is not a variable of the {self.layout.flavour} macro language", start, end)

    def write(self, n: int, value: Value, start: int = -1, end: int = -1) -> None:
        kind = self.layout.kind(n)
        if kind == "local":
            _store(self._scopes[-1], n, value)
        elif kind == "common":
            _store(self.commons, n, value)
        elif kind == "null":
            raise MacroError("E0303", "#0 is always vacant and cannot be assigned", start, end)
        elif kind == "system" and self.system is not None:
            if not self.system.write(n, value):
                raise MacroError("E0303", f"#{n} is a read-only system variable", start, end)
        else:
            raise MacroError("E0302", f"#{n} is not a variable of the {self.layout.flavour} macro language",
                             start, end)


def _store(table: dict[int, float], n: int, value: Value) -> None:
    if value is None:
        table.pop(n, None)
    else:
        table[n] = value
