"""Report columns: which plans the report compares (``--compare``).

``--compare=O0,O1,O2`` compares planner levels on the selected machine;
``--compare=generic-mill,szgh-990mdb`` compares machine models at the selected level;
``NAME@O1`` (or ``O1@NAME``) fixes both.  Without ``--compare`` the report has the
selected level and, beside it, the nominal ``-O0`` estimate.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

_LEVEL = re.compile(r"^-?O([0-3])$")


@dataclass(frozen=True, slots=True)
class ColumnSpec:
    label: str
    machine: str | None  # None: the machine of -m
    level: int


def parse_compare(text: str, level: int) -> list[ColumnSpec] | str:
    """The column specs of a ``--compare`` value, or an error message."""
    out: list[ColumnSpec] = []
    for item in (part.strip() for part in text.split(",")):
        if not item:
            continue
        name: str | None = None
        lvl = level
        for piece in item.split("@"):
            m = _LEVEL.match(piece.strip())
            if m:
                lvl = int(m.group(1))
            elif piece.strip() and name is None:
                name = piece.strip()
            else:
                return f"--compare: cannot read {item!r} (expected O0..O3, a machine name, or NAME@O1)"
        label = f"O{lvl}" if name is None else f"{name} O{lvl}"
        out.append(ColumnSpec(label, name, lvl))
    if not out:
        return "--compare: no columns given"
    return out


def default_columns(level: int) -> list[ColumnSpec]:
    """The selected level, and the nominal estimate beside it (once, at -O0)."""
    cols = [ColumnSpec(f"O{level}", None, level)]
    if level != 0:
        cols.append(ColumnSpec("nominal O0", None, 0))
    return cols
