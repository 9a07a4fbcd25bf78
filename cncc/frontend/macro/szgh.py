"""SZGH statements: block IF/ELIF/ELSE/ENDIF, WAT/OUT, MSG/STAF and FILE*.

``WAT`` and the input-test M codes become :class:`~cncc.ir.Wait` commands (the
timing report counts them as waits); ``OUT`` becomes a ``SetOutput(Ynn,
on))``; ``MSG`` a pausing :class:`~cncc.ir.Message`, ``STAF`` a plain one.  The
program-writing statements go through :class:`~cncc.frontend.macro.fileio.Sandbox`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from cncc import diagnostics as dg
from cncc.dialects import CodeDef
from cncc.frontend.macro.fileio import Sandbox, SandboxError
from cncc.frontend.macro.frames import CallFrame
from cncc.frontend.syntax import Else, ElseIf, EndIf, FileStmt, IfBlock, IoOut, IoWait, MessageStmt, Statement, Word
from cncc.ir import Message, SetOutput, Wait
from cncc.source import Span

if TYPE_CHECKING:
    from cncc.frontend.macro.executor import Executor


class SzghStatements:
    def __init__(self, ex: Executor) -> None:
        self.ex = ex
        self.sandbox = Sandbox(ex.opts.write_dir, ex.opts.protected_paths)
        self.file_path: str | None = None
        self.file_name = ""
        self.lines: list[str] = []
        self.file_open = False
        self.m_waits = ex.flavour == "szgh" and bool(ex.dialect.option("m18xx_input_wait", False))

    # ---- M18nn / M28nn input waits (not in the code table: a pattern)
    def is_m_input_wait(self, w: Word) -> bool:
        if not self.m_waits or w.value != int(w.value):
            return False
        v = int(w.value)
        return 1800 <= v <= 1855 or 2800 <= v <= 2855

    def m_input_code(self, w: Word) -> CodeDef:
        v = int(w.value)
        op = "input_wait_on" if v < 2800 else "input_wait_off"
        return CodeDef("M", v * 10, f"M{v}", op, "non_modal", "input wait", {}, v % 100)

    def argument_block(self, words: tuple[Word, ...]) -> bool:
        """A block of argument words only (SZGH G66: such a block calls the macro)."""
        if not self.ex.dialect.option("g66_calls_on_argument_blocks", False):
            return False
        mapping = self.ex.vars.layout.arguments
        letters = [w.letter for w in words if w.letter != "N"]
        return bool(letters) and all(c in mapping and c not in "GM" for c in letters)

    # ---- statements
    def statement(self, fr: CallFrame, i: int, st: Statement) -> None:
        ex = self.ex
        sid = fr.unit.source.source_id
        span = Span(sid, st.start, st.end)
        match st:
            case IfBlock():
                if not ex.ev.condition(st.cond):
                    self._next_branch(fr, i)
            case ElseIf() | Else():
                end = fr.unit.if_end.get(i)  # the branch taken before ends here
                if end is not None:
                    fr.pc = end + 1
            case EndIf():
                pass
            case IoWait():
                self._wait(st, span)
            case IoOut():
                ex.io.outputs[st.signal] = st.on
                ex.out.append(SetOutput(span, ex.it.frame, st.signal, st.on))
            case MessageStmt():
                ex.out.append(Message(span, ex.it.frame, st.text, pause=st.pause))
                if st.pause:
                    ex.emit(dg.MACRO_STOP_MESSAGE, span, f"MSG pauses the program: {st.text}")
            case FileStmt():
                self._file(st, span)

    def _next_branch(self, fr: CallFrame, i: int) -> None:
        unit = fr.unit
        j = unit.if_next.get(i)
        while j is not None:
            marker = next((s for s in unit.blocks[j].statements if isinstance(s, ElseIf | Else | EndIf)), None)
            if isinstance(marker, ElseIf):
                if marker.cond is None:
                    self.ex.emit(dg.MACRO_BARE_ELIF, Span(unit.source.source_id, marker.start, marker.end),
                                 "ELIF without a condition is taken as ELSE")
                    fr.pc = j + 1
                    return
                if self.ex.ev.condition(marker.cond):
                    fr.pc = j + 1
                    return
                j = unit.if_next.get(j)
                continue
            fr.pc = j + 1  # ELSE: its branch; ENDIF: past the block
            return
        fr.pc = len(unit.blocks)  # an IF without ENDIF (reported when loaded): skip the rest

    def _wait(self, st: IoWait, span: Span) -> None:
        ex = self.ex
        state = ex.io.input_valid(st.signal)
        if state is not None and state != st.valid:
            ex.fail(dg.MACRO_INPUT_TIMEOUT, span,
                    f"WAT waits for {st.signal} to be {'valid' if st.valid else 'invalid'}, which the --io file "
                    f"never makes it (the controller alarms after its timeout)")
            return
        ex.out.append(Wait(span, ex.it.frame, f"{st.signal} {'valid' if st.valid else 'invalid'}"))

    # ---- FILEON / FILEWD / FILEWC / FILECE / FILEMS
    def _file(self, st: FileStmt, span: Span) -> None:
        op = st.op
        if op == "FILEON":
            self.close_files()
            self.file_name = st.arg
            self.file_path = self._resolve(st.arg, span)
            self.lines = []
            self.file_open = True
        elif op == "FILEWD":
            self._append(st.arg, span)
        elif op == "FILEWC":
            self._append(self._coordinates(), span)
        elif op == "FILECE":
            self.close_files()
        elif op == "FILEMS":
            path = self._resolve(st.arg, span)
            if path is not None:
                self._write(path, self._globals_program(), span)

    def _resolve(self, name: str, span: Span) -> str | None:
        try:
            return self.sandbox.resolve(name)
        except SandboxError as exc:
            code = dg.MACRO_FILE_NOT_WRITTEN if self.sandbox.write_dir is None else dg.MACRO_FILE_REFUSED
            self.ex.emit(code, span, f"program {name!r} is not written: {exc}")
            return None

    def _append(self, text: str, span: Span) -> None:
        if not self.file_open:
            self.ex.emit(dg.MACRO_FILE_REFUSED, span, "no program is open for writing (FILEON first)")
            return
        self.lines.append(text)

    def _coordinates(self) -> str:
        it = self.ex.it
        k = it.frame.units.mm_per_unit
        parts = []
        for i, letter in enumerate("XYZ"):
            parts.append(f"{letter}{_num(it.pos[i] / k)}")
        if it.pos[3] != 0.0:
            parts.append(f"A{_num(it.pos[3])}")
        return "".join(parts)

    def _globals_program(self) -> str:
        commons = self.ex.vars.commons
        return "".join(f"#{n}={_num(commons[n])}\n" for n in sorted(commons) if 21 <= n <= 999) + "M99\n"

    def _write(self, path: str, text: str, span: Span) -> None:
        try:
            self.sandbox.write(path, text)
        except (OSError, SandboxError) as exc:
            self.ex.emit(dg.MACRO_FILE_REFUSED, span, f"cannot write {path}: {exc}")

    def close_files(self) -> None:
        if self.file_open and self.file_path is not None:
            text = "".join(line + "\n" for line in self.lines)
            self._write(self.file_path, text, Span(self.ex.it.source_id, 0, 0))
        self.file_open = False
        self.file_path = None
        self.lines = []


def _num(v: float) -> str:
    text = f"{v:.3f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text
