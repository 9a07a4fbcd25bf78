"""LinuxCNC's lathe cycles G70 (finishing) and G71/G71.1/G71.2, G72/G72.1/G72.2 (roughing): the checks.

cncc checks a G7x block as rs274 2.9 does before it moves (no Q, a word the cycle does
not read, a repeated word, U/W axis words, cutter compensation, a plane other than
G18, ``I`` not above zero) and reports rs274's texts; a block that passes those checks
is cut by :mod:`cncc.frontend.linuxcnc.g7x_run`.  The cycle is written from LinuxCNC's
G-code manual and black-box runs of rs274 2.9, not from LinuxCNC's source (GPL-2.0):
docs/decisions.md, 2026-12-02, "G70-G72 written from the manual".
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from cncc import diagnostics as dg
from cncc.frontend.syntax import Block, Word
from cncc.ir import CompSide, Plane
from cncc.source import Span

if TYPE_CHECKING:
    from cncc.frontend.linuxcnc.executor import Frame, LinuxcncExecutor

CYCLE_CODES = frozenset({700, 710, 711, 712, 720, 721, 722})  # G code tenths
_CYCLE_ONLY = frozenset("QDEIJKRPLUWH")  # words of the cycle, not of its rapid to X/Z
# rs274's check_items texts for a word the G7x block does not use (G70 reads D E P Q, G71/G72 D I Q R)
_NO_USE = {
    "E": "E word with no G70, G76, M66, M67 or M68 to use it",
    "I": "I word with no G2, G3, G5, G5.1, G10, G33.1, G76, or G87 to use it",
    "J": "J word with no G2, G3, G5, G5.1, G10, G76 or G87 to use it",
    "K": "K word with no G2, G3, G33, G33.1, G76, or G87 to use it",
    "H": "H word with no G43 or G76 to use it",
    "L": "L word with no G10, cutter compensation, canned cycle, digital/analog input, M98 or NURBS code",
    "P": "P word with no G2 G3 G4 G10 G64 G5 G5.2 G76 G82 G86 G88 G89 or M50 M51 M52 M53 M62 M63 M64 M65 M66 M98 "
         "or user M code to use it",
    "R": "R word with no g code that uses it",
}
EQUAL = 1e-4  # rs274's TOLERANCE_EQUAL: an arc to where the tool is is not written


def cycle_word(words: tuple[Word, ...]) -> Word | None:
    return next((w for w in words if w.letter == "G" and round(w.value * 10) in CYCLE_CODES), None)


def _value(words: tuple[Word, ...], letter: str) -> float | None:
    return next((w.value for w in words if w.letter == letter), None)


def _unused_word(words: tuple[Word, ...], cycle: int) -> tuple[Word, str] | None:
    """The first word the cycle does not read, with rs274's text (blocks with other codes that read it aside)."""
    if any(w.letter == "G" and round(w.value * 10) in (40, 100, 430, 640) for w in words) or any(
            w.letter == "M" for w in words):
        return None
    uses = "DEPQ" if cycle == 70 else "DIQR"
    return next(((w, _NO_USE[w.letter]) for w in words if w.letter in _NO_USE and w.letter not in uses), None)


def _refusal(ex: LinuxcncExecutor, span: Span, words: tuple[Word, ...], cycle: int, name: str) -> bool:
    """rs274's checks of the block before it moves (True: refused, the diagnostic is out)."""
    it = ex.it
    letters = [w.letter for w in words if w.letter not in "GM"]
    bad: tuple[str, Word | None, str] | None = None
    twice = next((w for w in words if w.letter not in "GM" and letters.count(w.letter) > 1), None)
    axis_uw = next((w for w in words if w.letter in "UW"), None)  # rs274, like a lathe set-up, has no U/W axes
    unused = _unused_word(words, cycle)
    if twice is not None:
        bad = (dg.REPEATED_WORD, twice, f"Multiple {twice.letter.lower()} words on one line")
    elif axis_uw is not None:
        bad = (dg.SYNTAX, axis_uw, f"Bad character '{axis_uw.letter.lower()}' used")
    elif unused is not None:
        bad = (dg.LATHE_CYCLE_WORDS, unused[0], unused[1])
    elif _value(words, "Q") is None:
        bad = (dg.LATHE_CYCLE_WORDS, None, "G7x.x  requires a Q word")
    elif it.frame.comp_side is not CompSide.OFF and cycle != 70:
        bad = (dg.LATHE_CYCLE_STATE, None, f"{name} cannot be used with cutter compensation enabled")
    elif it.frame.plane is not Plane.ZX:
        bad = (dg.LATHE_CYCLE_STATE, None, f"{name} can only be used in XZ plane (G18)")
    if bad is None:
        return False
    code, word, message = bad
    ex.fail(code, span if word is None else Span(span.source_id, word.start, word.end), message)
    return True


def _number(words: tuple[Word, ...], letter: str, default: float) -> float:
    v = _value(words, letter)
    return default if v is None else v


def run_g7x(ex: LinuxcncExecutor, fr: Frame, block: Block, words: tuple[Word, ...], g: Word) -> None:
    """Check the block as rs274 does, read the Q profile, then cut it (:mod:`g7x_run`)."""
    from cncc.frontend.linuxcnc.g7x_run import cut

    span = fr.index.span(block)
    cycle, sub = divmod(round(g.value * 10), 10)
    if _refusal(ex, span, words, cycle, f"G{cycle}.{sub}"):
        return
    if cycle != 70 and _number(words, "I", 1.0) <= 0:
        ex.fail(dg.LATHE_CYCLE_WORDS, span, "G7X error: I must be greater than zero.")
        return
    cut(ex, fr, span, words, cycle, sub)
