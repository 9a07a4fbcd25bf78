"""Modal interpretation: syntax blocks -> IR commands.

The :class:`Interpreter` keeps the modal state (a frozen :class:`ModalState`
snapshot), the current frame and the current position, and lowers one block at a
time with :meth:`Interpreter.execute`.  Codes are looked up in the dialect's tables
and dispatched on their canonical ``op`` through the handler table in
:mod:`cncc.frontend.ops`; codes without a handler get a "not supported yet"
diagnostic rather than a syntax error.

Within a block, effects happen in the order a Fanuc-family controller applies them:
comments, feed mode, F, S, T, M06, spindle, coolant, dwell, plane, units, cutter
compensation, length compensation, work system, path mode, distance mode, return
level, non-modal setting codes, motion, then program stops and calls.
"""

from __future__ import annotations

import copy
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink
from cncc.dialects import CodeDef, Dialect, code_name, code_tenths
from cncc.frontend.catalogue import m_group
from cncc.frontend.modal import ModalState
from cncc.frontend.registry import DEFAULT_ORDER
from cncc.frontend.registry import ORDER as ORDER  # re-exported (the in-block order of ops)
from cncc.frontend.run_state import CycleState, LayerRecords, References, RunNotes, TransformState
from cncc.frontend.syntax import Block, Word
from cncc.frontend.words import WordReader
from cncc.ir import IDENTITY_FRAME, ZERO6, Command, Comment, Frame, HoldAxes, Motion, Units, Vec6
from cncc.ir.frame import ALL_HELD, LINEAR_HELD, NOT_HELD
from cncc.source import Span

if TYPE_CHECKING:
    from cncc.frontend.registry import HandlerTable
    from cncc.frontend.rs274_state import Rs274State

AXIS_LETTERS = "XYZABC"
AXIS_INDEX = {c: i for i, c in enumerate(AXIS_LETTERS)}
MODAL_FREE_GROUPS = frozenset({"non_modal"})
_OFF_AT_POWER_ON = frozenset({"scaling", "mirror", "rotation", "polar", "cutter_comp", "length_comp", "modal_macro",
                              "cycle"})


@dataclass(slots=True)
class InterpOptions:
    """Tables and switches that come from the command line, not from the program."""

    work_offsets_mm: dict[int, Vec6] = field(default_factory=dict)  # 1 = G54 ...
    tool_lengths_mm: dict[int, float] = field(default_factory=dict)  # H number -> length
    tool_radii_mm: dict[int, float] = field(default_factory=dict)  # D number -> radius
    tool_numbers: frozenset[int] | None = None  # the T numbers a LinuxCNC tool table (.tbl) lists (None: none given)
    reference_mm: tuple[Vec6, ...] = (ZERO6,)  # G28, G30 P2, P3, P4 in machine coordinates
    block_delete: bool = True  # skip blocks starting with '/'
    strict: bool = False
    start_mm: Vec6 = ZERO6
    machine_m_codes: dict[int, str] = field(default_factory=dict)  # M tenths -> meaning (machine model)
    batches: bool = False  # the caller takes MoveBatch items (cncc/ir/batch.py) for runs of plain moves


@dataclass(slots=True)
class BlockContext:
    """Everything the handlers of one block share."""

    block: Block
    span: Span
    words: dict[str, Word]  # non-G/M words by letter
    codes: list[CodeDef]
    out: list[Command]
    axis_used: bool = False  # an op consumed the axis words
    block_flags: set[str] = field(default_factory=set)  # one-block modifiers (G53, G09 ...)


class Interpreter:
    """Lowers blocks of one dialect to IR commands, keeping modal state.

    The interpreter is the one owner of run state: the fields in ``__slots__`` are all
    there is (the records of :mod:`cncc.frontend.run_state`, the modal snapshot, frame
    and position).  Executors that run blocks for another source file or report through
    another sink say so with :meth:`redirect` instead of replacing ``sink`` or
    ``source_id``.
    """

    __slots__ = ("_end_noted", "_motion_cache", "cycle", "dialect", "ended", "extras", "frame", "group_codes",
                 "handlers", "modal", "notes", "options", "pos", "reader", "refs", "rs274", "sink", "source_id",
                 "table", "transform")

    def __init__(self, dialect: Dialect, sink: DiagnosticSink, source_id: int = 0,
                 options: InterpOptions | None = None, table: HandlerTable | None = None) -> None:
        from cncc.frontend.handler_tables import core_table

        self.dialect = dialect
        self.sink = sink
        self.source_id = source_id
        # Its own copy of the tables a program writes (G10, #2001 ...): the caller's stay as given.
        self.options = _own_tables(options or InterpOptions())
        self.table = table or core_table()  # a dialect layer passes its own composed table
        self.handlers = self.table.handlers
        units = Units.INCH if dialect.default_units == "inch" else Units.MM
        self.reader = WordReader.for_dialect(dialect, units)
        self.modal = ModalState()
        # No axis has a programmed position yet: the machine starts wherever it is (Frame.held_axes).
        self.frame = Frame(units=units, work_offset_mm=self.options.work_offsets_mm.get(1, ZERO6),
                           held_axes=ALL_HELD)
        self.pos: Vec6 = self.options.start_mm
        o = self.frame.total_offset_mm  # the program start point as a machine position (SZGH G26)
        self.refs = References(start_machine_mm=(self.pos[0] + o[0], self.pos[1] + o[1], self.pos[2] + o[2],
                                                 self.pos[3] + o[3], self.pos[4] + o[4], self.pos[5] + o[5]))
        self.cycle = CycleState()  # frontend/cycles.py
        self.transform = TransformState()  # frontend/transforms.py
        self.rs274: Rs274State | None = None  # frontend/rs274.py, made by the first RS274 op that needs it
        self.notes = RunNotes()
        self.extras = LayerRecords()  # dialect layers' records (SERIES 8)
        self.ended = False
        self.group_codes: dict[str, str] = {}
        self._end_noted = False
        self._motion_cache: dict[Motion, Motion] = {}
        self._apply_defaults()

    # ---- set-up
    def _apply_defaults(self) -> None:
        """Apply the dialect's power-on codes without emitting anything.

        Groups whose power-on state is "off" (transforms, compensation, cycles, modal
        calls) are already off in a fresh frame and modal state; their default code is
        only recorded, not run, because an option may give it another meaning
        (SYNTEC ``g50_is_cancel = false`` makes G50 the scaling *on* code).
        """
        scratch: list[Command] = []
        for group, code in self.dialect.defaults.items():
            if group in _OFF_AT_POWER_ON:
                continue
            letter = code[0]
            cdef = self.dialect.code(letter, code_tenths(code[1:]))
            if cdef is None or cdef.op not in self.handlers:
                continue
            ctx = BlockContext(Block(0, 0, 0, ()), Span(self.source_id, 0, 0), {}, [cdef], scratch)
            self.handlers[cdef.op](self, ctx, cdef)
        self.group_codes = dict(self.dialect.defaults)

    # ---- main entry points
    def run(self, blocks: Iterable[Block]) -> Iterator[Command]:
        for block in blocks:
            yield from self.execute(block)

    def execute(self, block: Block) -> list[Command]:
        """Lower one block whose word values are plain numbers."""
        out: list[Command] = []
        if self.ended:
            if not self._end_noted and (block.words or block.statements):
                self._end_noted = True
                self.sink.emit(dg.AFTER_END, Span(self.source_id, block.start, block.end),
                               "blocks after the program end are not executed")
            return out
        if block.block_delete and self.options.block_delete:
            return out
        span = Span(self.source_id, block.start, block.end)
        for c in block.comments:
            text = _comment_text(c.text)
            if text is not None:
                out.append(Comment(Span(self.source_id, c.start, c.end), self.frame, text))
            if c.text.startswith("(") and not c.text.endswith(")"):
                self.sink.emit(dg.UNCLOSED_COMMENT, Span(self.source_id, c.start, c.end),
                               "comment '(' is not closed on this line; the rest of the line is taken as comment")
        if block.statements:
            self.sink.emit(dg.NOT_SUPPORTED, Span(self.source_id, block.statements[0].start, block.statements[0].end),
                           f"macro statements need the {self.dialect.macro_flavour} macro evaluator")
            return out
        if not block.words:
            return out
        ctx = self._classify(block, span, out)
        if ctx is None:
            return out
        from cncc.frontend import ops

        ops.run_block(self, ctx)
        return out

    def redirect(self, sink: DiagnosticSink | None = None, source_id: int | None = None) -> Redirect:
        """A context in which the blocks report to ``sink`` and their spans are in file
        ``source_id`` (an executor running a subprogram file, or a controller's sink);
        both are restored when it ends."""
        return Redirect(self, sink, source_id)

    def run_state(self) -> dict[str, object]:
        """A copy of the run state (every field but the fixed parts: dialect, sink, handler
        table, caches; of the options only the offset tables, which G10 writes), for
        checkpoints (``cncc/lsp/incremental.py``); the mutable records are copied, so
        running on does not change it, and two are equal when the runs are in the same state."""
        state = {k: _copied(getattr(self, k)) for k in self.__slots__ if k not in _FIXED_FIELDS}
        o = self.options
        state[_TABLES] = (dict(o.work_offsets_mm), dict(o.tool_lengths_mm), dict(o.tool_radii_mm))
        return state

    def restore_run_state(self, state: dict[str, object]) -> None:
        """Go back to a :meth:`run_state` (which stays usable for another restore)."""
        for k, v in state.items():
            if k == _TABLES:
                assert isinstance(v, tuple)
                o = self.options
                o.work_offsets_mm, o.tool_lengths_mm, o.tool_radii_mm = (dict(t) for t in v)
            else:
                setattr(self, k, _copied(v))

    # ---- helpers used by the handlers
    def emit_error(self, code: str, span: Span, message: str) -> None:
        self.sink.emit(code, span, message)

    def word_span(self, w: Word) -> Span:
        return Span(self.source_id, w.start, w.end)

    def intern_motion(self, m: Motion) -> Motion:
        return self._motion_cache.setdefault(m, m)

    def set_frame(self, frame: Frame) -> None:
        """Switch frames keeping the machine position: program position follows."""
        old, new = self.frame.total_offset_mm, frame.total_offset_mm
        if old != new:
            p = self.pos
            self.pos = (p[0] + old[0] - new[0], p[1] + old[1] - new[1], p[2] + old[2] - new[2],
                        p[3] + old[3] - new[3], p[4] + old[4] - new[4], p[5] + old[5] - new[5])
        if frame.units is not self.frame.units:
            self.reader = WordReader.for_dialect(self.dialect, frame.units)
        old_frame = self.frame
        if (frame.scaling, frame.mirror, frame.rotation) != (old_frame.scaling, old_frame.mirror, old_frame.rotation):
            frame = _hold_after_cancel(old_frame, frame)
        self.frame = frame

    def hold_axes(self, axes: Iterable[int], ctx: BlockContext) -> None:
        """The machine moved these axes outside the program (tool change, reference return, G53, probe): the
        next absolute word of each says where it goes (a translation writes it even if unchanged).  A
        ``HoldAxes`` record tells the emitter."""
        held = list(self.frame.held_axes)
        for k in axes:
            held[k] = True
        new = (held[0], held[1], held[2], held[3], held[4], held[5])
        if new != self.frame.held_axes:
            self.frame = replace(self.frame, held_axes=new)
            ctx.out.append(HoldAxes(ctx.span, self.frame, new))

    def release_axes(self, axes: Iterable[int]) -> None:
        """An absolute position was programmed for ``axes``: they no longer keep a cancelled transform's point."""
        held = self.frame.held_axes
        if held == NOT_HELD:
            return
        new = list(held)
        for k in axes:
            new[k] = False
        if tuple(new) != held:
            self.frame = replace(self.frame, held_axes=(new[0], new[1], new[2], new[3], new[4], new[5]),
                                 after_cancel=self.frame.after_cancel and True in new[:3])

    def set_modal(self, group: str, code: CodeDef) -> None:
        """Record the code now in force in ``group`` (for #4001... and hover texts)."""
        self.group_codes[group] = code.name

    # ---- block classification
    def _classify(self, block: Block, span: Span, out: list[Command]) -> BlockContext | None:
        words: dict[str, Word] = {}
        codes: list[CodeDef] = []
        groups: dict[str, CodeDef] = {}
        m_count = 0
        ok = True
        for w in block.words:
            letter = w.letter
            if w.expr is not None:
                self.sink.emit(dg.NOT_SUPPORTED, self.word_span(w),
                               f"{letter} with an expression needs the {self.dialect.macro_flavour} macro evaluator")
                ok = False
                continue
            if letter in "GM":
                cdef = self._lookup(w)
                if cdef is None:
                    ok = False
                    continue
                if letter == "M":
                    m_count += 1
                    group = "m:" + m_group(cdef.op)
                else:
                    group = cdef.group
                prev = groups.get(group)
                if prev is not None and group not in MODAL_FREE_GROUPS and group != "m:other":
                    gname = group.removeprefix("m:")
                    self.sink.emit(dg.MODAL_CONFLICT, self.word_span(w),
                                   f"{cdef.name} and {prev.name} are in the same modal group ({gname})")
                    ok = False
                    continue
                groups[group] = cdef
                codes.append(cdef)
            elif letter == "N" or letter == "O":
                continue
            else:
                if letter in words:
                    self.sink.emit(dg.REPEATED_WORD, self.word_span(w), f"address {letter} appears twice in the block")
                    ok = False
                    continue
                words[letter] = w
        if m_count > self.dialect.max_m_per_block:
            self.sink.emit(dg.TOO_MANY_M, span,
                           f"{m_count} M codes in one block; {self.dialect.name} allows {self.dialect.max_m_per_block}")
            ok = False
        if "motion" in groups and "cycle" in groups and groups["cycle"].op != "cycle_off":
            # Group 01 and a canned cycle in one block: the motion wins, the cycle is cancelled.
            codes.remove(groups["cycle"])
        if not ok:
            return None
        order = self.table.order
        codes.sort(key=lambda c: order.get(c.op, DEFAULT_ORDER))
        return BlockContext(block, span, words, codes, out)

    def _lookup(self, w: Word) -> CodeDef | None:
        if w.value < 0 or w.value >= 10000:
            self.sink.emit(dg.NUMBER_RANGE, self.word_span(w), f"{w.letter}{w.value:g} is out of range")
            return None
        tenths = round(w.value * 10)
        if abs(w.value * 10 - tenths) > 1e-6:
            self.sink.emit(dg.UNKNOWN_G if w.letter == "G" else dg.UNKNOWN_M, self.word_span(w),
                           f"{w.letter}{w.value:g} is not a {self.dialect.name} code")
            return None
        cdef = self.dialect.code(w.letter, tenths)
        if cdef is None and w.letter == "M":
            from cncc.frontend.mcodes import machine_m_code

            cdef = machine_m_code(self, w, tenths)
            if cdef is not None:
                return cdef
        if cdef is None:
            self.sink.emit(dg.UNKNOWN_G if w.letter == "G" else dg.UNKNOWN_M, self.word_span(w),
                           f"{code_name(w.letter, tenths)} is not a {self.dialect.name} code")
        return cdef


_FIXED_FIELDS = frozenset({"dialect", "sink", "source_id", "options", "handlers", "table", "_motion_cache"})


_TABLES = "options.tables"  # run_state's key for the offset tables


def _own_tables(o: InterpOptions) -> InterpOptions:
    return replace(o, work_offsets_mm=dict(o.work_offsets_mm), tool_lengths_mm=dict(o.tool_lengths_mm),
                   tool_radii_mm=dict(o.tool_radii_mm))


def _copied(v: object) -> object:
    """``v`` itself when it cannot change (frozen records, numbers, tuples), else a copy:
    containers one level deep, the mutable records (``TransformState``, ``RunNotes``,
    ``LayerRecords``, ``Rs274State``) deep."""
    if isinstance(v, dict | list | set):
        return v.copy()
    return v if _immutable(v) else copy.deepcopy(v)


def _immutable(v: object) -> bool:
    params = getattr(type(v), "__dataclass_params__", None)
    return params.frozen if params is not None else v is None or isinstance(v, int | float | str | tuple | frozenset)


class Redirect:
    """:meth:`Interpreter.redirect`'s context (a class: it is entered once per macro block)."""

    __slots__ = ("_it", "_saved", "_sink", "_source_id")

    def __init__(self, it: Interpreter, sink: DiagnosticSink | None, source_id: int | None) -> None:
        self._it, self._sink, self._source_id = it, sink, source_id
        self._saved = (it.sink, it.source_id)  # (set again on entry: a context may be entered later)

    def __enter__(self) -> Interpreter:
        it = self._it
        self._saved = (it.sink, it.source_id)
        if self._sink is not None:
            it.sink = self._sink
        if self._source_id is not None:
            it.source_id = self._source_id
        return it

    def __exit__(self, *exc: object) -> None:
        self._it.sink, self._it.source_id = self._saved


def _hold_after_cancel(old: Frame, new: Frame) -> Frame:
    """The transforms changed: a cancel keeps the machine where it is, a new transform starts afresh.

    After G50, G50.1, G69 (SZGH G37, G12 ...) the tool stays at the transformed point and
    the program position of each axis is apart from it until that axis gets an absolute
    word (SYNTEC §1.2.23, SZGH §3.22/§3.23); where a manual is silent the uncommanded
    axis does not move either.  ``Frame.held_axes`` carries this to the transform passes.
    """
    only_removed = all(
        n is None or n == o for n, o in ((new.scaling, old.scaling), (new.rotation, old.rotation))
    ) and (new.mirror is None or new.mirror == old.mirror or (
        old.mirror is not None and new.mirror.center_mm == old.mirror.center_mm
        and all(o or not n for n, o in zip(new.mirror.axes, old.mirror.axes, strict=True))))
    if not only_removed:  # a transform switched on or changed: the held axes stay as they were
        return new
    held = tuple(a or b for a, b in zip(new.held_axes, LINEAR_HELD, strict=True))
    return replace(new, held_axes=held, after_cancel=True)  # type: ignore[arg-type]


def _comment_text(text: str) -> str | None:
    if text.startswith("//"):
        return text[2:].strip()
    if text.startswith("("):
        return text[1:-1].strip() if text.endswith(")") else text[1:].strip()
    if text.startswith(";"):
        return text[1:].strip()
    return text.strip()


__all__ = ["IDENTITY_FRAME", "BlockContext", "InterpOptions", "Interpreter"]
