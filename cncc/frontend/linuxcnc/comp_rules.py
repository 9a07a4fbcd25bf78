"""What LinuxCNC 2.9's interpreter refuses while cutter radius compensation is on.

rs274 checks each code when it runs it, in its order of execution: M6 and a second G41/G42
run before the block's G40-G42 and see the compensation in force before the block; every
other code runs after them (``G40 G53 G0 X0`` is fine, ``G41 D1 G28`` is not).  The codes
and rs274's texts are data (``[comp_refuses]`` of ``linuxcnc.toml``, keys ``before`` and
``after``: op -> text); G10 L2/L20 is refused only for the active system, a canned cycle
also when it runs modally, and reading ``#5420``-``#5428`` in an expression
(:func:`position_read_refused`; a DEBUG message may read them).  The block is not run
(``E0572`` with rs274's text).  G92.1-G92.3 are run as nothing (``ignored``; rs274 2.9 prints no
``SET_G92_OFFSET`` for them and keeps the offset): :func:`without_ignored`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from cncc.frontend.syntax import Word
from cncc.ir import CompSide

if TYPE_CHECKING:
    from cncc.frontend.interp import Interpreter

_COMP_OPS = {"comp_off": False, "comp_left": True, "comp_right": True, "comp_left_dynamic": True,
             "comp_right_dynamic": True}
_POSITION = range(5420, 5429)
_OVERRIDE_CONTROL = frozenset({"feed_override", "speed_override", "adaptive_feed", "feed_stop"})  # M50-M53 P


def _table(it: Interpreter, stage: str) -> dict[str, str]:
    raw = it.dialect.raw.get("comp_refuses", {}).get(stage, {})
    return {str(k): str(v) for k, v in raw.items()}


def _ops(it: Interpreter, words: tuple[Word, ...]) -> list[tuple[str, str]]:
    """(op, group) of the block's G and M codes."""
    out: list[tuple[str, str]] = []
    for w in words:
        if w.letter in "GM":
            c = it.dialect.code(w.letter, round(w.value * 10))
            if c is not None:
                out.append((c.op, c.group or ""))
    return out


def refused(it: Interpreter, words: tuple[Word, ...], in_cycle: bool) -> str | None:
    """rs274's error text when the block runs a code that compensation forbids, else None.
    ``in_cycle``: the block runs a canned cycle (its own code or the one in force)."""
    if not it.dialect.raw.get("comp_refuses"):
        return None
    ops = _ops(it, words)
    on_before = it.frame.comp_side is not CompSide.OFF
    on_after = next((_COMP_OPS[op] for op, _ in ops if op in _COMP_OPS), on_before)
    if on_before:
        before = _table(it, "before")
        hit = next((before[op] for op, _ in ops if op in before), None)
        if hit is None and any(op in _OVERRIDE_CONTROL for op, _ in ops):  # M50-M53: P0 disables, else enables
            p = next((w.value for w in words if w.letter == "P"), 1.0)
            hit = before.get("overrides_off" if p == 0 else "overrides_on")
        if hit is not None:
            return hit
    if not on_after:
        return None
    after = _table(it, "after")
    for op, _ in ops:
        if op == "data_input_rs274":
            if _changes_active_system(it, words):
                return after.get("data_input_active")
            continue
        if op in after:
            return after[op]
    if in_cycle:
        return after.get("cycle")
    return None


def _changes_active_system(it: Interpreter, words: tuple[Word, ...]) -> bool:
    """G10 L2/L20 of the active work system (P0 or its number)."""
    got = {w.letter: w.value for w in words if w.letter in "LP"}
    if round(got.get("L", -1)) not in (2, 20):
        return False
    p = round(got.get("P", -1))
    return p == 0 or p == it.frame.work_index


def without_ignored(it: Interpreter, words: tuple[Word, ...]) -> tuple[Word, ...]:
    """The block without the codes rs274 runs as nothing while compensation is on (G92.1-G92.3)."""
    ignored = it.dialect.raw.get("comp_refuses", {}).get("ignored", [])
    if not ignored or not any(w.letter == "G" for w in words):
        return words
    ops = _ops(it, words)
    if not next((_COMP_OPS[op] for op, _ in ops if op in _COMP_OPS), it.frame.comp_side is not CompSide.OFF):
        return words
    return tuple(w for w in words if not (w.letter == "G" and (c := it.dialect.code("G", round(w.value * 10)))
                                          is not None and c.op in ignored))


def position_read_refused(it: Interpreter, n: int) -> str | None:
    """rs274's text for reading the current position (#5420-#5428) while compensation is on."""
    if n not in _POSITION or it.frame.comp_side is CompSide.OFF:
        return None
    text = it.dialect.raw.get("comp_refuses", {}).get("position_read")
    return str(text) if text else None
