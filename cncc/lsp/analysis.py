"""One analysis of one document: the real compiler, under a budget.

``analyze(request, check)`` runs the driver's front end and path passes on the
document text, collects the diagnostics, the commands (for code actions) and the
time of every line (for inlay hints), and checks the codes against a target
dialect.  It calls ``check()`` every few hundred commands so that a guarded job
(:mod:`cncc.lsp.guard`) can stop it; what was collected up to then stays valid.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field

from cncc import diagnostics as dg
from cncc.diagnostics import Diagnostic, DiagnosticSink
from cncc.dialects import Dialect, DialectError
from cncc.ir import Command
from cncc.ir.machine import MachineModel
from cncc.lsp.config import Settings, open_dialect
from cncc.lsp.positions import LineIndex
from cncc.lsp.scan import Comments, tokens
from cncc.source import SourceMap, Span

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
    reached: int = 0  # offset of the last command seen
    elapsed_s: float = 0.0
    sink: DiagnosticSink = field(default_factory=lambda: DiagnosticSink(max_count=5000))

    @property
    def text(self) -> str:
        return self.request.text

    @property
    def version(self) -> int | None:
        return self.request.version


def new_analysis(req: Request) -> Analysis:
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
    from cncc import driver

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
    a.machine = _machine(settings, sink)
    sources = SourceMap()
    src = sources.add(req.path or req.uri, req.text)
    if not req.text.strip():
        sink.emit(dg.EMPTY_PROGRAM, Span(src.source_id, 0, 0), "the program contains no blocks")
        return
    opts = driver.Options(inputs=[req.path], dialect=a.dialect.name, offsets_file=settings.path(settings.offsets),
                          tools_file=settings.path(settings.tools), repair_arcs=req.repair_arcs)
    cmds = driver.path_passes(driver.front_end(src, a.dialect, a.machine, opts, sink), a.dialect, a.machine,
                              opts, sink)
    _collect(a, cmds, check)
    if settings.opt_level > 0 and req.stop_after < 0 and len(a.commands) < MAX_COMMANDS:
        check()
        _planned_times(a, settings.opt_level)


def _machine(settings: Settings, sink: DiagnosticSink) -> MachineModel:
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
    return model


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


def _planned_times(a: Analysis, level: int) -> None:
    """Replace the nominal motion times by the planner's at ``-O<level>``."""
    from cncc import driver
    from cncc.backends.nominal import command_time_s
    from cncc.ir import MOTION_TYPES

    machine = a.machine
    assert machine is not None
    cmds = a.commands
    try:
        traj, _how = driver.plan_trajectory(cmds, machine, level, a.sink)
    except Exception as exc:  # the planner is young: keep the nominal times, say why
        a.sink.emit(dg.NOT_SUPPORTED, Span(0, 0, 0), f"-O{level} planning failed ({type(exc).__name__}: {exc}); "
                    "inlay hints show nominal times", severity=dg.Severity.NOTE)
        return
    per_cmd = [0.0] * len(cmds)
    for k, d in zip(traj.cmd_index.tolist(), traj.duration_s.tolist(), strict=True):
        if 0 <= k < len(per_cmd):
            per_cmd[k] += d
    line_of = a.index.line_of
    times: dict[int, float] = {}
    for c, t_motion in zip(cmds, per_cmd, strict=True):
        t = t_motion if isinstance(c, MOTION_TYPES) else command_time_s(c, machine)[0]
        if t > 0.0:
            line = line_of(c.span.start)
            times[line] = times.get(line, 0.0) + t
    a.line_time_s = times


# ---- target checks ------------------------------------------------------------------
def _supports(target: Dialect, letter: str, tenths: int, op: str, cycle: str, index: int) -> bool:
    same = target.code(letter, tenths)
    if same is not None and same.op == op:
        return True
    return any(c.op == op and c.cycle == cycle and (op != "work" or c.index == index) for c in target.codes.values())


def check_target(a: Analysis, check: Callable[[], None]) -> None:
    """Warn where a code of the program has no counterpart (same op) in the target."""
    dialect, target = a.dialect, a.target
    assert dialect is not None and target is not None
    comments = Comments.of(dialect)
    index = a.index
    seen: dict[tuple[str, int], bool] = {}
    for line in range(index.line_count):
        if line % 1024 == 0:
            check()
        base = index.line_start(line)
        for tok in tokens(index.line_text(line), base, comments):
            if tok.kind != "word" or tok.text not in "GM":
                continue
            tenths = tok.tenths
            if tenths is None:
                continue
            cdef = dialect.code(tok.text, tenths)
            if cdef is None:
                continue
            key = (tok.text, tenths)
            ok = seen.get(key)
            if ok is None:
                ok = seen[key] = _supports(target, tok.text, tenths, cdef.op, cdef.cycle, cdef.index)
            if not ok:
                what = cdef.summary.split(":")[0].split(";")[0].rstrip(".") or cdef.op
                why = target.unsupported_reason(tok.text, tenths)  # the target controller's own reason
                a.sink.emit(dg.TARGET_UNSUPPORTED, Span(0, tok.start, tok.end),
                            f"{target.name} cannot run {cdef.name} ({what})" + (f": {why}" if why else ""))

