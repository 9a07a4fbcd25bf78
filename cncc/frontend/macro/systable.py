"""Per-dialect tables of system variables (``[[system_variables]]`` in a dialect file).

Each entry is a range of numbers with a ``kind`` (what cncc reads or writes for it:
``tool_length``, ``work``, ``position`` ...), an ``access`` (``"rw"`` or ``"r"``) and
what the manual calls it.  The table says which numbers exist on the controller and
which a program may write; :mod:`cncc.frontend.macro.sysvars` does the reading and
writing by kind.  A number no entry covers is unknown: a warning, read vacant, a write
ignored (the controller may have it as an option cncc does not know).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from cncc.dialects import Dialect, DialectError

KINDS = frozenset({
    "io_input", "output", "constant", "alarm", "message_stop", "modal_g", "modal_other", "position",
    "machine_position", "work", "work_extended", "tool_length", "tool_length_wear", "tool_radius",
    "tool_radius_wear",
})


@dataclass(frozen=True, slots=True)
class SystemRange:
    first: int
    last: int
    kind: str
    writable: bool
    what: str


class SystemTable:
    """The ranges of one dialect, looked up by number (later entries win on overlap)."""

    def __init__(self, ranges: list[SystemRange]) -> None:
        self.ranges = ranges

    def find(self, n: int) -> SystemRange | None:
        found = None
        for r in self.ranges:  # a few dozen entries: a scan is cheap and keeps "later wins"
            if r.first <= n <= r.last:
                found = r
        return found

    def __len__(self) -> int:
        return len(self.ranges)


def table_for(dialect: Dialect) -> SystemTable | None:
    """The dialect's table, or None when it has none (the built-in Fanuc numbering applies)."""
    raw = dialect.raw.get("system_variables")
    if not raw:
        return None
    return SystemTable([_entry(e, i, dialect.name) for i, e in enumerate(raw)])


def _entry(e: Any, i: int, name: str) -> SystemRange:
    where = f"{name}.toml system_variables[{i}]"
    if not isinstance(e, dict):
        raise DialectError(f"{where}: expected a table")
    try:
        first, last, kind = int(e["first"]), int(e["last"]), str(e["kind"])
    except (KeyError, TypeError, ValueError) as exc:
        raise DialectError(f"{where}: needs integer 'first', 'last' and a 'kind' ({exc})") from None
    if kind not in KINDS:
        raise DialectError(f"{where}.kind: {kind!r} is not one of {', '.join(sorted(KINDS))}")
    access = str(e.get("access", "r"))
    if access not in ("r", "rw") or last < first:
        raise DialectError(f"{where}: access must be 'r' or 'rw' and last >= first")
    return SystemRange(first, last, kind, access == "rw", str(e.get("what", "")))


__all__ = ["KINDS", "SystemRange", "SystemTable", "table_for"]
