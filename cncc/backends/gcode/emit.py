"""G-code in a target dialect from IR commands (``--emit=gcode``, ``-t``, ``-E``).

Consumes IR commands in program coordinates (after the path passes: cycles the
target cannot keep expanded, transforms and cutter compensation applied); produces
program lines for the target, looked up by canonical op in its tables
(:mod:`cncc.backends.gcode.target`):

* one word order: G codes, axes, arc words, cycle words, F; every motion block
  names its motion code; absolute distances and feed per minute throughout (the IR
  has resolved G91 and per-revolution feeds);
* lengths always with a decimal point, so the least-input-unit rule never changes
  their meaning; quantised to the output precision (3 decimals in mm, 4 in inch);
* arcs in the forms the target reads (:mod:`cncc.backends.gcode.arcs`), the centre
  offsets computed from the written numbers so that they re-parse exactly;
* offsets the target cannot set are folded into the coordinates
  (:mod:`cncc.backends.gcode.frames`); canned cycles kept whole are written with the
  target's cycle codes (:mod:`cncc.backends.gcode.cycles`);
* a rotation, mirror or scaling record left in the frames (the target runs it,
  :mod:`cncc.backends.gcode.keep_transforms`) is written as G68 X Y R / G51.1 X Y /
  G51 X Y Z P (I J K; SZGH G36 R) when a command's frame gains it and G69 / G50.1 /
  G50 (G37) when it loses it; positions stay untransformed.

The output re-parses in the target dialect to the same motion
(``tests/backends/test_translate_roundtrip.py``).

This module is the motion emitter (program, moves, arcs, canned cycles); it builds on
:mod:`cncc.backends.gcode.modes` (mode, tool, stop, M-code and probe commands), which builds on
:mod:`cncc.backends.gcode.frame_sync` (units, plane, offsets, kept transforms), which builds on
:mod:`cncc.backends.gcode.writer` (the output's state, numbers, blocks and axis words).
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from cncc import diagnostics as dg
from cncc.backends.gcode import cycles as cy
from cncc.backends.gcode import patterns as pt
from cncc.backends.gcode.arcs import ARC_LETTERS, ArcForm, helix_feed_ratio, split
from cncc.backends.gcode.modes import ModeWriter
from cncc.backends.gcode.numbers import fixed
from cncc.backends.gcode.writer import AXES, EmitOptions
from cncc.diagnostics import DiagnosticSink
from cncc.dialects import Dialect
from cncc.ir import (
    MODE_TYPES,
    Arc,
    Aux,
    Command,
    Comment,
    Coolant,
    CoolantState,
    Cycle,
    Dwell,
    Frame,
    Linear,
    Message,
    OriginKind,
    Plane,
    Rapid,
    SelectTool,
    Spindle,
    SpindleSpeed,
    SpindleState,
    Stop,
    ToolChange,
    Units,
    Vec6,
    Wait,
)
from cncc.ir.batch import Item, MoveBatch, expand

__all__ = ["AXES", "EmitOptions", "GcodeEmitter", "emit_gcode"]

_SPINDLE_OPS = {SpindleState.CW: "spindle_cw", SpindleState.CCW: "spindle_ccw", SpindleState.OFF: "spindle_off",
                SpindleState.ORIENT: "spindle_orient"}
_COOLANT_OPS = {CoolantState.FLOOD: "coolant_flood", CoolantState.MIST: "coolant_mist",
                CoolantState.OFF: "coolant_off"}


class GcodeEmitter(ModeWriter):
    """IR commands to program lines in a target dialect: the program, motion, arcs and canned cycles."""

    # ---- program -------------------------------------------------------------------------------
    def emit(self, cmds: Iterable[Item]) -> Iterator[str]:
        if self.t.percent:
            yield "%\n"
        self.started = False
        for cmd in cmds:
            if isinstance(cmd, MoveBatch):  # a run of plain moves: written a segment at a time
                from cncc.backends.gcode.batch import batch_lines

                yield from batch_lines(self, cmd)
            else:
                yield from self.one(cmd)
        if not self.started:
            yield self._preamble(Frame(units=self.units))
        if self.t.percent:
            yield "%\n"

    def one(self, cmd: Command) -> Iterator[str]:
        """The lines of one command of the program (the preamble before the first)."""
        self.span = cmd.span
        if not self.started and not isinstance(cmd, Comment):  # the modes, in the first command's units
            self.started = True
            if not self.opt.from_program_start:  # a selection (editor) or IR built by hand: start known
                self.held = cmd.frame.held_axes
                self.unknown = {k for k in range(6) if cmd.frame.held_axes[k]}
            yield self._preamble(cmd.frame)
        yield from self._command(cmd)

    def _preamble(self, f: Frame) -> str:
        if self.forced is None:
            self.units = f.units
        return self.block([self.code("plane_xy"), self.code("inch" if self.units is Units.INCH else "metric"),
                           self.code("absolute"), self.code("feed_per_min")])

    def _command(self, cmd: Command) -> Iterator[str]:
        if self.probe is not None and isinstance(cmd, Linear):  # the moves after a G38.x marker
            return self._probe_move(cmd)
        return self._one_command(cmd)

    def _one_command(self, cmd: Command) -> Iterator[str]:
        self._note_frame(cmd)
        match cmd:
            case Rapid() | Linear() | Arc():
                self._check_increment(cmd)
                yield from self._sync(cmd.frame, cmd.start, cancel_cycle=True)
                yield from self._motion(cmd)
            case Cycle():
                yield from self._cycle(cmd)
            case Dwell():
                yield self.op_block("dwell", "a dwell", [self._dwell_word(cmd.seconds)])
            case SpindleSpeed():
                yield self.block([f"S{fixed(cmd.rpm, 3)}"])
            case SelectTool():
                yield self._select_tool(cmd)
            case Spindle():
                yield from self._spindle(cmd)
            case Coolant():
                yield self.op_block(_COOLANT_OPS[cmd.state], f"{cmd.state.value} coolant")
            case ToolChange():
                yield from self._tool_change(cmd)
            case Stop():
                yield from self._stop(cmd)
            case Comment():
                yield self.block([], cmd.text)
            case Message():
                stop = self.code("program_stop") if cmd.pause else ""
                yield self.block([stop], cmd.text)
            case Wait():
                yield self.op_block("program_stop", "a wait", comment=f"wait: {cmd.what}")
            case Aux():
                self.spindle_stopped = False  # a machine M code may start anything
                yield from self._aux(cmd)
            case _ if isinstance(cmd, MODE_TYPES):
                yield from self._mode(cmd)
            case _:
                pass

    def _spindle(self, cmd: Spindle) -> Iterator[str]:
        stop = cmd.state is SpindleState.OFF
        if not (stop and self.spindle_stopped):  # M02/M30's implied stop after an M05: not written twice
            yield self.op_block(_SPINDLE_OPS[cmd.state], f"spindle {cmd.state.value}")
        self.spindle_stopped = stop

    def _return_start(self, cmd: Rapid) -> Iterator[str]:
        """SZGH G26/G261-G264: back to where the program started, which the output cannot know.
        The target's own code where it has it (the moved axes are then unknown again), else E0861."""
        from cncc.dialects import code_tenths

        code = cmd.origin.code
        cdef = self.t.dialect.code(code[:1], code_tenths(code[1:]))
        if cdef is None or cdef.op != "return_start":
            self.warn(dg.XL_RETURN_START, f"{code} returns to the program's start point; {self.t.name} has "
                                          "no such code and a rapid to an assumed start would move elsewhere "
                                          "from any other start", once=False)
            return
        moved = {k for k in range(6) if cmd.end[k] != cmd.start[k]} or ({cdef.index - 1} if cdef.index else set())
        yield self.block([cdef.name])
        self.qpos = None
        self.unknown |= {k for k in moved if k < 3}

    def _motion(self, cmd: Rapid | Linear | Arc) -> Iterator[str]:
        match cmd:
            case Rapid() if cmd.origin.kind is OriginKind.RETURN_START:
                yield from self._return_start(cmd)
            case Rapid():
                yield from self._g91([self.t.code("rapid"),
                                      *self._axes(cmd.start, cmd.end, self._released(cmd.frame))])
            case Linear():
                words = [self.t.code("linear"), *self._axes(cmd.start, cmd.end, self._released(cmd.frame)),
                         self._feed_word(cmd.feed_mm_min)]
                yield from self._g91(words)
            case Arc():
                yield from self._arc(cmd)

    def _arc(self, a: Arc) -> Iterator[str]:
        t = self.t
        i, j = a.plane.first, a.plane.second
        self._start_at(a.start)
        closes = t.full_circle and not ({i, j} & self.offgrid)  # a full circle can end where it starts
        form = ArcForm(single_quadrant=t.single_quadrant, r_form=t.arc_form == "r", full_circle=closes,
                       turns_word=bool(t.turns_word),
                       min_piece_mm=max(10.0 ** (1 - self.decimals) * self.units.mm_per_unit,
                                        float(t.option("arc_ij_tolerance_mm", 0.0))))
        pieces = split(a.start, a.end, a.center, a.plane, a.turns, form)
        if len(pieces) > 1:
            self.warn(dg.XL_ARC_SPLIT, f"{t.name} output: an arc is written as {len(pieces)} pieces")
        projection = t.option("helix_feed", "projection") == "projection"
        code = t.code("arc_ccw" if a.turns > 0 else "arc_cw")
        n = a.plane.normal
        released = self._released(a.frame)
        g91 = self.g91_block
        for piece in pieces:
            offsets = self._centre_offsets(a, piece.start)
            rise_from = self._start_at(piece.start)[n]
            words = [code, *self._axes(piece.start, piece.end, always=(i, j, *released))]  # full circles too
            released = ()
            words += self._centre_words(a.plane, offsets, piece.sweep_rad, form)
            if piece.turns_extra:
                words.append(f"{t.turns_word}{piece.turns_extra + 1}")
            feed = a.feed_mm_min
            if projection:  # F of the projection, from the rise the target will see in this piece
                rise_mm = (self._start_at(piece.end)[n] - rise_from) * 10.0 ** -self.decimals * self.units.mm_per_unit
                feed *= helix_feed_ratio(piece.start, _with(piece.end, n, piece.start[n] + rise_mm), a.center,
                                         a.plane, 1 if a.turns > 0 else -1, piece.sweep_rad)
            words.append(self._feed_word(feed))
            yield self.block([self.t.code("incremental"), *words] if g91 and piece is pieces[0] else words)
        if g91:
            self.g91_block = False
            yield self.block([self.t.code("absolute")])

    def _centre_offsets(self, a: Arc, start: Vec6) -> tuple[int, int]:
        """Centre minus the tool's position in counts: from the written numbers where the tool is
        at one (so the centre re-parses to the written centre), else from the position itself."""
        fold = self.fold or (0.0,) * 6
        start_q = self._start_at(start)
        out = []
        for k in (a.plane.first, a.plane.second):
            if k in self.offgrid:
                out.append(self.counts(a.center[k] - start[k]))
            else:
                out.append(self.counts(a.center[k] + fold[k]) - start_q[k])
        return out[0], out[1]

    def _centre_words(self, plane: Plane, offsets: tuple[int, int], sweep_rad: float, form: ArcForm) -> list[str]:
        if form.r_form:
            import math

            sign = -1 if sweep_rad > math.pi else 1
            return [f"R{self.text(sign * round(math.hypot(*offsets)))}"]
        d1, d2 = offsets
        if form.single_quadrant:
            d1, d2 = abs(d1), abs(d2)
        l1, l2 = ARC_LETTERS[plane]
        return [f"{l1}{self.text(d1)}", f"{l2}{self.text(d2)}"]

    # ---- canned cycles -----------------------------------------------------------------------
    def _cycle(self, c: Cycle) -> Iterator[str]:
        problem = cy.keep_problem(c, self.t)
        if not problem and c.frame.incremental and self.unknown & {c.plane.first, c.plane.second, c.axis}:
            # the kept cycle's words are absolute: from a position the output does not know they would
            # assume where the machine starts, so the cycle is written as its moves (G91 blocks)
            problem = "an incremental cycle before its axes have a known position"
        if not problem:
            yield from self._sync(c.frame, c.start, cancel_cycle=False)
            n = c.axis
            fold = self.fold or (0.0,) * 6
            initial = self.counts(c.initial_mm + fold[n], n)
            if self.cycle_initial is not None and self.cycle_initial != initial:
                yield self.block([self.t.code("cycle_off")])
                self.cycle_initial = None
            self._start_at(c.start)
            assert self.qpos is not None
            if self.cycle_initial is None and self.qpos[n] != initial:
                problem = "the tool is not at the cycle's initial level"
        if problem:
            if self.opt.expand_cycle is None:
                self.warn(dg.XL_NO_CODE, f"canned cycle {c.code} cannot be written: {problem}")
                return
            for cmd in self.opt.expand_cycle(c):
                yield from self._command(cmd)
            return
        yield from self._cycle_blocks(c, initial)

    def _cycle_blocks(self, c: Cycle, initial: int) -> Iterator[str]:
        t, n = self.t, c.axis
        fold = self.fold or (0.0,) * 6
        first, second = c.plane.first, c.plane.second
        cdef = t.cycles[c.kind.value]
        ret = t.code("return_initial" if c.return_initial else "return_r")
        data = [cdef.name, f"{AXES[n]}{self.length(c.bottom_mm + fold[n])}", f"R{self.length(c.r_mm + fold[n])}",
                *self._cycle_extra(c, cdef.words)]
        same = self.cycle_initial is not None and data == self.cycle_data
        pattern = pt.pattern_block(c, t, self.units.mm_per_unit, self.decimals, fold) if c.pattern else None
        if c.pattern and pattern is None:
            self.warn(dg.XL_PATTERN, f"the {c.pattern} pattern is written as its {len(c.holes)} holes")
        if pattern is not None:  # the cycle data (K0: no hole), then the pattern block
            if not same or ret != self.cycle_return:
                rep = str(t.option("cycle_repeat_word", "K"))
                self.inc_poison = True
                yield self.block([ret, *data, self._feed_word(c.feed_mm_min), f"{rep}0"])
            self.inc_poison = True
            yield self.block(pattern)
        for k, hole in enumerate(() if pattern is not None else c.holes):
            self.inc_poison = True
            q = self._at(hole)
            here = self.qpos or q
            # a plane axis the source does not name (held: not positioned since the start or a cancel)
            # stays where the machine is: a word for it would assume that position (X0. from X13)
            words = [f"{AXES[a]}{self.text(q[a], a)}" for a in range(6)
                     if a != n and (q[a] != here[a] or (a in (first, second) and not c.frame.held_axes[a]))]
            if k > 0 and not words:  # a repeat at a held point: the depth word drills where the tool is
                words = [data[1]]
            if k == 0 and same:  # the cycle in force has this data: the hole, and G98/G99 if it changed
                words = [ret if ret != self.cycle_return else "", *words, self._feed_word(c.feed_mm_min)]
            elif k == 0:
                words = [ret, data[0], *words, *data[1:], self._feed_word(c.feed_mm_min)]
            self.qpos = q
            yield self.block(words)
        self.cycle_initial, self.cycle_data, self.cycle_return = initial, data, ret
        self.qpos = self._at(c.holes[-1])

    def _cycle_extra(self, c: Cycle, kinds: dict[str, str]) -> list[str]:
        words = []
        q = cy.q_value_mm(c)
        if q > 0:
            words.append(f"Q{self.length(q)}")
        if c.dwell_s > 0:
            unit_ms = self.t.option("cycle_dwell_unit", "s") == "ms" or kinds.get("P") == "time_ms"
            words.append(f"P{round(c.dwell_s * 1000)}." if unit_ms else f"P{fixed(c.dwell_s, 3)}")
        pitch = cy.needs_pitch_word(c, self.t)
        if pitch:
            words.append(f"{pitch}{self.length(c.tap_pitch_mm)}")
        return words


def emit_gcode(cmds: Iterable[Item], dialect: Dialect, options: EmitOptions | None = None,
               sink: DiagnosticSink | None = None) -> Iterator[str]:
    """Yield program lines (with newlines) for ``cmds`` (commands and batches of moves) in ``dialect``."""
    em = GcodeEmitter(dialect, options, sink)
    if em.opt.keep_subprograms:
        from cncc.backends.gcode.subprograms import keep_subprograms

        return keep_subprograms(em, expand(cmds))
    return em.emit(cmds)


def _with(p: Vec6, axis: int, value: float) -> Vec6:
    q = list(p)
    q[axis] = value
    return (q[0], q[1], q[2], q[3], q[4], q[5])
