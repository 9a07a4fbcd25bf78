"""W0513 without a tool table: one warning per program listing every H/D number used.

When the run has a tool table (``--tools`` or offsets written by the program before
the first use), each H or D number missing from it is its own warning at the word.
Without one, every H and D word would warn (79 warnings in 16 shop files): the
program then gets one warning, at the first use, whose message lists the numbers.
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING, Any

from cncc import diagnostics as dg
from cncc.frontend.run_state import OffsetNotes
from cncc.source import Span

if TYPE_CHECKING:
    from cncc.frontend.interp import Interpreter


def offset_missing(it: Interpreter, span: Span, letter: str, index: int) -> None:
    """Report that offset ``letter``+``index`` (H1, D7) is not in the tool table."""
    st = it.notes.offsets
    if st is None:
        st = it.notes.offsets = OffsetNotes(bool(it.options.tool_lengths_mm or it.options.tool_radii_mm))
    name = f"{letter}{index}"
    if st.table_given:
        it.sink.emit(dg.OFFSET_NOT_IN_TABLE, span, f"{name} is not in the tool table; 0 is used")
        return
    if name in st.names:
        return
    st.names.append(name)
    message = (f"no tool table (--tools): 0 is used for the offsets {', '.join(st.names)}"
               if len(st.names) > 1 else f"no tool table (--tools): 0 is used for the offset {name}")
    items = it.sink.items
    at = _find(items, st)
    if at >= 0:
        items[at] = replace(items[at], message=message)
        st.at, st.item = at, items[at]
        return
    before = len(items)
    it.sink.emit(dg.OFFSET_NOT_IN_TABLE, span, message)
    st.at, st.item = (before, items[before]) if len(items) > before else (-1, None)


def _find(items: list[Any], st: OffsetNotes) -> int:
    """Where the warning is now: at its index, or moved (a stage may take reports out and put them back)."""
    if st.item is None:
        return -1
    if 0 <= st.at < len(items) and items[st.at] is st.item:
        return st.at
    return next((k for k in range(len(items) - 1, -1, -1) if items[k] is st.item), -1)
