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
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass

from cncc import diagnostics as dg
from cncc.backends.gcode import cycles as cy
from cncc.backends.gcode import patterns as pt
from cncc.backends.gcode.arcs import ArcForm, helix_feed_ratio, split
from cncc.backends.gcode.frames import TargetFrame, add, sub
from cncc.backends.gcode.keep_transforms import scale_codes, scale_words
from cncc.backends.gcode.numbers import counts_text, fixed, quantize
from cncc.backends.gcode.target import Target, make_target
from cncc.diagnostics import DiagnosticSink
from cncc.dialects import Dialect
from cncc.ir import (
    MODE_TYPES,
    Arc,
    Aux,
    CallBoundary,
    Command,
    Comment,
    Coolant,
    CoolantState,
    Cycle,
    Dwell,
    Frame,
    HoldAxes,
    Linear,
    Message,
    ModeCommand,
    OriginKind,
    PathMode,
    Plane,
    PresetG92,
    Probe,
    Rapid,
    SelectTool,
    SetPathMode,
    SetToolNumber,
    Spindle,
    SpindleSpeed,
    SpindleState,
    Stop,
    StopKind,
    ToolChange,
    Units,
    Vec6,
    Wait,
    WriteWorkTable,
)
from cncc.ir.batch import Item, MoveBatch, expand
from cncc.ir.frame import Mirror, Rotation, Scaling
from cncc.source import NO_SPAN, Span

AXES = "XYZABC"
_PLANE_OPS = {Plane.XY: "plane_xy", Plane.ZX: "plane_zx", Plane.YZ: "plane_yz"}
_ARC_LETTERS = {Plane.XY: ("I", "J"), Plane.ZX: ("K", "I"), Plane.YZ: ("J", "K")}
_SPINDLE_OPS = {SpindleState.CW: "spindle_cw", SpindleState.CCW: "spindle_ccw", SpindleState.OFF: "spindle_off",
                SpindleState.ORIENT: "spindle_orient"}
_COOLANT_OPS = {CoolantState.FLOOD: "coolant_flood", CoolantState.MIST: "coolant_mist",
                CoolantState.OFF: "coolant_off"}
_STOP_OPS = {StopKind.PROGRAM_STOP: "program_stop", StopKind.OPTIONAL_STOP: "optional_stop",
             StopKind.PROGRAM_END: "program_end", StopKind.END_REWIND: "program_end_rewind"}
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


class GcodeEmitter:
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

    def _note_frame(self, cmd: Command) -> None:
        """The power-on work system, and the axes a cancel or an outside move left held."""
        tf = self.tf
        if tf.work_mm is None and cmd.frame.work_index == 1:  # the power-on G54 (before a G55 ... of the program)
            tf.work_mm = tf.work_tables.setdefault(1, cmd.frame.work_offset_mm)
        if True in cmd.frame.held_axes and not isinstance(cmd, Rapid | Linear | Arc):  # a cancel (a mode command)
            self.held = tuple(a or b for a, b in zip(self.held, cmd.frame.held_axes, strict=True))
        if isinstance(cmd, HoldAxes):  # moved outside the program (M06, G28, G53)
            self.unknown |= {k for k, h in enumerate(cmd.axes) if h}

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
                yield self.op_block(_SPINDLE_OPS[cmd.state], f"spindle {cmd.state.value}")
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
                yield from self._aux(cmd)
            case _ if isinstance(cmd, MODE_TYPES):
                yield from self._mode(cmd)
            case _:
                pass

    def _mode(self, cmd: ModeCommand) -> Iterator[str]:
        """The mode commands a translation acts on: call boundaries, G92 presets, G10 work offsets, G61/G64."""
        match cmd:
            case Probe():
                self.probe = (self.t.code(cmd.op), cmd.folded)
            case SetToolNumber():  # M61 Q
                yield self.op_block("set_tool_number", "setting the tool number without a change", [f"Q{cmd.tool}"])
            case CallBoundary() if self.opt.keep_subprograms:
                from cncc.backends.gcode.subprograms import call_marker

                yield call_marker(self, cmd)
            case PresetG92():
                self.g92_force |= set(cmd.axes)
            case WriteWorkTable():
                yield from self._work_table(cmd.index, cmd.old_mm, cmd.new_mm)
            case SetPathMode() if not cmd.for_cycle:
                op = "exact_stop_mode" if cmd.mode is PathMode.EXACT_STOP else "continuous_mode"
                if self.t.has(op):
                    yield self.block([self.t.code(op)])

    def _select_tool(self, cmd: SelectTool) -> str:
        limit = self.t.word_max.get("T")
        if limit is not None and cmd.tool > limit:
            self.warn(dg.XL_WORD_RANGE, f"T{cmd.tool}: {self.t.name} takes tool numbers up to {limit:g}")
        return self.block([f"T{cmd.tool}"])

    def _stop(self, cmd: Stop) -> Iterator[str]:
        if self.cycle_initial is not None and cmd.kind in (StopKind.PROGRAM_END, StopKind.END_REWIND):
            yield self.block([self.t.code("cycle_off")])
            self.cycle_initial = None
        yield self.op_block(_STOP_OPS[cmd.kind], cmd.kind.name.lower().replace("_", " "))

    def _tool_change(self, cmd: ToolChange) -> Iterator[str]:
        code = self.t.code("tool_change")
        if code:
            yield self.block([code])
            return
        self.warn(dg.XL_NO_CODE, f"{self.t.name} has no tool change; a program stop asks the operator")
        yield self.block([self.t.code("program_stop")], f"change to tool T{cmd.tool}")

    def _aux(self, cmd: Aux) -> Iterator[str]:
        whole, frac = divmod(cmd.code, 10)
        name = f"M{whole:02d}" + (f".{frac}" if frac else "")
        if self.opt.same_dialect:
            yield self.block([name, *(f"{k}{v:g}" for k, v in cmd.args)])
        else:
            self.warn(dg.XL_NO_CODE, f"{name} has no known meaning to carry over to {self.t.name}")
            yield self.block([], f"{name} not translated")

    def _probe_move(self, cmd: Linear) -> Iterator[str]:
        """The moves after a probe marker: the probe move in the target's probe code (or refused), then
        the stand-alone interpreter's back-off, which a machine does not make (the position is unknown)."""
        assert self.probe is not None
        self._note_frame(cmd)
        code, left = self.probe
        self.probe = (code, left - 1) if left > 1 else None
        if cmd.origin.kind is OriginKind.PROBE_BACKOFF:
            pass
        elif code:
            self._check_increment(cmd)
            yield from self._sync(cmd.frame, cmd.start, cancel_cycle=True)
            words = [code, *self._axes(cmd.start, cmd.end, self._released(cmd.frame)), self._feed_word(cmd.feed_mm_min)]
            yield from self._g91(words)
        else:
            self.warn(dg.XL_NO_PROBE, f"{self.t.name} has no probing: the {cmd.origin.code} probe move is not written",
                      once=False)
            yield self.block([], f"{cmd.origin.code} probe: no {self.t.name} code")
        if self.probe is None:  # where a probe stops is not known: the next move writes every axis
            self.unknown |= {0, 1, 2}
            self.qpos = None

    def _work_table(self, index: int, old: Vec6, new: Vec6) -> Iterator[str]:
        """G10 L2 (or L20, LinuxCNC's G10 L20) set a work offset: the target's ``G10 L2 Pn`` when it has one,
        else the target keeps its table value and the difference is folded into the coordinates (N0809)."""
        tf = self.tf
        tf.work_tables.setdefault(index, old)
        code = self.t.code("data_input") or self.t.code("data_input_rs274")
        if not code or not 1 <= index <= 6:
            return
        if self.cycle_initial is not None:
            yield self.block([self.t.code("cycle_off")])
            self.cycle_initial = None
        self.sync_poison = True
        yield self.block([code, "L2", f"P{index}", *self._vector_words(new)])
        self.sync_poison = False
        tf.work_tables[index] = new
        if tf.work_mm is not None and tf.work_index == index:
            tf.work_mm = new
            self.qpos = None

    def _dwell_word(self, seconds: float) -> str:
        """The dwell word in the target: a word of kind ``time`` in seconds, else ``time_ms``."""
        cdef = self.t.by_op.get("dwell")
        kinds = cdef.words if cdef is not None else {}
        for letter in ("P", "X", "U"):
            if kinds.get(letter) == "time":
                return f"{letter}{fixed(seconds, 3)}"
        for letter, kind in kinds.items():
            if kind == "time_ms":
                return f"{letter}{round(seconds * 1000)}"
        return f"P{fixed(seconds, 3)}"

    # ---- frames ------------------------------------------------------------------------------
    def _sync(self, f: Frame, start: Vec6, cancel_cycle: bool) -> Iterator[str]:
        """Bring the target's units, plane and offsets to ``f``; update the fold."""
        lines: list[str] = []
        if cancel_cycle and self.cycle_initial is not None:
            lines.append(self.block([self.t.code("cycle_off")]))
            self.cycle_initial = None
        if self.forced is None and f.units is not self.units:
            if self.qpos is not None:  # where the target is, in mm: the last written numbers, in the old units
                k = 10.0 ** -self.decimals * self.units.mm_per_unit
                self.written_mm = [self.qpos[i] * k for i in range(3)]
            self.units = f.units
            self.sync_poison = True
            lines.append(self.block([self.code("inch" if f.units is Units.INCH else "metric", "units")]))
            self.feed = None
            self.qpos = None
        if f.plane is not self.plane:
            self.plane = f.plane
            lines.append(self.block([self.code(_PLANE_OPS[f.plane], "the plane")]))
        self.sync_poison = True  # units and offsets have no incremental form
        lines += self._offsets(f, start)
        self.sync_poison = False
        if lines and self.cycle_initial is not None:
            lines.insert(0, self.block([self.t.code("cycle_off")]))
            self.cycle_initial = None
        fold = self.tf.fold(f, False)
        if fold != self.fold:
            self.fold = fold
            self.qpos = None
        if any(abs(v) > 1e-12 for v in fold):
            self.warn(dg.XL_FOLDED, f"{self.t.name} output: an offset the target cannot set is added to the "
                                    "coordinates")
        mirror = f.mirror != self.mirror and self.t.has("mirror_on")
        rotation = f.rotation != self.rotation and self.t.has("rotate_on")
        scaling = f.scaling != self.scaling and self.t.has("scale_on")
        if (mirror or rotation or scaling) and self.cycle_initial is not None and not lines:
            lines.append(self.block([self.t.code("cycle_off")]))
            self.cycle_initial = None
        self.sync_poison = True
        if scaling and self.scaling is not None:  # off first: SYNTEC's G50 also cancels a mirror
            lines.append(self._scaling_block(None))
        if mirror:
            lines += self._mirror_blocks(f.mirror)
        if rotation:
            lines.append(self._rotation_block(f.rotation))
        if scaling and f.scaling is not None:
            lines.append(self._scaling_block(f.scaling))
        self.sync_poison = False
        yield from lines

    def _mirror_blocks(self, m: Mirror | None) -> list[str]:
        """G50.1 for the mirror in force, G51.1 with the kept record's axes at its centre."""
        out, old = [], self.mirror
        self.mirror = m
        self.qpos = None
        fold = self.fold or (0.0,) * 6
        if old is not None:
            out.append(self.block([self.t.code("mirror_off"),
                                   *(f"{AXES[k]}{self.length(old.center_mm[k] + fold[k])}" for k in range(3)
                                     if old.axes[k])]))
        if m is not None:
            out.append(self.block([self.t.code("mirror_on"),
                                   *(f"{AXES[k]}{self.length(m.center_mm[k] + fold[k])}" for k in range(3)
                                     if m.axes[k])]))
        return out

    def _scaling_block(self, s: Scaling | None) -> str:
        """G51 (SZGH G36, alone in its block) with the kept record's centre and factors, or G50 (G37)."""
        self.scaling = s
        self.qpos = None
        on, off = scale_codes(self.t)
        if s is None:
            return self.block([off])
        words = scale_words(self.t, s)
        assert words is not None, "keep_transforms keeps only writable scalings"
        fold = self.fold or (0.0,) * 6
        return self.block([on, *(f"{AXES[k]}{self.length(s.center_mm[k] + fold[k])}" for k in words[0]), *words[1]])

    def _rotation_block(self, r: Rotation | None) -> str:
        """G68 with the kept record (centre in the target's program coordinates, angle in degrees), or G69."""
        self.rotation = r
        self.qpos = None  # positions are read again from the commands under the new rotation
        if r is None:
            return self.block([self.t.code("rotate_off")])
        fold = self.fold or (0.0,) * 6
        i, j = r.plane.first, r.plane.second
        centre = [f"{AXES[k]}{self.text(self.counts(c + fold[k], k), k)}"
                  for k, c in zip((i, j), r.center_mm, strict=True)]
        return self.block([self.t.code("rotate_on"), *centre, f"R{fixed(r.angle_deg, ROTATION_DECIMALS)}"])

    def _offsets(self, f: Frame, start: Vec6) -> list[str]:
        tf, out = self.tf, []
        if tf.work_mm is None:  # the target's G54 is taken to be the source's (as its table had it)
            if f.work_index == 1:
                tf.work_tables.setdefault(1, f.work_offset_mm)
            tf.work_mm = tf.work_tables[1] if f.work_index == 1 else (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
        if f.work_index != tf.work_index and f.work_index in self.t.work:
            out.append(self.block([self.t.work[f.work_index].name]))
            tf.adopt_work(f)
        g92 = self.t.code("set_origin") or self.t.code("set_origin_rs274")  # LinuxCNC's G92 presets alike
        g92_want = sub(f.g92_offset_mm, tf.g92_in_local_mm)  # what the target's G92 must hold
        if g92_want != tf.g92_mm and not self.g92_force and self.t.has("local_offset"):
            # A G92 *offset* change (LinuxCNC G52/G92.x, a cancel) of an axis whose position the output does
            # not know (or whose offset is already held there): the target's G92 would set it from wherever
            # the machine is, so the change goes into the target's local offset (G52), which moves the
            # origin by the same amount from any start.
            delta = sub(g92_want, tf.g92_mm)
            if any(abs(delta[i]) > 1e-12 and (i in self.unknown or tf.g92_in_local_mm[i]) for i in range(6)):
                tf.g92_in_local_mm = add(tf.g92_in_local_mm, delta)
                g92_want = tf.g92_mm
        elif g92_want != tf.g92_mm and not self.g92_force and any(
                abs(g92_want[i] - tf.g92_mm[i]) > 1e-12 and i in self.unknown for i in range(6)):
            # no local offset in the target: leave its G92 as it is and let the fold add the change to the
            # coordinates (the G92 is written once the axis has a known position)
            self.warn(dg.XL_FOLDED, f"{self.t.name} output: a G92 offset change of an axis with no known position "
                                    "is added to the coordinates")
            g92_want = tf.g92_mm
        local_want = add(f.local_offset_mm, tf.g92_in_local_mm)
        if local_want != tf.local_mm and self.t.has("local_offset"):
            out.append(self.block([self.t.code("local_offset"), *self._vector_words(local_want)]))
            tf.local_mm = local_want
        if (f.tool_length_mm, f.tool_length_index) != (tf.tool_mm, tf.tool_index):
            out += self._tool_length(f)
        if (g92_want != tf.g92_mm or self.g92_force) and g92:
            machine = add(start, add(f.total_offset_mm, _tool(f)))
            old = tf.g92_mm
            tf.g92_mm = g92_want
            here = sub(machine, tf.offset())
            words = [f"{AXES[i]}{self.text(self.counts(here[i], i), i)}" for i in range(6)
                     if abs(g92_want[i] - old[i]) > 1e-12 or i in self.g92_force]
            self.unknown -= self.g92_force  # a preset gives the axis a program position where it is
            self.g92_force = set()
            out.append(self.block([g92, *words]))
        if out:
            self.qpos = None
        return out

    def _tool_length(self, f: Frame) -> list[str]:
        tf = self.tf
        if f.tool_length_mm == 0.0 and self.t.has("length_off"):
            tf.tool_mm, tf.tool_index = 0.0, 0
            return [self.block([self.t.code("length_off")])]
        op = "length_plus" if f.tool_length_mm > 0 else "length_minus"
        if f.tool_length_index > 0 and self.t.has(op) and f.tool_length_axis == 2:
            tf.tool_mm, tf.tool_index, tf.tool_axis = f.tool_length_mm, f.tool_length_index, f.tool_length_axis
            return [self.block([self.t.code(op), f"H{f.tool_length_index}"])]
        if self.t.has("length_dynamic") and f.tool_length_axis == 2:  # grbl G43.1 Z<length>
            tf.tool_mm, tf.tool_index, tf.tool_axis = f.tool_length_mm, f.tool_length_index, 2
            return [self.block([self.t.code("length_dynamic"), f"Z{self.length(f.tool_length_mm)}"])]
        return []

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
        changed = [i for i in range(6) if q[i] != qpos[i] or i in always or (self.all_axes and i < 3)]
        self.all_axes = False
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
        l1, l2 = _ARC_LETTERS[plane]
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
            words = [f"{AXES[a]}{self.text(q[a], a)}" for a in range(6)
                     if a != n and (a in (first, second) or q[a] != (self.qpos or q)[a])]
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


def _with(p: Vec6, axis: int, value: float) -> Vec6:
    q = list(p)
    q[axis] = value
    return (q[0], q[1], q[2], q[3], q[4], q[5])


def _tool(f: Frame) -> Vec6:
    v = [0.0] * 6
    v[f.tool_length_axis] = f.tool_length_mm
    return (v[0], v[1], v[2], v[3], v[4], v[5])


def emit_gcode(cmds: Iterable[Item], dialect: Dialect, options: EmitOptions | None = None,
               sink: DiagnosticSink | None = None) -> Iterator[str]:
    """Yield program lines (with newlines) for ``cmds`` (commands and batches of moves) in ``dialect``."""
    em = GcodeEmitter(dialect, options, sink)
    if em.opt.keep_subprograms:
        from cncc.backends.gcode.subprograms import keep_subprograms

        return keep_subprograms(em, expand(cmds))
    return em.emit(cmds)
