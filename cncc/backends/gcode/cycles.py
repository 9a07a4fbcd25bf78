"""Canned cycles in translated G-code: which ones a target can keep, and their words.

Consumes :class:`cncc.ir.Cycle` commands and a :class:`Target`; produces

* :func:`keep_problem` — why the target would not run this cycle exactly as the
  source did ("" when it would): the target has no code for the kind, a machine
  parameter of the target (peck clearance, shift direction, return rule, peck
  tapping) gives different moves, or the cycle sits in a transformed frame;
* :func:`cycle_words` — the words of the first block of the cycle (``G98 G83 X Y Z
  R Q P F`` in the target's letters and units); the other holes take only the plane
  axes.

Everything is written absolute (G90), so the source's incremental rules and repeat
counts never reach the target: each repeat is written as its own hole.
"""

from __future__ import annotations

from cncc.backends.gcode.target import Target
from cncc.ir import CompSide, Cycle, CycleKind, CycleKindBase, Plane, Vec6

_PECKS = (CycleKind.PECK, CycleKind.PECK_HIGH_SPEED)
_TAPS = (CycleKind.TAP, CycleKind.TAP_LEFT)
_SHIFTS = (CycleKind.FINE_BORE, CycleKind.BACK_BORE)
_CLEARANCE_KEYS: dict[CycleKindBase, str] = {
    CycleKind.PECK_HIGH_SPEED: "cycle_g73_retract_mm", CycleKind.PECK: "cycle_g83_clearance_mm",
    CycleKind.TAP: "cycle_tap_clearance_mm", CycleKind.TAP_LEFT: "cycle_tap_clearance_mm"}
_TOL_MM = 1e-9


def keep_problem(c: Cycle, target: Target) -> str:
    """Why ``c`` cannot be written as the target's cycle ("" when it can)."""
    kind = c.kind.value
    if not bool(target.dialect.raw.get("emit", {}).get("keep_cycles", True)):
        return f"{target.name} output keeps no canned cycles"
    if kind not in target.cycles:
        return f"{target.name} has no {kind.replace('_', ' ')} cycle"
    missing = [op for op in ("cycle_off", "return_initial" if c.return_initial else "return_r") if not target.has(op)]
    if missing:
        return f"{target.name} has no code for {missing[0].replace('_', ' ')}"
    f = c.frame
    if f.rotation or f.scaling or f.mirror or f.polar or f.comp_side is not CompSide.OFF:
        return "the cycle is in a transformed frame"
    if c.motion.per_rev or c.motion.inverse_time:
        return "the cycle feed is not per minute"
    return _parameter_problem(c, target)


def _parameter_problem(c: Cycle, target: Target) -> str:
    if abs(target_retract(c, target) - c.retract_mm) > _TOL_MM:
        return f"{target.name} returns to a different level (cycle_return_higher)"
    key = _CLEARANCE_KEYS.get(c.kind)
    uses_clearance = c.kind in _PECKS or (c.kind in _TAPS and c.peck_mm > 0)
    if key and uses_clearance and abs(float(target.option(key, 0.0)) - c.clearance_mm) > _TOL_MM:
        return f"{target.name}'s {key} is {float(target.option(key, 0.0)):g}, the source's {c.clearance_mm:g}"
    if c.kind in _TAPS and c.peck_mm > 0 and (target.option("cycle_peck_tap", "return_r") == "return_r") \
            != c.peck_tap_to_r:
        return f"{target.name} pecks taps differently (cycle_peck_tap)"
    if c.kind in _TAPS and c.spindle_rpm <= 0:
        return "a tapping cycle without a spindle speed"
    if c.kind in _SHIFTS and shift_vector(c, target) != c.shift_mm:
        return f"{target.name} shifts the boring bar in another direction (cycle_shift_direction)"
    if c.kind in _PECKS and peck_lift(c.kind, target) != (getattr(c, "lift_pause_s", 0.0),
                                                          getattr(c, "lift_at_feed", False)):
        return f"{target.name} lifts between pecks differently (cycle_peck_pause_ms)"
    user = f"cycle_user_{target.cycles[c.kind.value].name.lower()}"
    if target.option(user, 0):
        return f"{target.name} runs a user program for {target.cycles[c.kind.value].name} ({user})"
    return ""


def peck_lift(kind: CycleKind, target: Target) -> tuple[float, bool]:
    """(pause before each peck lift in s, lift at feed) of the target (SZGH User P8)."""
    ms = float(target.option("cycle_peck_pause_ms", 0.0))
    if kind not in _PECKS or abs(ms) <= 5.0:
        return (0.0, False)
    return (abs(ms) / 1000.0, ms < 0)


def target_retract(c: Cycle, target: Target) -> float:
    """The level the target returns to after each hole (its G98/G99 rule)."""
    if c.kind is CycleKind.BACK_BORE:
        return c.initial_mm
    if not c.return_initial:
        return c.r_mm
    if bool(target.option("cycle_return_higher", False)) and c.r_mm > c.initial_mm:
        return c.r_mm
    return c.initial_mm


def shift_vector(c: Cycle, target: Target) -> Vec6:
    """The G76/G87 shift the target makes for ``|shift|`` (its direction parameters)."""
    q = max(abs(v) for v in c.shift_mm)
    if q == 0.0:
        return c.shift_mm
    direction = int(target.option("cycle_shift_direction", 0))
    reverse = bool(target.option("cycle_fine_bore_shift_reverse", False))
    if c.kind is CycleKind.BACK_BORE:
        own = int(target.option("cycle_back_bore_shift_direction", -1))
        reverse = own < 0
        direction = direction if own < 0 else own
    plane: Plane = c.frame.plane
    axis = plane.first if direction < 2 else plane.second
    sign = -1.0 if direction % 2 else 1.0
    if reverse:
        sign = -sign
    v = [0.0] * 6
    v[axis] = sign * q
    return (v[0], v[1], v[2], v[3], v[4], v[5])


def q_value_mm(c: Cycle) -> float:
    """The Q word: peck depth, or the shift distance of a boring cycle (0: no Q)."""
    if c.kind in _SHIFTS:
        return max(abs(v) for v in c.shift_mm)
    return c.peck_mm


def needs_pitch_word(c: Cycle, target: Target) -> str:
    """The target's tapping pitch letter when it has one (SZGH K), else ""."""
    return str(target.option("cycle_pitch_word", "")) if c.kind in _TAPS else ""
