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
from cncc.frontend.linuxcnc.builder import oword_of
from cncc.frontend.linuxcnc.g7x_path import Path
from cncc.frontend.linuxcnc.g7x_segments import ProfileError, Round, Segment, Straight, corner
from cncc.frontend.syntax import Block, Word
from cncc.ir import CompSide, Plane
from cncc.source import Span

if TYPE_CHECKING:
    from cncc.frontend.linuxcnc.executor import Frame, LinuxcncExecutor

CYCLE_CODES = frozenset({700, 710, 711, 712, 720, 721, 722})  # G code tenths
_CYCLE_ONLY = frozenset("QDEIJKRPLUWAC")  # words of the cycle, not of its rapid to X/Z
EQUAL = 1e-4  # rs274's TOLERANCE_EQUAL: an arc to where the tool is is not written


def cycle_word(words: tuple[Word, ...]) -> Word | None:
    return next((w for w in words if w.letter == "G" and round(w.value * 10) in CYCLE_CODES), None)


def _value(words: tuple[Word, ...], letter: str) -> float | None:
    return next((w.value for w in words if w.letter == letter), None)


def _program_units(mm: float, k: float) -> float:
    """A position in the program's unit.  cncc keeps positions in mm; rs274 keeps the inch value it read, so an
    inch position is rounded back to it (a one-segment profile's offset side hangs on the last bit)."""
    return mm if k == 1.0 else round(mm / k, 10)


def run_g7x(ex: LinuxcncExecutor, fr: Frame, block: Block, words: tuple[Word, ...], g: Word) -> None:  # noqa: C901 - split by its owner (lathe)
    it = ex.it
    span = fr.index.span(block)
    cycle, sub = divmod(round(g.value * 10), 10)
    name = f"G{cycle}.{sub}"
    letters = [w.letter for w in words if w.letter not in "GM"]
    twice = next((w for w in words if w.letter not in "GM" and letters.count(w.letter) > 1), None)
    if twice is not None:
        ex.fail(dg.REPEATED_WORD, Span(span.source_id, twice.start, twice.end),
                f"Multiple {twice.letter.lower()} words on one line")
        return
    axis_uw = next((w for w in words if w.letter in "UW"), None)
    if axis_uw is not None:  # rs274 (and a lathe configuration) has no U/W axes; the profile may use U/W
        ex.fail(dg.SYNTAX, Span(span.source_id, axis_uw.start, axis_uw.end),
                f"Bad character '{axis_uw.letter.lower()}' used")
        return
    q = _value(words, "Q")
    if q is None:
        ex.fail(dg.LATHE_CYCLE_WORDS, span, "G7x.x  requires a Q word")
        return
    if it.frame.comp_side is not CompSide.OFF and cycle != 70:
        ex.fail(dg.LATHE_CYCLE_STATE, span, f"{name} cannot be used with cutter compensation enabled")
        return
    if it.frame.plane is not Plane.ZX:
        ex.fail(dg.LATHE_CYCLE_STATE, span, f"{name} can only be used in XZ plane (G18)")
        return
    k = it.frame.units.mm_per_unit
    tenths = [round(w.value * 10) for w in words if w.letter == "G"]
    incremental = 910 in tenths or (it.modal.incremental and 900 not in tenths)  # the block's own G90/G91 first
    x, z = _program_units(it.pos[0], k), _program_units(it.pos[2], k)
    xw, zw = _value(words, "X"), _value(words, "Z")
    if xw is not None:
        x = x + xw if incremental else xw
    if zw is not None:
        z = z + zw if incremental else zw
    # The rapid to X/Z (rs274 writes it even without axis words), with the block's other words.
    rapid = tuple(Word("G", 0.0, False, w.start, w.end) if w is g else w for w in words
                  if w.letter not in _CYCLE_ONLY)
    errors = ex.sink.errors
    if not any(w.letter in "XYZABC" for w in rapid):
        rapid += (Word("X", it.pos[0] / k if incremental else x, True, g.start, g.end),)
        if incremental:
            rapid = tuple(w if w.letter != "X" else Word("X", 0.0, True, g.start, g.end) for w in rapid)
    ex._run_words(block, rapid, ())
    if ex.sink.errors > errors:
        return
    label = str(round(q))
    profile = _collect(ex, fr, span, label, complex(z, x), incremental)
    if profile is None or len(profile) <= 1:
        return
    d = _value(words, "D") or 0.0
    e = _value(words, "E") or 0.0
    i = _value(words, "I")
    i = 1.0 if i is None else i
    p = _value(words, "P")
    p = 1.0 if p is None else p
    r = _value(words, "R")
    r = 0.5 if r is None else r
    if i <= 0:
        ex.fail(dg.LATHE_CYCLE_WORDS, span, "G7X error: I must be greater than zero.")
        return
    out = _Emitter(ex, block, g, complex(it.pos[2] / k, it.pos[0] / k))
    path = Path(profile)
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
    try:
        while len(ex.stack) > depth and not ex.stopped:
            top = ex.stack[-1]
            if top.pc >= len(top.index.blocks):
                ex._fell_off(top)
                continue
            b = top.index.blocks[top.pc]
            if oword_of(b.statements) is None and not b.words and not b.statements:
                top.pc += 1
                continue
            ex._step(top)
    finally:
        ex.capture = None
    while len(ex.stack) > depth:  # an error stopped the subroutine
        ex.stack.pop()
    if ex.stopped:
        return None
    return _profile(ex, taken, start, incremental)


def _profile(ex: LinuxcncExecutor, taken: list[tuple[Span, tuple[Word, ...]]], start: complex,  # noqa: C901
             incremental: bool) -> list[Segment] | None:
    from cncc.frontend.linuxcnc.lathe import diameter_mode
    from cncc.frontend.rs274 import state

    it = ex.it
    arc_incremental = not state(it).arc_absolute
    motion = {"rapid": 0, "linear": 1, "arc_cw": 2, "arc_ccw": 3}.get(it.modal.motion, -1)
    segs: list[Segment] = []
    for span, words in taken:
        got = {w.letter: w.value for w in words}
        end = 0j if incremental else start
        if "U" in got:
            if incremental:
                _bad(ex, span, "G7x error: Cannot use U in incremental mode (G91)")
                return None
            if "X" in got:
                _bad(ex, span, "G7x error: Cannot use U and X in the same block")
                return None
            end += 1j * (got["U"] / 2 if diameter_mode(it) else got["U"])
        elif "X" in got:
            end = complex(end.real, got["X"])
        if "W" in got:
            if incremental:
                _bad(ex, span, "G7x error: Cannot use W in incremental mode (G91)")
                return None
            if "Z" in got:
                _bad(ex, span, "G7x error: Cannot use W and Z in the same block")
                return None
            end += got["W"]
        elif "Z" in got:
            end = complex(got["Z"], end.imag)
        centre = complex(got.get("K", 0.0), got.get("I", 0.0))
        if incremental:
            end += start
        gm = [round(w.value * 10) for w in words if w.letter == "G" and round(w.value * 10) in (0, 10, 20, 30)]
        if gm:
            motion = gm[-1] // 10
        if end == start:
            continue
        if motion in (0, 1):
            segs.append(Straight(start, end))
        elif motion in (2, 3):
            arc = _arc(ex, span, got, start, end, centre, motion == 3, arc_incremental)
            if arc is None:
                return None
            segs.append(arc)
        else:
            continue
        if "A" in got and "C" in got:
            _bad(ex, span, "G7X error: Both A and C parameters on a corner")
            return None
        for letter in "AC":
            if letter in got:
                segs.append(corner(letter, got[letter], end))
        start = end
    return segs


def _arc(ex: LinuxcncExecutor, span: Span, got: dict[str, float], start: complex, end: complex, centre: complex,
         ccw: bool, arc_incremental: bool) -> Round | None:
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
