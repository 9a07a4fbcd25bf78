"""LinuxCNC's lathe cycles G70 (finishing) and G71/G71.1/G71.2, G72/G72.1/G72.2 (roughing).

``G71 Q- <X-> <Z-> <D-> <I-> <R->`` (LinuxCNC 2.9, ``interp_g7x.cc``): a rapid to X/Z,
then the subroutine ``oQ`` is run to collect the profile (its G0-G3 moves with X/Z, U/W
increments, I/K or R centres and A fillets / C chamfers; everything else in it is
ignored), then the profile is cut (:mod:`cncc.frontend.linuxcnc.g7x_path`).  The cut is
lowered to plain G0/G1/G2/G3 blocks run through the shared interpreter in absolute
distance and arc-centre modes (as LinuxCNC's ``switch_settings`` does), so the IR holds
nothing but moves: every back end, translations included, writes them as moves.

Errors, each with LinuxCNC's text: no Q, a plane other than G18, cutter compensation
(G71/G72), no subroutine oQ, I not above zero, a profile that is not monotonic.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from cncc import diagnostics as dg
from cncc.frontend.linuxcnc.g7x_path import Path
from cncc.frontend.linuxcnc.g7x_segments import ProfileError, Round, Segment, Straight, corner
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


def _program_units(mm: float, k: float) -> float:
    """A position in the program's unit.  cncc keeps positions in mm; rs274 keeps the inch value it read, so an
    inch position is rounded back to it (a one-segment profile's offset side hangs on the last bit)."""
    return mm if k == 1.0 else round(mm / k, 10)


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


def _start(ex: LinuxcncExecutor, words: tuple[Word, ...]) -> tuple[complex, bool]:
    """The cycle's start point (Z + X*1j, program units) and whether the block is in G91."""
    it = ex.it
    k = it.frame.units.mm_per_unit
    tenths = [round(w.value * 10) for w in words if w.letter == "G"]
    incremental = 910 in tenths or (it.modal.incremental and 900 not in tenths)  # the block's own G90/G91 first
    x, z = _program_units(it.pos[0], k), _program_units(it.pos[2], k)
    xw, zw = _value(words, "X"), _value(words, "Z")
    if xw is not None:
        x = x + xw if incremental else xw
    if zw is not None:
        z = z + zw if incremental else zw
    return complex(z, x), incremental


def _rapid(ex: LinuxcncExecutor, block: Block, words: tuple[Word, ...], g: Word, incremental: bool) -> bool:
    """The rapid to the block's X/Z with its other words (rs274 writes it even without axis words); False after
    an error."""
    it = ex.it
    k = it.frame.units.mm_per_unit
    rapid = tuple(Word("G", 0.0, False, w.start, w.end) if w is g else w for w in words
                  if w.letter not in _CYCLE_ONLY)
    if not any(w.letter in "XYZABC" for w in rapid):
        rapid += (Word("X", 0.0 if incremental else it.pos[0] / k, True, g.start, g.end),)
    errors = ex.sink.errors
    ex._run_words(block, rapid, ())
    return ex.sink.errors == errors


def _number(words: tuple[Word, ...], letter: str, default: float) -> float:
    v = _value(words, letter)
    return default if v is None else v


def run_g7x(ex: LinuxcncExecutor, fr: Frame, block: Block, words: tuple[Word, ...], g: Word) -> None:
    it = ex.it
    span = fr.index.span(block)
    cycle, sub = divmod(round(g.value * 10), 10)
    if _refusal(ex, span, words, cycle, f"G{cycle}.{sub}"):
        return
    start, incremental = _start(ex, words)
    if not _rapid(ex, block, words, g, incremental):
        return
    profile = _collect(ex, fr, span, str(round(_number(words, "Q", 0.0))), start, incremental)
    if profile is None or len(profile) <= 1:
        return
    d, e, i = _number(words, "D", 0.0), _number(words, "E", 0.0), _number(words, "I", 1.0)
    p, r = _number(words, "P", 1.0), _number(words, "R", 0.5)
    if i <= 0:
        ex.fail(dg.LATHE_CYCLE_WORDS, span, "G7X error: I must be greater than zero.")
        return
    k = it.frame.units.mm_per_unit
    out = _Emitter(ex, block, g, complex(it.pos[2] / k, it.pos[0] / k))
    path = Path(profile)
    x, z = start.imag, start.real
    try:
        if cycle == 70:
            path.g70(out, x, z, d, e, p)
        else:
            path.g71(out, sub, x, z, 0.0, 0.0, d, i, r, rotate=cycle == 72)
    except ProfileError as exc:
        ex.fail(dg.LATHE_PROFILE, span, f"G7X error: {exc}")
    except _Stopped:
        return


class _Stopped(Exception):
    """A move of the cycle failed (its diagnostic is out): stop the cycle."""


class _Emitter:
    """Runs the cycle's moves as absolute G0/G1/G2/G3 blocks of the shared interpreter."""

    def __init__(self, ex: LinuxcncExecutor, block: Block, g: Word, at: complex) -> None:
        self.ex, self.block, self.g, self.at = ex, block, g, at

    def _run(self, code: float, end: complex, centre: complex | None = None) -> None:
        from cncc.frontend.rs274 import state

        ex, g = self.ex, self.g
        it = ex.it
        words = [Word("G", code, False, g.start, g.end), Word("X", end.imag, True, g.start, g.end),
                 Word("Z", end.real, True, g.start, g.end)]
        if centre is not None:
            words += [Word("I", centre.imag, True, g.start, g.end), Word("K", centre.real, True, g.start, g.end)]
        st = state(it)
        saved = (it.modal, st.arc_absolute)
        it.modal = it.modal.with_(incremental=False)
        st.arc_absolute = True
        errors = ex.sink.errors
        b = self.block
        try:
            ex.out.extend(it.execute(Block(b.line, b.start, b.end, tuple(words))))
        finally:
            it.modal = it.modal.with_(incremental=saved[0].incremental)
            st.arc_absolute = saved[1]
        self.at = end
        if ex.sink.errors > errors:
            ex.stopped = True
            raise _Stopped

    def straight_move(self, end: complex) -> None:
        self._run(1.0, end)

    def straight_rapid(self, end: complex) -> None:
        self._run(0.0, end)

    def circular_move(self, ccw: bool, center: complex, end: complex) -> None:
        if abs(self.at.real - end.real) < EQUAL and abs(self.at.imag - end.imag) < EQUAL:
            return
        self._run(3.0 if ccw else 2.0, end, center)


def _collect(ex: LinuxcncExecutor, fr: Frame, span: Span, label: str, start: complex,
             incremental: bool) -> list[Segment] | None:
    """Run subroutine ``o<label>`` collecting its moves as profile segments (None after an error)."""
    found = fr.index.subs.get(label)
    index = fr.index
    if found is None:
        loaded = ex.load_sub(label)
        if loaded is None or label not in loaded.subs:
            ex.fail(dg.OWORD_NO_SUB, span, f"G7x Q{label}: there is no subroutine o{label}", label)
            return None
        index, found = loaded, loaded.subs[label]
    depth = len(ex.stack)
    ex.push_scope([])
    ex.stack.append(type(fr)(index, found[0] + 1, label, fr.pc, fr, span))  # executor.Frame: no import circle
    taken: list[tuple[Span, tuple[Word, ...]]] = []
    ex.capture = taken
    steps = 0
    try:
        while len(ex.stack) > depth and not ex.stopped:
            top = ex.stack[-1]
            if top.pc >= len(top.index.blocks):
                ex._fell_off(top)
                continue
            steps += 1
            if steps > ex.max_steps:  # an endless loop in the profile subroutine
                ex.fail(dg.MACRO_STEP_BUDGET, span, f"the profile o{label} stopped after {ex.max_steps} blocks "
                        "(an endless loop?)")
                break
            ex._step(top)
    finally:
        ex.capture = None
    while len(ex.stack) > depth:  # an error stopped the subroutine
        ex.stack.pop()
    if ex.stopped:
        return None
    return _profile(ex, taken, start, incremental)


def _end_point(ex: LinuxcncExecutor, span: Span, got: dict[str, float], start: complex,
               incremental: bool) -> complex | None:
    """The end of a profile move: X/Z, or U/W increments (U a diameter in G7); None after an error."""
    from cncc.frontend.linuxcnc.lathe import diameter_mode

    end = 0j if incremental else start
    for inc, ax in (("U", "X"), ("W", "Z")):
        if inc in got:
            if incremental:
                _bad(ex, span, f"G7x error: Cannot use {inc} in incremental mode (G91)")
                return None
            if ax in got:
                _bad(ex, span, f"G7x error: Cannot use {inc} and {ax} in the same block")
                return None
            step = got[inc] / 2 if inc == "U" and diameter_mode(ex.it) else got[inc]
            end += 1j * step if inc == "U" else step
        elif ax in got:
            end = complex(end.real, got[ax]) if ax == "X" else complex(got[ax], end.imag)
    return end + start if incremental else end


def _profile(ex: LinuxcncExecutor, taken: list[tuple[Span, tuple[Word, ...]]], start: complex,
             incremental: bool) -> list[Segment] | None:
    """The segments of the collected moves (rs274's reading of the profile); None after an error."""
    from cncc.frontend.rs274 import state

    it = ex.it
    arc_incremental = not state(it).arc_absolute
    motion = {"rapid": 0, "linear": 1, "arc_cw": 2, "arc_ccw": 3}.get(it.modal.motion, -1)
    segs: list[Segment] = []
    for span, words in taken:
        got = {w.letter: w.value for w in words}
        end = _end_point(ex, span, got, start, incremental)
        if end is None:
            return None
        gm = [round(w.value * 10) for w in words if w.letter == "G" and round(w.value * 10) in (0, 10, 20, 30)]
        motion = gm[-1] // 10 if gm else motion
        if end == start or motion not in (0, 1, 2, 3):
            continue
        seg = Straight(start, end) if motion < 2 else _arc(ex, span, got, start, end, motion == 3, arc_incremental)
        if seg is None:
            return None
        segs.append(seg)
        if "A" in got and "C" in got:
            _bad(ex, span, "G7X error: Both A and C parameters on a corner")
            return None
        segs += [corner(letter, got[letter], end) for letter in "AC" if letter in got]
        start = end
    return segs


def _arc(ex: LinuxcncExecutor, span: Span, got: dict[str, float], start: complex, end: complex, ccw: bool,
         arc_incremental: bool) -> Round | None:
    centre = complex(got.get("K", 0.0), got.get("I", 0.0))
    if "R" in got:
        if "I" in got or "K" in got:
            _bad(ex, span, "G7X error: both R and I or K flag used for arc")
            return None
        r = got["R"]
        chord = end - start
        n2 = abs(chord) ** 2
        h2 = (r * r - n2 / 4) / n2
        if h2 < 0:  # rs274 2.9 takes the square root of a negative number here
            _bad(ex, span, "G7X error: the arc radius is smaller than half the chord")
            return None
        off = 1j * math.sqrt(h2) * chord
        centre = (start + end) / 2.0 + (off if ccw else -off)
    else:
        if "I" not in got and "K" not in got:
            _bad(ex, span, "G7X error: either I or K must be present for arc")
            return None
        if arc_incremental:
            centre += start
    return Round(start, end, ccw=ccw, center=centre)


def _bad(ex: LinuxcncExecutor, span: Span, message: str) -> None:
    """Report a profile block rs274 refuses; the caller then returns None (no profile)."""
    ex.fail(dg.LATHE_PROFILE, span, message)
    return None
