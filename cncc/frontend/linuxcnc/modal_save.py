"""LinuxCNC's M70-M73: save, invalidate and restore the modal state of a call level.

``M70`` saves the modal state at the current call level, ``M71`` forgets it, ``M72``
restores it, ``M73`` saves it and restores it when the subroutine returns.  A restore
runs the codes of the saved state that differ from the current one, as rs274 2.9 does
(``gen_restore_cmd``), so the trace shows the calls those codes make: first the units
(G20/G21), then in one block the feed mode, F (not in G93; one decimal), S (a whole
number), M3/M4/M5, the plane,
G7/G8, cutter compensation, tool length (G43 H/G43.1 Z/G49), work system, path mode
(G61/G61.1/G64 P Q), distance mode, arc centre mode and the canned-cycle return level.
``M72`` with nothing saved at its level is an error (rs274's text).

Coolant as rs274 2.9 restores it (measured): M7 when mist was on and is off now, M8 likewise
for flood, M9 when both were off and one is on now; the first M code of the restore (M3/M4/M5,
then coolant) is in its main block, each further one in a block of its own after it; a
coolant that is on now and was off stays on when the other one was on.
Compensation: G40 when it was off; G41/G42 without D (the loaded tool) when it was on.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from cncc.ir import CompSide, PathMode, Plane, SpindleState, Units

if TYPE_CHECKING:
    from cncc.frontend.interp import Interpreter

Words = list[tuple[str, float]]
_PLANES = {Plane.XY: 17.0, Plane.ZX: 18.0, Plane.YZ: 19.0}
_SPINDLE = {SpindleState.CW: 3.0, SpindleState.CCW: 4.0, SpindleState.OFF: 5.0}
_PATH = {PathMode.EXACT_PATH: 61.0, PathMode.EXACT_STOP: 61.1, PathMode.CONTINUOUS: 64.0}


@dataclass(frozen=True, slots=True)
class Saved:
    units: Units
    feed_mode: float  # 93, 94, 95
    feed: float  # no F yet: 0
    rpm: float
    spindle: SpindleState
    plane: Plane
    length: tuple[str, float, int]  # code name, offset mm, H index
    work: str
    path: tuple[PathMode, float | None, float]  # mode, P mm, Q mm
    incremental: bool
    arc_absolute: bool
    retract: str
    mist: bool = False
    flood: bool = False
    diameter: bool = False  # G7
    comp: CompSide = CompSide.OFF


def save(it: Interpreter, coolant: tuple[bool, bool] = (False, False)) -> Saved:
    """The modal state now; ``coolant``: (mist, flood) on."""
    from cncc.frontend.cycles import spindle_state  # (imported here: the executor loads this module early)
    from cncc.frontend.linuxcnc.lathe import diameter_mode
    from cncc.frontend.rs274 import state

    st = state(it)
    f = it.frame
    mode = 93.0 if st.inverse_time else 95.0 if it.modal.per_rev else 94.0
    p = it.modal.path
    return Saved(f.units, mode, it.modal.feed or 0.0, it.modal.spindle_rpm, spindle_state(it), f.plane,
                 (it.group_codes.get("length_comp", "G49"), f.tool_length_mm, f.tool_length_index),
                 it.group_codes.get("work", "G54"), (p.mode, p.blend_tolerance_mm, st.naive_mm),
                 it.modal.incremental, st.arc_absolute, it.group_codes.get("cycle_return", "G99"),
                 coolant[0], coolant[1], diameter_mode(it), f.comp_side)


def _code(name: str) -> tuple[str, float]:
    return name[0], float(name[1:])


def _m_codes(now: Saved, s: Saved) -> Words:
    """The restore's M codes: M3/M4/M5, then rs274's coolant (M9, or M7 and M8)."""
    out: Words = []
    if now.spindle is not s.spindle and s.spindle in _SPINDLE:
        out.append(("M", _SPINDLE[s.spindle]))
    if not s.mist and not s.flood:
        return out + ([("M", 9.0)] if now.mist or now.flood else [])
    return out + ([("M", 7.0)] if s.mist and not now.mist else []) + ([("M", 8.0)] if s.flood and not now.flood else [])


def restore_blocks(it: Interpreter, s: Saved, coolant: tuple[bool, bool] = (False, False)) -> tuple[Words, ...]:
    """The words of the restore blocks (units; the others with the first M code; each further M code)
    for the state differing from ``s``; ``coolant``: (mist, flood) on now."""
    now = save(it, coolant)
    units: Words = [] if now.units is s.units else [("G", 20.0 if s.units is Units.INCH else 21.0)]
    k = s.units.mm_per_unit
    out: Words = []
    if now.feed_mode != s.feed_mode:
        out.append(("G", s.feed_mode))
    if now.feed != s.feed and s.feed_mode != 93.0:
        out.append(("F", float(f"{s.feed:.1f}")))  # rs274 writes the restore line's F with one decimal
    if now.rpm != s.rpm:
        out.append(("S", float(f"{s.rpm:.0f}")))  # and S with none
    ms = _m_codes(now, s)
    out += ms[:1]  # rs274 writes one M code in the restore block, each further one in a block of its own
    if now.plane is not s.plane and s.plane in _PLANES:
        out.append(("G", _PLANES[s.plane]))
    if now.diameter != s.diameter:
        out.append(("G", 7.0 if s.diameter else 8.0))
    if (now.comp is CompSide.OFF) != (s.comp is CompSide.OFF):
        out.append(("G", 40.0 if s.comp is CompSide.OFF else 41.0 if s.comp is CompSide.LEFT else 42.0))
    _rest(now, s, k, out)
    return (units, out, *([m] for m in ms[1:]))


def _rest(now: Saved, s: Saved, k: float, out: Words) -> None:
    """Tool length, work system, path mode, distance modes and the cycle return level (``k``: mm per unit)."""
    if now.length[0] != s.length[0]:
        out.append(_code(s.length[0]))
        if s.length[0] == "G43.1":
            out.append(("Z", s.length[1] / k))
        elif s.length[0] == "G43" and s.length[2]:
            out.append(("H", float(s.length[2])))
    if now.work != s.work:
        out.append(_code(s.work))
    if now.path != s.path:
        mode, tol_mm, naive_mm = s.path
        out.append(("G", _PATH[mode]))
        if mode is PathMode.CONTINUOUS and tol_mm is not None:
            out += [("P", tol_mm / k), ("Q", naive_mm / k)]
    if now.incremental != s.incremental:
        out.append(("G", 91.0 if s.incremental else 90.0))
    if now.arc_absolute != s.arc_absolute:
        out.append(("G", 90.1 if s.arc_absolute else 91.1))
    if now.retract != s.retract:
        out.append(_code(s.retract))
