"""SERIES 8 run state beside the shared modal snapshot: a record in the interpreter's
dialect-layer records (``Interpreter.extras``, :class:`~cncc.frontend.run_state.LayerRecords`)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from cncc.dialects import CodeDef
from cncc.frontend.syntax import Word
from cncc.source import Span

if TYPE_CHECKING:
    from cncc.frontend.interp import Interpreter


@dataclass(slots=True)
class CycleWords:
    """Stored canned-cycle data: levels are absolute (A-18) and kept across cycles and G80."""

    r_mm: float | None = None
    z_mm: float | None = None
    first_mm: float | None = None  # G83 I: level of the first peck
    peck_mm: float | None = None  # G83 J
    lead_mm: float | None = None  # G84 K
    dwell_s: float = 0.0  # P
    shift_mm: tuple[float, float] = (0.0, 0.0)  # G88/G89 I J


@dataclass(slots=True)
class S8State:
    arc_r_mm: float | None = None  # the modal arc radius: only an R in an arc block sets it
    sharp: bool = False  # G21/G22/G23 in force: exact stop at every block end
    restore_incremental: bool | None = None  # G67/G68: the G90/G91 state after this block
    corner: tuple[str, float, Span] | None = None  # G10 in this block: ("R"|"L", size mm, span)
    comp_warned: bool = False
    moved: bool = False  # a motion has been made (for the unit-switch warning)
    g06_warned: bool = False
    cycle: CycleWords = field(default_factory=CycleWords)
    cycle_code: CodeDef | None = None  # the G81-G89 code in force
    at_depth: bool = False  # G87 left the tool at depth
    feed_before: float | None = None  # the modal F before this block (G04 F is not a feed)
    dwell_f: Word | None = None  # G04 F: the dwell time taken out of the block
    inverse_f: float | None = None  # G93: the last F (1/min), carried to the next feed blocks
    css_reference: tuple[float, float] | None = None  # G92 R: (radius mm, X mm where it was given)
    x_diameter: bool = False  # lathe program with lathe_diameter_x: X words are diameters
    vendor_noted: set[str] = field(default_factory=set)  # G34-G36, G49/G50 whose reading was announced


def attach(it: Interpreter) -> S8State:
    """Give ``it`` a fresh SERIES 8 record (in its dialect-layer records, ``Interpreter.extras``)."""
    return it.extras.attach(S8State())


def get(it: Interpreter) -> S8State | None:
    """The SERIES 8 state of ``it``; None for interpreters of other dialects."""
    return it.extras.get(S8State)


def option(it: Interpreter, key: str, default: Any) -> Any:
    return it.dialect.option(key, default)
