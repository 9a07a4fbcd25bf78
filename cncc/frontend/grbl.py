"""grbl 1.1's block checks, run before the interpreter sees a block.

grbl rejects a whole line with ``error:N`` when anything in it is wrong, and runs
nothing of it.  :class:`GrblChecker` repeats its checks in grbl's order (the words
as they are read, then the modal and geometric checks of its parser's step 3) and
drops the block with one ``E0250`` diagnostic carrying grbl's number and reason.
The reasons for unsupported codes and addresses come from the dialect's
``[unsupported]`` table; the numeric limits from its ``[options]``.

Consumes syntax blocks and the interpreter's state (position, modes); produces the
blocks grbl would run.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable, Iterator
from dataclasses import dataclass

from cncc import diagnostics as dg
from cncc.frontend.interp import Interpreter
from cncc.frontend.syntax import Block, Word
from cncc.ir import Plane, Units
from cncc.source import SourceFile, Span

REASONS = {
    1: "Expected command letter", 2: "Bad number format", 4: "Value < 0", 11: "Line overflow",
    20: "Unsupported command", 21: "Modal group violation", 22: "Undefined feed rate",
    23: "Invalid gcode ID:23", 24: "Invalid gcode ID:24", 25: "Invalid gcode ID:25",
    26: "Invalid gcode ID:26", 27: "Invalid gcode ID:27", 28: "Invalid gcode ID:28",
    29: "Invalid gcode ID:29", 30: "Invalid gcode ID:30", 31: "Invalid gcode ID:31",
    32: "Invalid gcode ID:32", 33: "Invalid gcode ID:33", 34: "Invalid gcode ID:34",
    35: "Invalid gcode ID:35", 36: "Invalid gcode ID:36", 37: "Invalid gcode ID:37",
    38: "Invalid gcode ID:38",
}
"""grbl's short messages (its error_codes CSV)."""

_G_GROUP = {0: "G1", 1: "G1", 2: "G1", 3: "G1", 38: "G1", 80: "G1", 4: "G0", 10: "G0", 28: "G0", 30: "G0",
            53: "G0", 92: "G0", 17: "G2", 18: "G2", 19: "G2", 90: "G3", 91: "G3", 93: "G5", 94: "G5",
            20: "G6", 21: "G6", 40: "G7", 43: "G8", 49: "G8", 54: "G12", 55: "G12", 56: "G12",
            57: "G12", 58: "G12", 59: "G12", 61: "G13"}
_M_GROUP = {0: "M4", 1: "M4", 2: "M4", 30: "M4", 3: "M7", 4: "M7", 5: "M7", 7: "M8", 8: "M8", 9: "M8",
            56: "M9"}
_VALUE_LETTERS = "FIJKLNPRSTXYZ"
_STRIP = re.compile(r"\([^)]*\)?|;.*|\s+")


class Reject(Exception):
    """Internal: grbl's error ``number`` for ``word`` (or the whole block)."""

    def __init__(self, number: int, detail: str = "", word: Word | None = None) -> None:
        super().__init__(number)
        self.number, self.detail, self.word = number, detail, word


@dataclass(slots=True)
class _Parsed:
    words: dict[str, Word]
    groups: dict[str, tuple[int, int]]  # modal group -> (int value, mantissa)
    axis_command: str  # "", "motion", "non_modal", "tlo"
    axes: set[str]


class GrblChecker:
    """Filters a block stream as grbl 1.1 would."""

    def __init__(self, it: Interpreter, src: SourceFile) -> None:
        self.it = it
        self.src = src
        d = it.dialect
        self.max_chars = int(d.option("line_max_chars", 79))
        self.max_tool = int(d.option("max_tool_number", 255))
        self.max_line = int(d.option("max_line_number", 10_000_000))
        self.systems = int(d.option("n_coordinate_systems", 6))
        self.m7 = bool(d.option("enable_m7", True))
        self.m56 = bool(d.option("enable_m56", False))
        self.arc_limit_mm = float(d.option("arc_radius_limit_mm", 0.5))
        self.arc_abs_mm = float(d.option("arc_radius_tolerance_mm", 0.005))
        self.arc_rel = float(d.option("arc_radius_tolerance_rel", 0.001))
        self.lines_checked: set[int] = set()

    def filter(self, blocks: Iterable[Block]) -> Iterator[Block]:
        for block in blocks:
            try:
                self.check(block)
            except Reject as exc:
                self._report(block, exc)
                continue
            yield block

    def _report(self, block: Block, exc: Reject) -> None:
        w = exc.word
        span = Span(self.src.source_id, w.start, w.end) if w else Span(self.src.source_id, block.start, block.end)
        reason = REASONS.get(exc.number, "")
        text = f"grbl error:{exc.number} ({reason})" + (f": {exc.detail}" if exc.detail else "")
        self.it.sink.emit(dg.CONTROLLER_REJECTS, span, text + "; block not run")

    # ---- the checks ------------------------------------------------------------------------------
    def check(self, block: Block) -> None:
        if block.line not in self.lines_checked:
            self.lines_checked.add(block.line)
            line = self.src.text[block.start:block.end]
            if len(_STRIP.sub("", line)) > self.max_chars:
                raise Reject(11, f"more than {self.max_chars} characters without blanks and comments")
        if block.statements:
            st = block.statements[0]
            raise Reject(1, self._why("#", "no parameters or macro variables"),
                         Word("#", 0.0, False, st.start, st.end))
        p = self._read_words(block)
        self._modal_checks(p)

    def _why(self, key: str, default: str) -> str:
        reason = self.it.dialect.unsupported_reason(key) or default
        return reason.split(": ", 1)[1] if reason.startswith("error:") and ": " in reason else reason

    def _read_words(self, block: Block) -> _Parsed:
        p = _Parsed({}, {}, "", set())
        for w in block.words:
            if w.expr is not None:
                raise Reject(1, self._why("#", "no parameters or expressions"), w)
            if w.letter == "G":
                self._g_word(p, w)
            elif w.letter == "M":
                self._m_word(p, w)
            else:
                self._value_word(p, w)
        return p

    def _g_word(self, p: _Parsed, w: Word) -> None:
        iv = int(w.value)
        mant = round(100 * (w.value - iv))
        group = _G_GROUP.get(iv)
        if group is None:
            raise Reject(20, self._code_reason("G", w.value), w)
        if (iv in (28, 30, 92) and mant not in (0, 10)) or (iv == 38 and mant not in (20, 30, 40, 50)):
            raise Reject(20, self._code_reason("G", w.value), w)
        bad_fraction = {90: mant != 0, 91: mant not in (0, 10), 61: mant != 0, 43: mant != 10}
        if bad_fraction.get(iv, False):
            raise Reject(20, self._code_reason("G", w.value), w)
        if iv == 91 and mant == 10:
            group = "G4"
        elif mant and iv not in (28, 30, 92, 38, 43):
            raise Reject(23, self._code_reason("G", w.value, "the command needs an integer value"), w)
        kind = ("motion" if iv in (0, 1, 2, 3, 38) else "non_modal" if iv in (10, 28, 30, 92) and mant == 0
                else "tlo" if iv in (43, 49) else "")
        if kind:
            if p.axis_command:
                raise Reject(24, "more than one command that uses axis words", w)
            p.axis_command = kind
        if group in p.groups:
            raise Reject(21, "two commands of one modal group", w)
        p.groups[group] = (iv, mant)

    def _code_reason(self, letter: str, value: float, default: str = "") -> str:
        tenths = round(value * 10)
        reason = self.it.dialect.unsupported_reason(letter, tenths) if abs(value * 10 - tenths) < 1e-6 else None
        if reason is None:
            return default or f"{letter}{value:g} is not a grbl command"
        return reason.split(": ", 1)[1] if ": " in reason else reason

    def _m_word(self, p: _Parsed, w: Word) -> None:
        iv = int(w.value)
        if w.value != iv:
            raise Reject(23, "M codes take integer values", w)
        group = _M_GROUP.get(iv)
        if group is None or (iv == 7 and not self.m7) or (iv == 56 and not self.m56):
            raise Reject(20, self._code_reason("M", w.value), w)
        if group in p.groups:
            raise Reject(21, "two commands of one modal group", w)
        p.groups[group] = (iv, 0)

    def _value_word(self, p: _Parsed, w: Word) -> None:
        letter = w.letter
        if letter not in _VALUE_LETTERS:
            raise Reject(20, self._why(letter, f"no {letter} word"), w)
        if letter in p.words:
            raise Reject(25, f"{letter} appears twice", w)
        if letter in "FNPTS" and w.value < 0:
            raise Reject(4, f"{letter} must not be negative", w)
        if letter == "T" and w.value > self.max_tool:
            raise Reject(38, f"tool number above {self.max_tool}", w)
        p.words[letter] = w
        if letter in "XYZ":
            p.axes.add(letter)

    # ---- step 3 of grbl's parser: the modal and geometric checks -----------------------------------
    def _modal_checks(self, p: _Parsed) -> None:
        words, groups = p.words, p.groups
        if p.axes and not p.axis_command:
            p.axis_command = "motion"
        nw = words.get("N")
        if nw is not None and nw.value > self.max_line:
            raise Reject(27, "line number out of range", nw)
        inverse = groups.get("G5", (93 if self._inverse() else 94, 0))[0] == 93
        motion = groups.get("G1", (self._motion_number(), 0))
        used = set("NFST")
        non_modal = groups.get("G0")
        if non_modal is not None:
            self._non_modal(p, non_modal, motion, used)
        if groups.get("G8", (0, 0))[0] == 43 and p.axes != {"Z"}:
            raise Reject(37, "G43.1 takes exactly the Z word")
        if motion[0] == 80:
            if p.axes:
                raise Reject(31, "axis words while no motion mode is in force (G80)")
        elif p.axis_command == "motion":
            used |= self._motion_checks(p, motion, inverse)
        if p.axis_command:
            used |= set("XYZ")
        unused = [w for k, w in words.items() if k not in used]
        if unused:
            raise Reject(36, f"{unused[0].letter} is not used by any command of the block", unused[0])

    def _non_modal(self, p: _Parsed, nm: tuple[int, int], motion: tuple[int, int], used: set[str]) -> None:
        code, mant = nm
        words = p.words
        if code == 4:
            if "P" not in words:
                raise Reject(28, "G4 needs P (seconds)")
            used.add("P")
        elif code == 10:
            if "L" not in words or "P" not in words:
                raise Reject(28, "G10 needs L and P")
            if int(words["L"].value) not in (2, 20):
                raise Reject(20, "only G10 L2 and G10 L20", words["L"])
            if int(words["P"].value) > self.systems:
                raise Reject(29, f"work coordinate system P{int(words['P'].value)} does not exist", words["P"])
            if not p.axes:
                raise Reject(26, "G10 needs axis words")
            used |= {"L", "P"}
        elif code == 92 and mant == 0 and not p.axes:
            raise Reject(26, "G92 needs axis words")
        elif code == 53 and motion[0] not in (0, 1):
            raise Reject(30, "G53 works only with G0 and G1")

    def _motion_checks(self, p: _Parsed, motion: tuple[int, int], inverse: bool) -> set[str]:
        code = motion[0]
        words = p.words
        if code == 0:
            return set()
        feed = words["F"].value if "F" in words else (0.0 if inverse else (self.it.modal.feed or 0.0))
        if feed == 0.0:
            raise Reject(22, "inverse time mode (G93) needs F in every feed block" if inverse
                         else "no feed rate programmed yet")
        if code in (2, 3):
            return self._arc_checks(p, code == 2)
        if code == 38 and self._target(p) == self.it.pos[:3]:
            raise Reject(33, "the probe target is the current position")
        return set()

    def _plane_axes(self, p: _Parsed) -> tuple[int, int, str, str]:
        plane = self.it.frame.plane if "G2" not in p.groups else {17: Plane.XY, 18: Plane.ZX, 19: Plane.YZ}[
            p.groups["G2"][0]]
        a0, a1 = plane.first, plane.second
        return a0, a1, "XYZ"[a0], "XYZ"[a1]

    def _arc_checks(self, p: _Parsed, clockwise: bool) -> set[str]:
        words = p.words
        if not p.axes:
            raise Reject(26, "an arc needs axis words")
        a0, a1, l0, l1 = self._plane_axes(p)
        if l0 not in p.axes and l1 not in p.axes:
            raise Reject(32, f"an arc needs {l0} or {l1} in the plane")
        start, end = self.it.pos, self._target(p)
        x, y = end[a0] - start[a0], end[a1] - start[a1]
        mm = self._mm_per_unit(p)
        if "R" in words:
            if end == start[:3]:
                raise Reject(33, "an R arc cannot end where it starts")
            r = words["R"].value * mm
            if 4 * r * r - x * x - y * y < 0:
                raise Reject(34, "the radius is less than half the distance to the end point", words["R"])
            return {"R"}
        o0, o1 = "IJK"[a0], "IJK"[a1]
        if o0 not in words and o1 not in words:
            raise Reject(35, f"an arc needs {o0} or {o1} in the plane")
        i = words[o0].value * mm if o0 in words else 0.0
        j = words[o1].value * mm if o1 in words else 0.0
        r = math.hypot(i, j)
        delta_r = abs(math.hypot(x - i, y - j) - r)
        if delta_r > self.arc_abs_mm and (delta_r > self.arc_limit_mm or delta_r > self.arc_rel * r):
            raise Reject(33, f"start and end radius differ by {delta_r:.4f} mm")
        return {"I", "J", "K"}

    # ---- state ------------------------------------------------------------------------------------
    def _mm_per_unit(self, p: _Parsed) -> float:
        units = p.groups.get("G6")
        if units is None:
            return self.it.frame.units.mm_per_unit
        return Units.INCH.mm_per_unit if units[0] == 20 else 1.0

    def _target(self, p: _Parsed | None = None) -> tuple[float, ...]:
        pos = list(self.it.pos[:3])
        if p is None:
            return tuple(pos)
        mm = self._mm_per_unit(p)
        incremental = p.groups.get("G3", (91 if self.it.modal.incremental else 90, 0))[0] == 91
        for k, letter in enumerate("XYZ"):
            w = p.words.get(letter)
            if w is not None:
                pos[k] = pos[k] + w.value * mm if incremental else w.value * mm
        return tuple(pos)

    def _inverse(self) -> bool:
        return self.it.modal.path.inverse_time

    def _motion_number(self) -> int:
        return {"rapid": 0, "linear": 1, "arc_cw": 2, "arc_ccw": 3, "none": 80}.get(self.it.modal.motion, 0)
