"""One analysis of one document: the real compiler, under a budget.

``analyze(analysis, check)`` is the fast first phase of every edit: it runs the
front end (with the macro executor's variable trace attached) and the path passes
on the document text, collects the diagnostics, the commands (for code actions),
the nominal time of every line (for inlay hints) and the variable values seen (for
hover), and checks the codes against a target dialect.  It calls ``check()`` every
few hundred commands so that a guarded job (:mod:`cncc.lsp.guard`) can stop it;
what was collected up to then stays valid.  The slower second phase (the program
on the configured machine) is :mod:`cncc.lsp.machine_check`.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from cncc import diagnostics as dg
from cncc.diagnostics import Diagnostic, DiagnosticSink
from cncc.dialects import Dialect, DialectError
from cncc.ir import Command
from cncc.ir.machine import MachineModel
from cncc.lsp.config import Settings, open_dialect
from cncc.lsp.pipeline import compile_commands
from cncc.lsp.positions import LineIndex
from cncc.lsp.scan import Comments, tokens
from cncc.lsp.trace import VariableTrace
from cncc.source import SourceMap, Span

if TYPE_CHECKING:
    from cncc.lsp.incremental import Memory, Shifts
    from cncc.lsp.machine_check import MachineCheck

CHECK_EVERY = 256  # commands between two budget checks
MAX_COMMANDS = 400_000  # commands kept for code actions (timing goes on past it)


@dataclass(frozen=True, slots=True)
class Request:
    uri: str
    path: str
    version: int | None
    text: str
    dialect: str  # name or TOML path
    settings: Settings
    repair_arcs: bool = False
    stop_after: int = -1  # offset: stop once a command starts past it (-1: run to the end)


@dataclass(slots=True)
class Analysis:
    request: Request
    index: LineIndex
    dialect: Dialect | None = None
    target: Dialect | None = None
    machine: MachineModel | None = None
    diagnostics: list[Diagnostic] = field(default_factory=list)
    commands: list[Command] = field(default_factory=list)
    line_time_s: dict[int, float] = field(default_factory=dict)  # 0-based line -> seconds
    stopped: str | None = None  # "budget" / "cancelled" when the run did not finish
    sources: SourceMap | None = None  # the document (id 0) and the programs it called
    trace: VariableTrace | None = None  # variable values seen by the macro executor (hover)
    machine_check: MachineCheck | None = None  # the second phase, once it has ended
    reached: int = 0  # offset of the last command seen
    elapsed_s: float = 0.0
    sink: DiagnosticSink = field(default_factory=lambda: DiagnosticSink(max_count=5000))
    memory: Memory | None = None  # checkpoints for the incremental analysis of the next edit
    shifts: Shifts = field(default_factory=lambda: _no_shifts())  # offsets of ``commands`` not yet moved
    resumed: tuple[int, int] | None = None  # lines re-run by an incremental analysis (else a full run)
    region: tuple[int, int, int] | None = None  # its offsets: start, end in the new text, end in the old

    def commands_between(self, lo: int, hi: int) -> list[Command]:
        """The commands that start in ``lo..hi`` (offsets), spans where the text has them."""
        from cncc.lsp.incremental import first_at, materialize

        i = first_at(self.commands, self.shifts, lo)
        j = first_at(self.commands, self.shifts, hi + 1)
        return materialize(self.commands, self.shifts, max(0, i - 1), j)

    @property
    def text(self) -> str:
        return self.request.text

    @property
    def version(self) -> int | None:
        return self.request.version


def _no_shifts() -> Shifts:
    from cncc.lsp.incremental import Shifts

    return Shifts()


def new_analysis(req: Request, previous: Analysis | None = None) -> Analysis:
    """A fresh analysis of ``req``; its line index is derived from ``previous`` (the analysis
    of an earlier version of the same document) when there is one."""
    if previous is not None and previous.request.uri == req.uri:
        from cncc.lsp.incremental import changed_range

        prefix, suffix = changed_range(previous.text, req.text)
        return Analysis(req, LineIndex.after_edit(previous.index, req.text, prefix, suffix))
    return Analysis(req, LineIndex(req.text))


def analyze(a: Analysis, check: Callable[[], None]) -> None:
    """Fill ``a`` (the guarded work of one job)."""
    t0 = time.perf_counter()
    try:
        _compile(a, check)
        if a.target is not None and a.dialect is not None:
            check_target(a, check)
    finally:
        a.diagnostics = list(a.sink)
        a.elapsed_s = time.perf_counter() - t0


def _compile(a: Analysis, check: Callable[[], None]) -> None:
    req, sink = a.request, a.sink
    settings = req.settings
    try:
        a.dialect = open_dialect(req.dialect, settings)
    except DialectError as exc:
        sink.emit(dg.BAD_OPTION, Span(0, 0, 0), f"dialect: {exc}")
        return
    if settings.target:
        try:
            a.target = open_dialect(settings.target, settings)
        except DialectError as exc:
            sink.emit(dg.BAD_OPTION, Span(0, 0, 0), f"target: {exc}")
    a.machine = _machine(settings, a.dialect, sink)
    if not req.text.strip():
        sink.emit(dg.EMPTY_PROGRAM, Span(0, 0, 0), "the program contains no blocks")
        return
    a.trace = VariableTrace()
    a.sources = SourceMap()
    if not settings.target:
        from cncc.lsp.incremental import Memory

        a.memory = Memory()
    _collect(a, compile_commands(req, a.dialect, a.machine, a.sources, sink, machine_coords=False, trace=a.trace,
                                 memory=a.memory), check)


def _machine(settings: Settings, dialect: Dialect, sink: DiagnosticSink) -> MachineModel:
    from cncc import driver

    scratch = DiagnosticSink()
    name = settings.path(settings.machine) if settings.machine and settings.machine.endswith(".toml") \
        else settings.machine
    model = driver.resolve_machine(name or driver.DEFAULT_MACHINE, scratch)
    if model is None:
        if settings.machine:  # only a configured machine that fails is worth a word
            for d in scratch:
                sink.emit(dg.BAD_OPTION, Span(0, 0, 0), f"{d.message}; using a generic mill",
                          severity=dg.Severity.WARNING)
        return driver.default_machine()
    opts = driver.Options(dialect_options=dict(settings.dialect_options))
    return driver.apply_dialect_to_machine(model, opts, scratch)


def _collect(a: Analysis, cmds: Iterator[Command], check: Callable[[], None]) -> None:
    from cncc.backends.nominal import command_time_s

    machine = a.machine
    assert machine is not None
    line_of = a.index.line_of
    times = a.line_time_s
    kept = a.commands
    stop_after = a.request.stop_after
    n = 0
    for c in cmds:
        n += 1
        if n % CHECK_EVERY == 0:
            check()
        span = c.span
        if span.source_id != 0:
            continue
        a.reached = span.start
        if len(kept) < MAX_COMMANDS:
            kept.append(c)
        t, cat = command_time_s(c, machine)
        if cat and t > 0.0:
            line = line_of(span.start)
            times[line] = times.get(line, 0.0) + t
        if 0 <= stop_after < span.start:
            return


# ---- target checks ------------------------------------------------------------------
def _supports(target: Dialect, letter: str, tenths: int, op: str, cycle: str, index: int) -> bool:
    same = target.code(letter, tenths)
    if same is not None and same.op == op:
        return True
    return any(c.op == op and c.cycle == cycle and (op != "work" or c.index == index) for c in target.codes.values())


def check_target(a: Analysis, check: Callable[[], None]) -> None:
    """Warn where the program uses what the target cannot run: a code with no counterpart (same
    op), an address the target rejects (in a block whose codes it does run), a macro variable
    or statement when the target has no macros.  The target's own reason is quoted when its
    dialect file gives one (grbl's ``[unsupported]`` table: its error numbers)."""
    dialect, target = a.dialect, a.target
    assert dialect is not None and target is not None
    comments = Comments.of(dialect)
    index = a.index
    seen: dict[tuple[str, int], bool] = {}
    no_macros = target.macro_flavour == "none" and dialect.macro_flavour != "none"
    for line in range(index.line_count):
        if line % 1024 == 0:
            check()
        base = index.line_start(line)
        flagged = False
        later: list[tuple[int, int, str]] = []
        for tok in tokens(index.line_text(line), base, comments):
            if tok.kind == "word" and tok.text in "GM":
                flagged |= _check_code(a, target, tok.text, tok.tenths, tok.start, tok.end, seen)
            elif tok.kind == "word" and tok.text in dialect.addresses:
                why = target.unsupported_reason(tok.text)
                if why:
                    later.append((tok.start, tok.end, f"{target.name} cannot read {tok.text} words: {why}"))
            elif no_macros and tok.kind in ("var", "keyword"):
                what = f"#{tok.text}" if tok.kind == "var" else tok.text
                why = target.unsupported_reason("#") if tok.kind == "var" else target.unsupported_reason("[")
                later.append((tok.start, tok.end, f"{target.name} has no macros: it cannot run {what}"
                              + (f" ({why})" if why else "")))
        if not flagged:
            seen_letters: set[str] = set()
            for start, end, message in later:
                key = message.split(":")[0]
                if key not in seen_letters:
                    seen_letters.add(key)
                    a.sink.emit(dg.TARGET_UNSUPPORTED, Span(0, start, end), message)


def _check_code(a: Analysis, target: Dialect, letter: str, tenths: int | None, start: int, end: int,
                seen: dict[tuple[str, int], bool]) -> bool:
    """Warn if the target has no counterpart of code ``letter``+``tenths``; True if it warned."""
    dialect = a.dialect
    assert dialect is not None
    if tenths is None:
        return False
    cdef = dialect.code(letter, tenths)
    if cdef is None:
        return False
    key = (letter, tenths)
    ok = seen.get(key)
    if ok is None:
        ok = seen[key] = _supports(target, letter, tenths, cdef.op, cdef.cycle, cdef.index)
    if ok:
        return False
    what = cdef.summary.split(":")[0].split(";")[0].rstrip(".") or cdef.op
    why = target.unsupported_reason(letter, tenths)  # the target controller's own reason
    a.sink.emit(dg.TARGET_UNSUPPORTED, Span(0, start, end),
                f"{target.name} cannot run {cdef.name} ({what})" + (f": {why}" if why else ""))
    return True
