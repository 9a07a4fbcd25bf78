"""The macro executor: a program counter over syntax blocks.

Consumes the blocks of the main program (and of called programs, loaded on
demand through :class:`~cncc.frontend.macro.program.ProgramLibrary`); produces IR
commands by handing each block, with every word value evaluated to a plain number,
to :meth:`cncc.frontend.interp.Interpreter.execute`.

Per block: the words run first (after substitution; a word whose value is vacant
is left out), then the macro statements in order.  A call or jump in the words
takes effect after the block's statements.  ``GOTO``, ``IF``, ``WHILE ... DO`` /
``END``, SZGH block ``IF/ELIF/ELSE/ENDIF`` and ``G22/G800`` move the program
counter; ``M98 M99 G65 G66 G67`` (and SZGH ``M97``, user macro G codes, input
tests) push and pop :class:`~cncc.frontend.macro.frames.CallFrame` records.

Every block and statement counts against a step budget; run-time errors (an
alarm, a missing label, a division by zero ...) stop the program with a diagnostic
whose related spans are the call chain.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink, Related
from cncc.dialects import CodeDef, Dialect
from cncc.frontend.interp import Interpreter
from cncc.frontend.macro.evaluate import Evaluator
from cncc.frontend.macro.frames import CallFrame, ModalCall
from cncc.frontend.macro.program import ProgramLibrary, Unit, program_key
from cncc.frontend.macro.sysvars import IoState, MachineVariables
from cncc.frontend.macro.values import MacroError, Value, VariableLayout, Variables
from cncc.frontend.syntax import (
    Assign,
    Block,
    Else,
    ElseIf,
    EndIf,
    EndLoop,
    FileStmt,
    Goto,
    If,
    IfBlock,
    IoOut,
    IoWait,
    MessageStmt,
    ProgramName,
    Statement,
    While,
    Word,
)
from cncc.ir import MOTION_TYPES, Command, Message, Stop, StopKind
from cncc.source import NO_SPAN, SourceFile, Span

EXEC_OPS = frozenset({
    "subprogram_call", "subprogram_return", "macro_call", "modal_call", "modal_call_off", "block_loop",
    "block_loop_end", "jump", "user_macro", "input_wait_on", "input_wait_off", "program_restart",
    "local_call",
})
"""Ops the executor handles itself instead of the interpreter."""

NOT_ARGUMENTS = frozenset("GLNOP")
DEFAULT_MAX_STEPS = 5_000_000


@dataclass(slots=True)
class MacroOptions:
    """Command-line inputs of the macro executor (``-D``, ``-I``, ``--max-steps`` ...)."""

    presets: dict[int, float] = field(default_factory=dict)
    include_dirs: tuple[str, ...] = ()
    max_steps: int = DEFAULT_MAX_STEPS
    io_inputs: dict[str, float] = field(default_factory=dict)
    write_dir: str | None = None
    load_source: Callable[[str], SourceFile | None] | None = None
    protected_paths: tuple[str, ...] = ()
    files_used: list[str] = field(default_factory=list)  # filled: subprogram files loaded (-M)
    # called before (False) and after (True) each block runs (the language server records variable values)
    trace: Callable[[Executor, Block, bool], None] | None = None
    # SetMode("call_begin"/"call_end", (program key, name)) around every run of a called program
    # (translation --keep-subprograms); off: no marker reaches the IR
    call_markers: bool = False
    # the other input files of the run: their O programs can be called (a main and its library)
    run_files: tuple[str, ...] = ()


def layout_for(dialect: Dialect) -> VariableLayout:
    if dialect.macro_flavour == "szgh":
        raw = dialect.raw.get("macro", {})
        args = {str(k): int(v) for k, v in raw.get("arguments", {}).items()} or None
        reserved = [(int(a), int(b)) for a, b in raw.get("reserved", [])]
        return VariableLayout.szgh(args, reserved)
    return VariableLayout.fanuc()


class Executor:
    """Runs one main program of a dialect with a Fanuc or SZGH macro flavour."""

    def __init__(self, dialect: Dialect, sink: DiagnosticSink, interp: Interpreter,
                 options: MacroOptions, parse: Callable[[SourceFile], list[Block]]) -> None:
        from cncc.frontend.macro.szgh import SzghStatements

        self.dialect = dialect
        self.sink = sink
        self.it = interp
        self.opts = options
        self.flavour = dialect.macro_flavour
        self.vars = Variables(layout_for(dialect))
        self.io = IoState(dict(options.io_inputs))
        self.sys = MachineVariables(interp, self.flavour, self.io, self._control)
        self.sys.warn = self._unknown_system_variable
        self.vars.system = self.sys
        self.ev = Evaluator(self.vars)
        exts = tuple(dict.fromkeys((*dialect.extensions, ".nc", "")))
        self.library = ProgramLibrary(parse, sink, options.include_dirs, exts, options.load_source)
        self.library.files_used = options.files_used
        self.library.run_files = options.run_files
        self.stack: list[CallFrame] = []
        self.steps = 0
        self.stopped = False
        self.modal: ModalCall | None = None
        self.out: list[Command] = []
        self.block: Block | None = None  # the block being run (for #3000 messages)
        self.exec_codes: dict[tuple[str, int], CodeDef] = {
            key: c for key, c in dialect.codes.items() if c.op in EXEC_OPS}
        if self.flavour == "szgh":  # User P500-P504: G74/G81-G84 as user cycle programs
            from cncc.frontend.macro.remap import remapped_codes

            self.exec_codes.update(remapped_codes(dialect, sink))
        self.szgh = SzghStatements(self)
        self._preset(options.presets)

    # ---- diagnostics
    def chain(self) -> tuple[Related, ...]:
        """The call chain, innermost call first, as related spans."""
        rel = []
        for fr in reversed(self.stack):
            if fr.call_span is not None:
                what = f"{fr.kind} call of {fr.name}" if fr.name else f"{fr.kind} call"
                rel.append(Related(fr.call_span, f"in the {what} from here"))
        return tuple(rel)

    def emit(self, code: str, span: Span, message: str) -> None:
        self.sink.emit(code, span, message, self.chain())

    def fail(self, code: str, span: Span, message: str) -> None:
        """A run-time error: report it and stop the program."""
        self.emit(code, span, message)
        self.stopped = True

    def _preset(self, presets: dict[int, float]) -> None:
        for n, v in presets.items():
            try:
                self.vars.write(n, v)
            except MacroError as exc:
                self.sink.emit(dg.BAD_OPTION, NO_SPAN, f"-D#{n}={v:g}: {exc.message}")

    # ---- main loop
    def run(self, main: SourceFile) -> Iterator[Command]:
        unit = self.library.add(main)
        first, last = unit.section_range(0)
        starts = unit.section_starts
        if starts and starts[0] > 0 and all(_is_preamble(b) for b in unit.blocks[:starts[0]]):
            # '%' and comment lines before the first O number belong to the main program
            first, last = 0, unit.section_range(starts[0])[1]
        self.stack = [CallFrame(unit, first, last, first, first, "main", None)]
        try:
            yield from self._loop()
        finally:
            self.szgh.close_files()

    def _loop(self) -> Iterator[Command]:
        stack = self.stack
        max_steps = self.opts.max_steps
        trace = self.opts.trace
        while stack and not self.stopped:
            fr = stack[-1]
            i = fr.pc
            if i >= fr.last:
                self._fell_off(fr)
            else:
                block = fr.unit.blocks[i]
                fr.pc = i + 1
                self.steps += 1 + len(block.statements)
                if self.steps > max_steps:
                    self.fail(dg.MACRO_STEP_BUDGET, fr.unit.span(block.start, block.end),
                              f"stopped after {max_steps} steps (blocks and statements); an endless loop or "
                              f"recursion? (--max-steps raises the budget)")
                    break
                self.block = block
                with self.it.redirect(source_id=fr.unit.source.source_id):  # the block's file
                    if trace is not None:
                        trace(self, block, False)
                    try:
                        self._run_block(fr, i, block)
                    except MacroError as exc:
                        span = (fr.unit.span(exc.start, exc.end) if exc.start >= 0
                                else fr.unit.span(block.start, block.end))
                        self.fail(exc.code, span, exc.message)
                    if trace is not None:
                        trace(self, block, True)
            if self.out:
                yield from self.out
                self.out = []
            if self.it.ended:
                break

    def _fell_off(self, fr: CallFrame) -> None:
        if fr.kind == "main":
            self.stack.clear()
            return
        if fr.unit.blocks and fr.last > fr.first:
            b = fr.unit.blocks[fr.last - 1]
            self.emit(dg.MACRO_NO_RETURN, fr.unit.span(b.start, b.end),
                      f"program {fr.name or '(label call)'} ends without M99; returning to the caller")
        self.do_return(fr, None, NO_SPAN)

    # ---- one block
    def _run_block(self, fr: CallFrame, i: int, block: Block) -> None:
        if block.block_delete and self.it.options.block_delete:
            return
        words = block.words
        statements = block.statements
        names = [s for s in statements if isinstance(s, ProgramName)] if statements else []
        if words or block.comments or names:
            if any(w.expr is not None for w in words):
                words = self.substitute(words)
            self.run_words(fr, i, block, words, names)
            if self.stopped:
                return
        for st in statements:
            self.statement(fr, i, st)
            if self.stopped or fr.pc != i + 1:
                break

    def substitute(self, words: tuple[Word, ...]) -> tuple[Word, ...]:
        """Words with every expression evaluated; vacant values drop the word."""
        out = []
        kinds = self.dialect.addresses
        for w in words:
            if w.expr is None:
                out.append(w)
                continue
            self.ev.round_step = self._increment(kinds.get(w.letter, "real"))
            try:
                v = self.ev.value(w.expr)
            finally:
                self.ev.round_step = None
            if v is None:
                if w.letter in "GM":
                    self.emit(dg.MACRO_VACANT_WORD, Span(self.it.source_id, w.start, w.end),
                              f"{w.letter} with a vacant value is left out")
                continue
            if not math.isfinite(v) or abs(v) > 1e12:
                raise MacroError(dg.MACRO_BAD_VALUE, f"{w.letter}{v:g} is not a usable word value", w.start, w.end)
            if w.letter in "GM":
                v = round(v * 10.0) / 10.0
            point = kinds.get(w.letter, "real") not in ("int",) or v != int(v)
            out.append(Word(w.letter, v, point, w.start, w.end))
        return tuple(out)

    def _increment(self, kind: str) -> float | None:
        """The least input increment of an address of ``kind``, in program units (None: ROUND to integers)."""
        rd = self.it.reader
        if kind == "length":
            return rd.liu_length_mm / rd.mm_per_unit
        if kind == "angle":
            return rd.liu_angle_deg
        return None

    def run_words(self, fr: CallFrame, i: int, block: Block, words: tuple[Word, ...],
                  names: list[ProgramName], comments: bool = True) -> None:
        special: list[tuple[Word, CodeDef]] = []
        exec_codes = self.exec_codes
        for w in words:
            if w.letter in "GM":
                cdef = exec_codes.get((w.letter, round(w.value * 10)))
                if cdef is not None:
                    special.append((w, cdef))
                elif w.letter == "M" and self.szgh.is_m_input_wait(w):
                    special.append((w, self.szgh.m_input_code(w)))
        if special or names:
            from cncc.frontend.macro.calls import run_special

            run_special(self, fr, i, block, words, special, names)
            return
        self.run_nc(fr, block, words, comments)

    def run_nc(self, fr: CallFrame, block: Block, words: tuple[Word, ...],
               comments: bool = True) -> list[Command]:
        """Run plain words through the interpreter (and a G66 call after a move)."""
        modal = self.modal
        if modal is not None and not fr.in_modal and self.flavour == "szgh" and self.szgh.argument_block(words):
            from cncc.frontend.macro.calls import call_modal

            call_modal(self, fr, self.arguments(words), Span(self.it.source_id, block.start, block.end))
            return []
        nc = Block(block.line, block.start, block.end, words, block.comments if comments else (), (),
                   0, block.percent)
        cmds = self.it.execute(nc)
        self.out.extend(cmds)
        if modal is not None and not fr.in_modal and any(isinstance(c, MOTION_TYPES) for c in cmds):
            from cncc.frontend.macro.calls import call_modal

            call_modal(self, fr, dict(modal.args), Span(self.it.source_id, block.start, block.end))
        return cmds

    # ---- statements
    def statement(self, fr: CallFrame, i: int, st: Statement) -> None:
        ev = self.ev
        match st:
            case Assign():
                n = ev.var_number(st.target)
                self.assign(n, ev.value(st.expr), st.start, st.end)
            case Goto():
                self.goto(fr, i, ev.number(st.target), Span(fr.unit.source.source_id, st.start, st.end))
            case If():
                if ev.condition(st.cond):
                    self._then(fr, i, st)
            case While():
                if not ev.condition(st.cond):
                    end = fr.unit.loop_end.get(i)
                    if end is None:
                        raise MacroError(dg.MACRO_LOOP_MISMATCH, f"DO {st.loop_id} has no END {st.loop_id}",
                                         st.start, st.end)
                    fr.pc = end + 1
            case EndLoop():
                start = fr.unit.loop_start.get(i)
                if start is None:
                    raise MacroError(dg.MACRO_END_WITHOUT_DO, f"END {st.loop_id} without WHILE ... DO {st.loop_id}",
                                     st.start, st.end)
                fr.pc = start
            case IfBlock() | ElseIf() | Else() | EndIf() | IoWait() | IoOut() | MessageStmt() | FileStmt():
                self.szgh.statement(fr, i, st)
            case ProgramName():
                pass

    def _then(self, fr: CallFrame, i: int, st: If) -> None:
        then = st.then
        if isinstance(then, Goto | Assign):
            self.statement(fr, i, then)
            return
        words = self.substitute(then)
        assert self.block is not None
        self.run_words(fr, i, self.block, words, [], comments=False)

    def assign(self, n: int, value: Value, start: int, end: int) -> None:
        if value is not None and (not math.isfinite(value) or abs(value) > 1e300):
            raise MacroError(dg.MACRO_BAD_VALUE, f"#{n} cannot hold {value!r}", start, end)
        if self.vars.layout.is_reserved(n) and self.dialect.option("reserved_variable_warning", False) \
                and self.stack and self.stack[-1].kind != "user":  # the controller's own cycle macros may
            self.emit(dg.MACRO_RESERVED, Span(self.it.source_id, start, end),
                      f"#{n} is reserved by the controller; writing it may disturb its own cycles")
        self.vars.write(n, value, start, end)

    def goto(self, fr: CallFrame, i: int, value: float, span: Span) -> None:
        n = round(value)
        if abs(value - n) > 1e-6 or n < 0 or n > 99999:
            raise MacroError(dg.MACRO_NO_LABEL, f"GOTO {value:g}: sequence numbers are whole numbers 0 to 99999",
                             span.start, span.end)
        unit = fr.unit
        target = unit.find_label(n, i)
        if target is None or not fr.first <= target < fr.last:
            raise MacroError(dg.MACRO_NO_LABEL, f"there is no block N{n} in this program to jump to",
                             span.start, span.end)
        for w, e in unit.loop_end.items():
            if w < target <= e and not w <= i <= e:
                raise MacroError(dg.MACRO_GOTO_INTO_LOOP, f"GOTO {n} jumps into the WHILE loop of line "
                                 f"{unit.blocks[w].line}; loops are entered through their WHILE",
                                 span.start, span.end)
        fr.block_loops = [lp for lp in fr.block_loops if lp[0] < target]
        fr.pc = target

    # ---- calls and returns (used by calls.py and szgh.py)
    def do_return(self, fr: CallFrame, label: int | None, span: Span) -> None:
        from cncc.frontend.macro.calls import do_return

        do_return(self, fr, label, span)

    def arguments(self, words: tuple[Word, ...]) -> dict[int, float]:
        from cncc.frontend.macro.calls import arguments

        return arguments(self, words)

    def _control(self, n: int, value: float | None) -> None:
        """``#3000`` (alarm) and ``#3006`` (stop with message) writes."""
        text = ""
        if self.block is not None and self.block.comments:
            text = self.block.comments[0].text.strip("()/; ")
        span = (Span(self.it.source_id, self.block.start, self.block.end) if self.block is not None else NO_SPAN)
        number = int(value or 0)
        if n == 3000:
            raise MacroError(dg.MACRO_ALARM, f"alarm {3000 + number}" + (f": {text}" if text else ""))
        self.out.append(Message(span, self.it.frame, text or f"stop {number}", pause=True))
        self.emit(dg.MACRO_STOP_MESSAGE, span, f"program stop with message{': ' + text if text else ''}")

    def _unknown_system_variable(self, message: str) -> None:
        span = (Span(self.it.source_id, self.block.start, self.block.end) if self.block is not None else NO_SPAN)
        self.emit(dg.UNKNOWN_SYSTEM_VARIABLE, span, message)

    def end_program(self, span: Span) -> None:
        """M99 in a main program (``m99_in_main = "end"``): end as M02 does."""
        self.out.append(Stop(span, self.it.frame, StopKind.PROGRAM_END))
        self.it.ended = True

    def find_program(self, fr: CallFrame, key: str, text: str, span: Span) -> tuple[Unit, int] | None:
        found = self.library.find(key, fr.unit, text)
        if found is None:  # reported and skipped: the run goes on, so later calls are checked too
            where = ", ".join(self.opts.include_dirs) or "no -I folder given"
            self.emit(dg.MACRO_NO_PROGRAM, span,
                      f"program {text or key} is neither an O section of this file nor a file in the -I "
                      f"folders ({where}); the call is skipped")
        return found


__all__ = ["EXEC_OPS", "Executor", "MacroOptions", "program_key"]


def _is_preamble(block: Block) -> bool:
    """A tape-start '%' or a comment-only line (no words, no statements)."""
    return not block.words and not block.statements
