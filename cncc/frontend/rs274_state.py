"""The RS274 run-state record (``Interpreter.rs274``) and its accessor.

A module of its own so that every RS274 module (``rs274``, ``rs274_g10``,
``rs274_curves``, ``rs274_sync``) reaches the record without importing another one
(no import circle; tests/test_layers.py).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from cncc.ir import ZERO6, Vec6

if TYPE_CHECKING:
    from cncc.frontend.interp import Interpreter


@dataclass(slots=True)
class Rs274State:
    """RS274 modes the shared :class:`~cncc.frontend.modal.ModalState` does not hold."""

    arc_absolute: bool = False  # G90.1
    inverse_time: bool = False  # G93
    g92_saved_mm: Vec6 = ZERO6  # parameters 5211-5216 (G92.2 keeps them, G92.3 restores)
    g92_applied: bool = False  # parameter 5210: G92/G52 in force (G92.1/G92.2 clear it, G92.3 sets it)
    stored_mm: dict[int, Vec6] = field(default_factory=dict)  # G28 (1) / G30 (2) in machine coordinates
    g5_pq_mm: tuple[float, float] = (0.0, 0.0)  # P, Q of the last G5 (its end tangent)
    nurbs: list[tuple[float, float, float]] = field(default_factory=list)  # G5.2 control points x, y, weight
    nurbs_order: int = 3
    naive_mm: float = 0.0  # G64 Q (the naive-CAM tolerance in force)
    rotation_deg: dict[int, float] = field(default_factory=dict)  # G10 L2 R: work system -> XY rotation


def state(it: Interpreter) -> Rs274State:
    """The interpreter's RS274 record, made on first use (``Interpreter.rs274``)."""
    st = it.rs274
    if st is None:
        st = it.rs274 = Rs274State()
    return st


__all__ = ["Rs274State", "state"]
