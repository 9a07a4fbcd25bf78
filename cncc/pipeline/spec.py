"""The ``-p`` pass spec: ``name{opt=value,opt=value},name2`` as text, parsed with positions.

>>> [(r.name, r.options) for r in parse("expand-cycles,arc-check{repair=true}")]
[('expand-cycles', {}), ('arc-check', {'repair': 'true'})]

Errors are :class:`SpecError` with the columns (0-based, end exclusive) of the part of
the spec that is wrong, so the driver can point at it.  Option values stay text here;
:func:`convert` turns them into a pass field's type.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

_NAME = re.compile(r"[A-Za-z][A-Za-z0-9_.-]*")
_OPTION = re.compile(r"\s*([A-Za-z_][A-Za-z0-9_]*)\s*=\s*([^,{}=]*?)\s*(?=[,}])")


class SpecError(ValueError):
    """A malformed or unknown part of a pass spec, at columns ``start``..``end``."""

    def __init__(self, message: str, start: int, end: int) -> None:
        super().__init__(message)
        self.message, self.start, self.end = message, start, max(end, start + 1)


@dataclass(frozen=True, slots=True)
class PassRequest:
    """One pass named in a spec: its name, its options as text, and where they are."""

    name: str
    options: dict[str, str] = field(default_factory=dict)
    start: int = 0  # column of the name
    end: int = 0  # column just after the name
    option_columns: dict[str, tuple[int, int]] = field(default_factory=dict)


def parse(text: str) -> list[PassRequest]:
    """The passes of ``text`` in order (empty text: none)."""
    out: list[PassRequest] = []
    i, n = 0, len(text)
    while i < n:
        while i < n and text[i] == " ":
            i += 1
        m = _NAME.match(text, i)
        if m is None:
            raise SpecError(f"expected a pass name at column {i + 1}", i, i + 1)
        name, start, i = m.group(), m.start(), m.end()
        options: dict[str, str] = {}
        columns: dict[str, tuple[int, int]] = {}
        if i < n and text[i] == "{":
            close = text.find("}", i)
            if close < 0:
                raise SpecError(f"the options of {name} are not closed with '}}'", i, n)
            i = _options(text, i + 1, close, name, options, columns)
        while i < n and text[i] == " ":
            i += 1
        if i < n and text[i] != ",":
            raise SpecError(f"expected ',' or the end after {name} at column {i + 1}", i, i + 1)
        if i < n and i + 1 == n:
            raise SpecError("a pass name must follow the last ','", i, i + 1)
        i += 1
        out.append(PassRequest(name, options, start, m.end(), columns))
    return out


def _options(text: str, i: int, close: int, name: str, options: dict[str, str],
             columns: dict[str, tuple[int, int]]) -> int:
    """Read ``opt=value,...`` between ``i`` and the ``}`` at ``close``; the column after ``}``."""
    while i < close:
        m = _OPTION.match(text, i, close + 1)
        if m is None:
            raise SpecError(f"expected option=value in the options of {name} at column {i + 1}", i, close)
        key = m.group(1)
        if key in options:
            raise SpecError(f"{name}: option {key} given twice", m.start(1), m.end(1))
        options[key] = m.group(2)
        columns[key] = (m.start(1), m.end(2))
        i = m.end()
        if text[i] == ",":
            i += 1
    return close + 1


def convert(value: str, annotation: str) -> object:
    """The option text ``value`` as the type a pass field is annotated with (bool, int,
    float or str, optionally ``| None``); ValueError when it does not fit."""
    kinds = {part.strip() for part in annotation.split("|")}
    if "None" in kinds and value.lower() in ("none", ""):
        return None
    kinds.discard("None")
    if kinds == {"bool"}:
        low = value.lower()
        if low in ("true", "on", "yes", "1"):
            return True
        if low in ("false", "off", "no", "0"):
            return False
        raise ValueError("expected true or false")
    if kinds == {"int"}:
        return int(value)
    if kinds == {"float"}:
        return float(value)
    if kinds == {"str"}:
        return value
    raise ValueError(f"a {annotation} cannot be given in a spec")


def settable(annotation: str) -> bool:
    """Whether a field annotated so can be set from a spec."""
    kinds = {part.strip() for part in annotation.split("|")} - {"None"}
    return len(kinds) == 1 and kinds <= {"bool", "int", "float", "str"}
