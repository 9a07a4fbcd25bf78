"""Runs a LinuxCNC program: O-word control flow, subroutines, parameters, messages.

Consumes the parser's blocks (``cncc/grammar/rs274ngc.lark``), produces IR commands
by handing each block, its words evaluated, to the shared
:class:`~cncc.frontend.interp.Interpreter`.  Per line, as LinuxCNC reads it: every
expression (words and parameter assignments) is evaluated with the old values, then
the assignments are made, then the words run.  ``(MSG,...)`` and ``(DEBUG,...)``
become operator messages, ``(PRINT,...)`` a note.  With ``stop_on_error`` (the
default) the program stops at its first error, as LinuxCNC's interpreter does;
cncc's diagnostics carry the interpreter's texts from the dialect's ``[errors]``.
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterator

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink, Related
from cncc.dialects import Dialect
from cncc.dialects.errors import ControllerSink, ControllerTexts
from cncc.frontend.interp import Interpreter
from cncc.frontend.linuxcnc import g76 as _g76  # noqa: F401  (registers G76)
from cncc.frontend.linuxcnc.comp_rules import position_read_refused, without_ignored
from cncc.frontend.linuxcnc.control import run_oword
from cncc.frontend.linuxcnc.evaluate import EvalError, Evaluator, Parameters, Scope
from cncc.frontend.linuxcnc.fastblock import run_plain
from cncc.frontend.linuxcnc.flow import FlowIndex
from cncc.frontend.linuxcnc.frames import Frame as Frame  # re-exported
from cncc.frontend.linuxcnc.g7x import cycle_word, run_g7x
from cncc.frontend.linuxcnc.lathe import block_words, diameter_mode
from cncc.frontend.linuxcnc.messages import format_message
from cncc.frontend.linuxcnc.params import SystemParameters, read_only_number
from cncc.frontend.linuxcnc.report import Before, Reporter
from cncc.frontend.parser import Parser
from cncc.frontend.syntax import Assign, Block, CommentItem, Var, Word
from cncc.ir import Command, Message
from cncc.source import SourceFile, Span

_MESSAGE = re.compile(r"^\(\s*(MSG|DEBUG|PRINT|ABORT)\s*,(.*)\)$", re.IGNORECASE | re.DOTALL)
FAST_MOVES = True  # plain moves take cncc.frontend.linuxcnc.fastblock's path (tests turn it off)
_PARAM_IN_TEXT = re.compile(r"#\s*<[^>]*>|#\d+")


class LinuxcncExecutor:
    def __init__(self, dialect: Dialect, sink: DiagnosticSink, it: Interpreter, parser: Parser,
                 include_dirs: tuple[str, ...] = (), max_steps: int = 5_000_000) -> None:
        self.dialect = dialect
        self.sink = ControllerSink(sink, ControllerTexts(dialect.raw.get("errors", {})))  # the run's (see run)
        self.it = it
        self.parser = parser
        self.system = SystemParameters(it, lambda: len(self.stack) - 1)
        self.params = Parameters(system=self._system, system_number=self.system.number,
                                 system_write=self.system.write,
                                 read_refused=lambda n: position_read_refused(self.it, n))
        self.ev = Evaluator(self.params)
        self.include_dirs = include_dirs
        self.max_steps = max_steps
        self.max_depth = int(dialect.option("max_call_depth", 10))
        self.stop_on_error = bool(dialect.option("stop_on_error", True))
        self.comments = {str(k): str(v) for k, v in dialect.raw.get("canon", {}).get("comments", {}).items()}
        if not dialect.option("interpreter_comments", True):
            self.comments = {}
        self.reporter = Reporter(it, self.comments)
        self.files: dict[str, FlowIndex] = {}
        self.stack: list[Frame] = []
        self.main: FlowIndex | None = None  # the main program (M2/M30 or its closing % must end it)
        self.opened = False  # the main program opens with a % line
        self.line = 0  # the line of the block running (#<_line>)
        self.out: list[Command] = []
        self.stopped = False
        self.ini_parameters: dict[str, float] = {}  # --ini: #<_ini[section]name> (read-only)
        self.no_fanuc_subs = False  # --ini: [RS274NGC] DISABLE_FANUC_STYLE_SUB
        self.fast = FAST_MOVES
        self.capture: list[tuple[Span, tuple[Word, ...]]] | None = None  # a G7x profile being read (g7x.py)

    # ---- diagnostics
    def fail(self, code: str, span: Span, message: str, detail: str = "") -> None:
        rel = tuple(Related(fr.call_span, f"in the call of {fr.name} from here")
                    for fr in reversed(self.stack) if fr.call_span is not None)
        self.sink.emit(code, span, message, rel, detail=detail)
        self.stopped = True

    def _system(self, name: str) -> float | None:
        if name.startswith("_ini["):
            return self.ini_parameters.get(name)
        if name == "_line":
            return float(self.line)
        if name in ("_value", "_value_returned"):
            return 0.0  # until a subroutine returns
        return self.system.name(name)

    def _assign(self, target: Var, value: float) -> None:
        """``#n = value`` / ``#<name> = value``; LinuxCNC's read-only parameters refuse it."""
        if target.index is None:
            name = target.name
            if name.startswith("_ini["):  # the --ini file's values (lcodes): rs274's own text
                raise EvalError(dg.MACRO_READ_ONLY, f"Cannot assign to read-only parameter #<{name}>",
                                target.start, target.end)
            if name.startswith("_") and (name in ("_line", "_value", "_value_returned")
                                         or self.system.read_only_name(name)):
                raise EvalError(dg.MACRO_READ_ONLY, f"#<{name}> is a read-only named parameter", target.start,
                                target.end, name)
            self.params.write_name(name, value)
            return
        n = self.ev.var_number(target)
        if read_only_number(n):
            raise EvalError(dg.MACRO_READ_ONLY, f"#{n} is a read-only parameter", target.start, target.end)
        self.params.write_number(n, value)

    # ---- running
    def run(self, src: SourceFile) -> Iterator[Command]:
        with self.it.redirect(sink=self.sink):  # the interpreter reports in the controller's words too
            yield from self._run(src)

    def _run(self, src: SourceFile) -> Iterator[Command]:
        index = FlowIndex.build(list(self.parser.blocks(src)), src, self.sink)
        if index is None:
            return
        self.stack = [Frame(index, 0)]
        self.main = index
        self.opened = next((b.percent for b in index.blocks if b.percent or b.words or b.statements), False)
        steps = 0
        while self.stack and not self.stopped and not self.it.ended:
            fr = self.stack[-1]
            depth = len(self.stack)
            if fr.pc >= len(fr.index.blocks):
                self._fell_off(fr)
            else:
                steps += 1
                if steps > self.max_steps:
                    b = fr.index.blocks[fr.pc]
                    self.fail(dg.MACRO_STEP_BUDGET, fr.index.span(b), f"stopped after {self.max_steps} blocks "
                              "(an endless loop?)")
                    break
                self._step(fr)
            if fr.auto_restore and len(self.stack) < depth and self.stack and not self.stopped and not self.it.ended:
                self._restore_modal(fr, self.stack[-1].call_span or fr.call_span)
            if self.out:
                self.system.observe(self.out)
                yield from self.out
                self.out = []

    def _percent(self, fr: Frame, i: int, block: Block) -> bool:
        """A ``%`` line: the opening one is skipped, the closing one ends the program (the rest of
        the file is not read); in a file that does not open with ``%`` it is an error."""
        first = next(k for k, b in enumerate(fr.index.blocks) if b.percent or b.words or b.statements)
        if i == first:
            return False
        if self.opened:
            self.stack.clear()
        else:
            self.fail(dg.SYNTAX, fr.index.span(block), "Bad character '%' used")
        return True

    def _fell_off(self, fr: Frame) -> None:
        if fr.caller is None:
            self.stack.clear()
            blocks = fr.index.blocks
            required = bool(self.it.dialect.option("program_end_required", False))
            if required and fr.index is self.main and blocks:  # M2/M30 or the closing % must end the file
                last = fr.index.span(blocks[-1])
                self.fail(dg.PROGRAM_NO_END, Span(last.source_id, last.end, last.end), "File ended with no percent "
                          "sign" + ("" if self.opened else " or program end"))
        else:
            if fr.m98_count:  # an O100 program called by M98 that runs to the end of the file: no M99
                last = fr.index.span(fr.index.blocks[-1])
                self.fail(dg.PROGRAM_NO_END, Span(last.source_id, last.end, last.end),
                          f"O{fr.name} called by M98 runs to the end of the file without M99: File ended with no "
                          "percent sign or program end")
            self.stack.pop()

    def _step(self, fr: Frame) -> None:
        i = fr.pc
        block = fr.index.blocks[i]
        fr.pc = i + 1
        self.line = block.line
        if block.block_delete and self.it.options.block_delete:
            return
        if block.percent and fr.index is self.main and self._percent(fr, i, block):
            return
        errors = self.sink.errors
        try:
            oword = fr.index.owords.get(i)
            if oword is not None:
                run_oword(self, fr, i, oword)
            else:
                self._block(fr, block)
        except EvalError as exc:
            self.fail(exc.code, fr.index.span_of(exc.start, exc.end), exc.message, exc.detail)
        if self.stop_on_error and self.sink.errors > errors:
            self.stopped = True

    def _block(self, fr: Frame, block: Block) -> None:
        self._define_names(block)
        words = self._drop_g80(tuple(self._value_word(w) for w in block.words))
        sets = [(s.target, self.ev.number(s.expr)) for s in block.statements if isinstance(s, Assign)]
        for target, value in sets:
            self._assign(target, value)
        if self.fast and self.capture is None and not diameter_mode(self.it):  # G7x profiles, G7: the full path
            plain = run_plain(self.it, block, words)
            if plain is not None:
                self.out.extend(plain)
                return
        words = block_words(self.it, words, capture=self.capture is not None)  # G7: X is a diameter
        if self.capture is not None:  # the profile of a G70-G72: its moves are collected, not run
            self.capture.append((fr.index.span(block), words))
            return
        if (g7x := cycle_word(words)) is not None:
            run_g7x(self, fr, block, words, g7x)
            return
        comments = self._messages(fr, block)
        m7x = [w for w in words if w.letter == "M" and round(w.value) in (70, 71, 72, 73)]
        if m7x:
            self._run_words(block, tuple(w for w in words if w not in m7x), comments)
            self._modal_save(fr, block, round(m7x[0].value))
            return
        m98 = [w for w in words if w.letter == "M" and round(w.value) in (98, 99)]
        if m98 and self.no_fanuc_subs:
            self.fail(dg.CONTROLLER_REJECTS, fr.index.span(block), "DISABLE_FANUC_STYLE_SUB set in INI file, but "
                      f"found m{round(m98[0].value)}")
            return
        if m98:
            from cncc.frontend.linuxcnc.control import m98_block

            words = m98_block(self, fr, block, words)
            if not words:
                self._run_words(block, (), comments)
                return
        self._run_words(block, words, comments)

    def _define_names(self, block: Block) -> None:
        """rs274 2.9 defines a named parameter (as 0) when it reads its assignment, so the line's own
        reads of it find 0."""
        for st in block.statements:
            if isinstance(st, Assign) and st.target.index is None and self.params.lookup(st.target.name) is None:
                self.params.write_name(st.target.name, 0.0)

    def _run_words(self, block: Block, words: tuple[Word, ...], comments: tuple[CommentItem, ...]) -> None:
        words = without_ignored(self.it, words)
        if not words and not comments:
            return
        nc = Block(block.line, block.start, block.end, words, comments, (), 0, block.percent)
        at = len(self.out)
        before = Before.of(self.it)
        if not self.reporter.allowed(Span(self.it.source_id, block.start, block.end), words):
            return
        self.out.extend(self.it.execute(nc))
        self._probe_result()
        self.reporter.after_block(Span(self.it.source_id, block.start, block.end), words, self.out, at, before)

    def _modal_save(self, fr: Frame, block: Block, m: int) -> None:
        """M70 save, M71 forget, M72 restore, M73 save and restore at the return of this call."""
        from cncc.frontend.linuxcnc.modal_save import save

        if self.stopped:
            return
        if m in (70, 73):
            coolant = (self.reporter.mist, self.reporter.flood)
            fr.modal_saved, fr.auto_restore = save(self.it, coolant), m == 73 and fr.caller is not None
        elif m == 71:
            fr.modal_saved, fr.auto_restore = None, False
        elif fr.modal_saved is None:
            self.fail(dg.CONTROLLER_REJECTS, fr.index.span(block),
                      "Cannot restore context from invalid stack frame - missing M70/M73?")
        else:
            self._restore_modal(fr, fr.index.span(block))

    def _restore_modal(self, fr: Frame, span: Span | None) -> None:
        from cncc.frontend.linuxcnc.modal_save import restore_blocks

        assert fr.modal_saved is not None
        start, end = (span.start, span.end) if span is not None else (0, 0)
        for words in restore_blocks(self.it, fr.modal_saved, (self.reporter.mist, self.reporter.flood)):
            if words:
                ws = tuple(Word(letter, value, True, start, end) for letter, value in words)
                self._run_words(Block(self.line, start, end, ws), ws, ())

    def _probe_result(self) -> None:
        """A G38.x probe sets #5061-#5070 (cncc/frontend/rs274_probe.py)."""
        from cncc.frontend.rs274_probe import take_result

        got = take_result(self.it)
        if got is not None:
            for k, v in enumerate(got):
                self.params.globals_numbered[5061 + k] = v

    def _drop_g80(self, words: tuple[Word, ...]) -> tuple[Word, ...]:
        """G80 beside another motion code (``G0 G80 X5``): LinuxCNC ignores the G80."""
        if sum(1 for w in words if w.letter == "G") < 2:
            return words
        motions = [w for w in words if w.letter == "G" and (c := self.it.dialect.code("G", round(w.value * 10)))
                   is not None and c.group == "motion"]
        if len(motions) < 2:
            return words
        return tuple(w for w in words if not (w in motions and round(w.value * 10) == 800))

    def _value_word(self, w: Word) -> Word:
        if w.expr is None:
            return w
        v = self.ev.number(w.expr)
        if w.letter in "GM":
            v = round(v * 10.0) / 10.0
        return Word(w.letter, v, True, w.start, w.end)

    def _messages(self, fr: Frame, block: Block) -> tuple[CommentItem, ...]:
        keep = []
        for c in block.comments:
            m = _MESSAGE.match(c.text.strip())
            if m is None:
                keep.append(c)
                continue
            kind, text = m.group(1).upper(), m.group(2)  # the text after the comma as written, blanks too
            span = Span(self.it.source_id, c.start, c.end)
            if kind in ("DEBUG", "PRINT"):
                text = format_message(text, self._read_number, self.params.lookup)
            if kind == "ABORT":  # rs274 stops with the text (parameters substituted) as its error
                self.fail(dg.PROGRAM_ABORT, span, self._substitute(m.group(2), c.start))
            elif kind == "PRINT":
                self.sink.emit(dg.LINUXCNC_PRINT, span, text.strip())
            else:
                self.out.append(Message(span, self.it.frame, text))
        return tuple(keep)

    def _substitute(self, text: str, pos: int) -> str:
        return _PARAM_IN_TEXT.sub(lambda mm: self._format_param(mm.group(0), pos), text)

    def _read_number(self, n: int) -> float:
        from cncc.frontend.syntax import Num

        value = self._message_read(Var(Num(float(n), False, 0, 0), 0, 0))
        return 0.0 if value is None else value  # LinuxCNC's reads are never vacant

    def _message_read(self, v: Var) -> float | None:
        """A parameter read of a message: rs274 lets DEBUG/PRINT read what an expression may not (#5420 in comp)."""
        refused, self.params.read_refused = self.params.read_refused, lambda n: None
        try:
            return self.ev.read(v)
        finally:
            self.params.read_refused = refused

    def _format_param(self, text: str, pos: int) -> str:
        from cncc.frontend.linuxcnc.builder import param_name
        from cncc.frontend.syntax import Num, Var

        if "<" in text:
            got = self.params.lookup(param_name(text))
            return "######" if got is None else f"{got:.6f}"
        n = int(text[1:])
        return f"{self._message_read(Var(Num(float(n), False, pos, pos), pos, pos)):.6f}"

    # ---- subroutine files
    def load_sub(self, name: str) -> FlowIndex | None:
        """The FlowIndex of ``<name>.ngc`` in the -I folders (cached), or None."""
        if name in self.files:
            return self.files[name]
        for folder in self.include_dirs:
            path = os.path.join(folder, f"{name}.ngc")
            if os.path.isfile(path):
                try:
                    with open(path, encoding="utf-8", errors="replace") as fh:
                        text = fh.read()
                except OSError:
                    continue
                src = SourceFile(2_000_000 + len(self.files), path, text)
                index = FlowIndex.build(list(self.parser.blocks(src)), src, self.sink)
                if index is not None:
                    self.files[name] = index
                    return index
        return None

    def push_scope(self, args: list[float]) -> None:
        scope = Scope()
        for k, v in enumerate(args[:30]):
            scope.numbered[k + 1] = v
        self.params.scopes.append(scope)

    def pop_scope(self) -> None:
        if len(self.params.scopes) > 1:
            self.params.scopes.pop()


def run_linuxcnc(src: SourceFile, dialect: Dialect, sink: DiagnosticSink, interp: Interpreter, parser: Parser,
                 macro: object = None) -> Iterator[Command]:
    dirs = tuple(getattr(macro, "include_dirs", ()) or ())
    steps = int(getattr(macro, "max_steps", 5_000_000) or 5_000_000)
    ex = LinuxcncExecutor(dialect, sink, interp, parser, dirs, steps)
    ex.ini_parameters = dict(getattr(macro, "ini_parameters", {}) or {})
    ex.no_fanuc_subs = bool(getattr(macro, "ini_no_fanuc_subs", False))
    return ex.run(src)
