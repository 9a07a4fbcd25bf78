"""The interpreter's run state beside the modal snapshot, as typed records it owns.

:class:`~cncc.frontend.interp.Interpreter` declares one field per record (see its
``__slots__``); no module keeps per-interpreter state of its own:

* :class:`References` (frozen, replaced): the G28/G30 intermediate point, the start
  point and SZGH G25's saved point, in machine or program terms;
* :class:`CycleState` (frozen, replaced): the canned cycle's stored data and the
  spindle direction the cycles check (``cncc/frontend/cycles.py``);
* :class:`TransformState` (mutable, owned): polar point, G10 wear tables and the
  compensation ops in force (``cncc/frontend/transforms.py``) — G10 writes single
  table entries, so the tables are changed in place rather than copied;
* :class:`RunNotes` (mutable, owned): which once-per-program notes were given
  (W0270 per M code, W0513 per offset number);
* :class:`LayerRecords`: one record per dialect layer type (SERIES 8's
  ``S8State``), for layers the core does not know by name.

The RS274 record (``cncc/frontend/rs274.py``'s ``Rs274State``) is a declared field
of its own, created when a RS274 op first needs it.  docs/decisions.md (2026-12-02,
house) gives the frozen-or-owned choice per record.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field
from typing import TypeVar

from cncc.dialects import CodeDef
from cncc.frontend.modal import Reference
from cncc.ir import ZERO6, CycleKind, Plane, SpindleState, Vec6

_R = TypeVar("_R")


@dataclass(frozen=True, slots=True)
class References:
    """Reference positions: G28/G30's intermediate point (program mm), the start point
    (machine mm, SZGH G26) and G25's saved point (machine mm, None before any G25)."""

    intermediate: Reference = field(default_factory=Reference)
    start_machine_mm: Vec6 = ZERO6
    saved_machine_mm: Vec6 | None = None


@dataclass(frozen=True, slots=True)
class CycleData:
    """The cycle in force and its stored (modal) data; levels are absolute."""

    code: CodeDef
    kind: CycleKind
    plane: Plane
    initial_mm: float
    r_mm: float | None = None
    bottom_mm: float | None = None
    q_mm: float | None = None  # |Q|: peck depth or boring shift (one shared modal value)
    dwell_s: float = 0.0
    pitch_mm: float | None = None  # tapping pitch word (SZGH K)


@dataclass(frozen=True, slots=True)
class CycleState:
    """The last cycle's stored data (in force while ``ModalState.cycle`` is set) and the
    spindle direction last programmed (M03/M04/M05/M19)."""

    data: CycleData | None = None
    spindle: SpindleState = SpindleState.OFF


@dataclass(slots=True)
class TransformState:
    """What the frame and compensation handlers keep beside the modal snapshot."""

    polar_radius_mm: float = 0.0
    polar_angle_deg: float = 0.0
    length_wear_mm: dict[int, float] = field(default_factory=dict)
    radius_wear_mm: dict[int, float] = field(default_factory=dict)
    length_op: str = "length_off"
    comp_op: str = "comp_off"
    d_index: int = 0


@dataclass(slots=True)
class OffsetNotes:
    """W0513 without a tool table: the offset numbers listed so far (frontend/offset_notes.py)."""

    table_given: bool
    names: list[str] = field(default_factory=list)
    at: int = -1  # index of the warning in the sink (a hint: the item itself is ``item``)
    item: object = None  # the warning as emitted (found again by identity)


@dataclass(slots=True)
class RunNotes:
    """Once-per-program notes already given."""

    m_codes_warned: set[int] = field(default_factory=set)  # W0270, by M tenths
    offsets: OffsetNotes | None = None


class LayerRecords:
    """The run-state records of dialect layers, at most one per record type."""

    __slots__ = ("_records",)

    def __init__(self) -> None:
        self._records: dict[type, object] = {}

    def get(self, kind: type[_R]) -> _R | None:
        record = self._records.get(kind)
        return record if isinstance(record, kind) else None

    def __eq__(self, other: object) -> bool:
        return isinstance(other, LayerRecords) and self._records == other._records

    __hash__ = None  # type: ignore[assignment]

    def __deepcopy__(self, memo: dict[int, object]) -> LayerRecords:
        out = LayerRecords()
        out._records = {k: copy.deepcopy(v, memo) for k, v in self._records.items()}
        return out

    def attach(self, record: _R) -> _R:
        """Give the interpreter ``record`` (replacing one of the same type)."""
        self._records[type(record)] = record
        return record


__all__ = ["CycleData", "CycleState", "LayerRecords", "OffsetNotes", "References", "RunNotes", "TransformState"]
