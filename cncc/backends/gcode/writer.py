"""The G-code writer's state and its words: numbers, blocks, positions and feeds.

:class:`BlockWriter` holds what the output has in force (units, plane, feed, the written position in
output counts, the axes whose position the output does not know) and makes blocks, axis words and F
words from it.  The frame synchronisation (:mod:`cncc.backends.gcode.frame_sync`), the mode and probe
commands (:mod:`cncc.backends.gcode.modes`) and the motion emitter (:mod:`cncc.backends.gcode.emit`)
build on it, in that order (each imports only the ones before it).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass

from cncc import diagnostics as dg
from cncc.backends.gcode.frames import TargetFrame, add
from cncc.backends.gcode.numbers import counts_text, fixed, quantize
from cncc.backends.gcode.target import Target, make_target
from cncc.diagnostics import DiagnosticSink
from cncc.dialects import Dialect
from cncc.ir import (
    Arc,
    Command,
    Cycle,
    Frame,
    HoldAxes,
    Linear,
    Plane,
    Rapid,
    Units,
    Vec6,
)
from cncc.ir.frame import Mirror, Rotation, Scaling
from cncc.source import NO_SPAN, Span

AXES = "XYZABC"
ANGLE_DECIMALS = 4
ROTATION_DECIMALS = 6  # G68 R: 1e-6 degrees is 0.02 um at 1 m


@dataclass(frozen=True, slots=True)
class EmitOptions:
    decimals_mm: int | None = None  # None: the target's default (3)
    decimals_inch: int | None = None  # None: the target's default (4)
    line_numbers: bool = False
    line_step: int = 10
    units: str = ""  # "" as programmed, "mm" or "inch": convert
    same_dialect: bool = True  # M codes without a known meaning are copied only within one dialect
    expand_cycle: Callable[[Cycle], Iterable[Command]] | None = None  # for cycles the output cannot keep
    keep_subprograms: bool = False  # mark call boundaries for cncc.backends.gcode.subprograms
    # A whole program (the machine starts anywhere: every axis's first word is written, and G91 moves of
    # axes not positioned yet stay G91) rather than a selection whose first position is known.
    from_program_start: bool = False


class BlockWriter:
    """The output in force and the words made from it (the base of the G-code emitter)."""

    def __init__(self, dialect: Dialect, options: EmitOptions | None = None,
                 sink: DiagnosticSink | None = None) -> None:
        self.t: Target = make_target(dialect)
        self.opt = options or EmitOptions()
        self.sink = sink
        self.dec_mm = self.t.decimals_mm if self.opt.decimals_mm is None else self.opt.decimals_mm
        self.dec_inch = self.t.decimals_inch if self.opt.decimals_inch is None else self.opt.decimals_inch
        forced = {"mm": Units.MM, "inch": Units.INCH}.get(self.opt.units)
        self.forced = forced
        self.units = forced or (Units.INCH if dialect.default_units == "inch" else Units.MM)
        self.plane = Plane.XY
        self.feed: float | None = None
        self.tf = TargetFrame()
        self.fold: Vec6 | None = None
        self.qpos: list[int] | None = None  # last written position, in output counts
        self.written_mm: list[float] | None = None  # the position written before a unit change (output mm)
        self.offgrid: set[int] = set()  # axes where the tool is not at a writable number
        self.cycle_initial: int | None = None  # counts of the initial level while a cycle is active
        self.cycle_data: list[str] = []  # code and data words of the cycle in force
        self.cycle_return = ""
        self.n = 0
        self.span: Span = NO_SPAN
        self.warned: set[str] = set()
        self.calls: list[tuple[str, str, Span]] = []  # (program key, name, calling block) per marked call
        self.call_depth = 0  # inside marked calls: no N numbers (the bodies are compared as text)
        self.inc_words: tuple[list[str], list[str]] | None = None  # (absolute, incremental) axis words
        self.inc_poison = False  # the next block has no incremental form (cycles, unwritable starts)
        self.sync_poison = False  # blocks setting units and offsets have none either
        self.in_alt = False
        self.all_axes = False  # the next move writes X, Y and Z (the first move of a call)
        # axes the next move writes even when their written value does not change: the tool axis after a
        # tool length block (LinuxCNC and grbl shift the program position by the offset change at once, a
        # Fanuc-like target applies it with the next move; the written word means the same on both)
        self.restate: set[int] = set()
        self.start_shift_mm: Vec6 | None = None  # added to the next move's start (a tool length change)
        self.rotation: Rotation | None = None  # the G68 record the output has in force
        self.mirror: Mirror | None = None  # the G51.1 record the output has in force
        self.scaling: Scaling | None = None  # the G51 record the output has in force
        self.held: tuple[bool, ...] = (True,) * 6  # Frame.held_axes of the last motion (at the start: all)
        self.unknown: set[int] = set(range(6))  # axes the output has not given an absolute position yet
        self.inc_move = False  # the motion being written was programmed in G91
        self.g91_block = False  # ... and moves an unknown axis: its words are written as increments in G91
        self.g92_force: set[int] = set()  # axes of a G92 preset in the source: written even if unchanged
        self.probe: tuple[str, int] | None = None  # a G38.x marker: (target code or "", moves of it still to come)
        self.started = False  # the preamble is written
        # the output's last spindle block was M05 and nothing since can have turned it on: a further stop
        # (the one M02/M30 implies, which the front end spells out) is not written again
        self.spindle_stopped = False

    # ---- numbers --------------------------------------------------------------------------
    @property
    def decimals(self) -> int:
        return self.dec_inch if self.units is Units.INCH else self.dec_mm

    def counts(self, v_mm: float, axis: int = 0) -> int:
        if axis >= 3:
            return quantize(v_mm, ANGLE_DECIMALS)
        return quantize(v_mm / self.units.mm_per_unit, self.decimals)

    def text(self, counts: int, axis: int = 0) -> str:
        return counts_text(counts, ANGLE_DECIMALS if axis >= 3 else self.decimals)

    def length(self, v_mm: float) -> str:
        return self.text(self.counts(v_mm))

    # ---- blocks ------------------------------------------------------------------------------
    def block(self, words: list[str], comment: str = "") -> str:
        text = " ".join(w for w in words if w)
        note = self.t.comment(comment) if comment else ""
        if note:
            text = f"{text} {note}" if text else note
        if self.opt.line_numbers and text and not self.call_depth and not self.in_alt:
            self.n += self.opt.line_step
            if self.n > self.t.max_line_number:
                self.warn(dg.XL_LINE_NUMBER, f"N{self.n} is beyond {self.t.name}'s largest N{self.t.max_line_number}")
            text = f"N{self.n} {text}"
        if self.t.dialect.block_end and words:
            text += self.t.dialect.block_end
        self._check_length(text, words)
        if self.call_depth and not self.in_alt:  # the incremental form rides along (subprograms.py)
            from cncc.backends.gcode.subprograms import incremental_form

            alt = incremental_form(self, words, comment)
            return f"{text}\n{alt}"
        return text + "\n"

    def _check_length(self, text: str, words: list[str]) -> None:
        limit = self.t.max_line_length
        if not limit:
            return
        size = len("".join(words)) if self.t.count_words_only else len(text)
        if size > limit:
            self.warn(dg.XL_LINE_LENGTH, f"a line of {size} characters; {self.t.name} reads at most {limit}",
                      once=False)

    def warn(self, code: str, message: str, once: bool = True) -> None:
        """Report ``code`` at the current command (N08xx notes become errors under -Werror)."""
        if self.sink is None or (once and code in self.warned):
            return
        self.warned.add(code)
        severity = dg.Severity.ERROR if self.sink.werror and dg.CODES[code].severity is dg.Severity.NOTE else None
        self.sink.emit(code, self.span, message, severity=severity)

    def code(self, op: str, what: str = "") -> str:
        name = self.t.code(op)
        if not name and what:
            self.warn(dg.XL_NO_CODE, f"{self.t.name} has no code for {what}")
        return name

    def op_block(self, op: str, what: str, words: Iterable[str] = (), comment: str = "") -> str:
        """A block with ``op``'s code; a comment saying what is missing when the target has none."""
        name = self.code(op, what)
        if not name:
            return self.block([], f"{what}: no {self.t.name} code")
        return self.block([name, *words], comment)

    def _note_frame(self, cmd: Command) -> None:
        """The power-on work system, and the axes a cancel or an outside move left held."""
        tf = self.tf
        if tf.work_mm is None and cmd.frame.work_index == 1:  # the power-on G54 (before a G55 ... of the program)
            tf.work_mm = tf.work_tables.setdefault(1, cmd.frame.work_offset_mm)
        if True in cmd.frame.held_axes and not isinstance(cmd, Rapid | Linear | Arc):  # a cancel (a mode command)
            self.held = tuple(a or b for a, b in zip(self.held, cmd.frame.held_axes, strict=True))
        if isinstance(cmd, HoldAxes):  # moved outside the program (M06, G28, G53)
            self.unknown |= {k for k, h in enumerate(cmd.axes) if h}

    def _vector_words(self, v: Vec6) -> list[str]:
        return [f"{AXES[i]}{self.text(self.counts(v[i], i), i)}" for i in range(6) if i < 3 or v[i]]

    # ---- motion ------------------------------------------------------------------------------
    def _at(self, p: Vec6) -> list[int]:
        fold = self.fold or (0.0,) * 6
        return [self.counts(p[i] + fold[i], i) for i in range(6)]

    def _start_at(self, start: Vec6) -> list[int]:
        """The written position, taken from ``start`` after a frame or unit change.

        Axes whose position is not a number the output can write are remembered in
        ``offgrid`` until a word is written for them (a full circle there is split).
        """
        if self.qpos is None:
            fold = self.fold or (0.0,) * 6
            if self.start_shift_mm is not None:  # the target's position after a tool length block
                start, self.start_shift_mm = add(start, self.start_shift_mm), None
            self.qpos = self._at(start)
            was = self.written_mm
            self.written_mm = None
            # off the grid: the new units cannot write the position, or the target is not at it (the
            # numbers written in the old units rounded it differently, e.g. 0.0104 in for 0.264 mm)
            self.offgrid = {i for i in range(3)
                            if abs(self.qpos[i] * 10.0**-self.decimals * self.units.mm_per_unit
                                   - (start[i] + fold[i])) > 1e-9
                            or (was is not None and abs(was[i] - (start[i] + fold[i])) > 1e-9)}
        return self.qpos

    def _axes(self, start: Vec6, end: Vec6, always: tuple[int, ...] = ()) -> list[str]:
        """Words for the axes whose written value changes (the first plane axis for a null move)."""
        qpos = self._start_at(start)
        q = self._at(end)
        changed = [i for i in range(6) if q[i] != qpos[i] or i in always or i in self.restate
                   or (self.all_axes and i < 3)]
        self.all_axes = False
        self.restate = set()
        if not changed:  # a null move writes one word: of an axis whose position the output knows
            p = self.plane
            known = [i for i in (p.first, p.second, p.normal) if i not in self.unknown]
            changed = [known[0] if known else p.first]
            if not known and self.t.code("incremental") and not self.call_depth:
                self.g91_block = True  # X0 as an increment: no axis is known yet
        words = [f"{AXES[i]}{self.text(q[i], i)}" for i in changed]
        if self.g91_block:
            words = [f"{AXES[i]}{self.text(q[i] - qpos[i], i)}" for i in changed]
        if self.call_depth:
            self.inc_poison = bool(self.offgrid & set(changed))  # increments from an unwritable position
            self.inc_words = (words, [f"{AXES[i]}{self.text(q[i] - qpos[i], i)}" for i in changed])
        self.offgrid -= set(changed)
        if not self.inc_move:
            self.unknown -= set(changed)
        self.qpos = q
        return words

    def _feed_word(self, feed_mm_min: float) -> str:
        if self.feed is not None and abs(self.feed - feed_mm_min) <= 1e-9 * max(1.0, feed_mm_min):
            return ""
        self.feed = feed_mm_min
        return "F" + fixed(feed_mm_min / self.units.mm_per_unit, max(self.decimals, 3))

    def _check_increment(self, cmd: Rapid | Linear | Arc) -> None:
        """cncc writes G90 coordinates; a G91 move of an axis whose position is unknown (``self.unknown``: not
        written since the start, a tool change, a reference return or G53) goes from wherever the machine is."""
        f = cmd.frame
        self.inc_move = f.incremental
        if not f.incremental or not self.unknown:
            return
        moved = [k for k in sorted(self.unknown) if abs(cmd.end[k] - cmd.start[k]) > 1e-12]
        if not moved and self.plane.first in self.unknown and cmd.end == cmd.start:
            moved = [self.plane.first]  # a null G91 move: its word (X0) must stay an increment too
        if moved and self.t.code("incremental") and self.t.code("absolute") and not self.call_depth:
            self.g91_block = True  # written as a G91 block (then G90): the same motion from any start
        elif moved:
            axes = " ".join(AXES[k] for k in moved)
            self.warn(dg.XL_INCREMENT_UNKNOWN_START, f"G91 move of {axes} before the program gives {axes} an absolute "
                                                     "position: the translation's G90 coordinates assume where the "
                                                     "machine starts; program an absolute position first", once=False)

    def _g91(self, words: list[str]) -> Iterator[str]:
        if not self.g91_block:
            yield self.block(words)
            return
        self.g91_block = False
        yield self.block([self.t.code("incremental"), *words])
        yield self.block([self.t.code("absolute")])

    def _released(self, f: Frame) -> tuple[int, ...]:
        """Axes the source names absolutely again after a transform cancel kept them where the tool was
        (``Frame.held_axes``): written even when their program value did not change, or the target,
        which holds them as well, would leave them at the transformed point."""
        held, self.held = self.held, f.held_axes
        return tuple(k for k in range(6) if held[k] and not f.held_axes[k])
