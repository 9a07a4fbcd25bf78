"""The driver: builds the pipeline from options — the one place that knows every stage.

``compile_files(options)`` reads the inputs, resolves each file's options (``cncc.toml``, the
modeline, a guessed dialect, the ``--ini`` file), lowers them with the front end, runs the path
passes (:mod:`cncc.pipeline.builder`), and hands the result to the backend stage
(:func:`cncc.emit.dispatch.run_backend`) named by ``options.emit``.  It never raises on bad
input: everything goes into the :class:`DiagnosticSink`.

The options record is :class:`cncc.options.Options`, the name-to-model lookups are in
:mod:`cncc.resolve`, and the backends' glue (translation, timing columns, planning, pulses) in
:mod:`cncc.emit`; their public names are re-exported here for the callers that import them
from the driver.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field
from functools import partial
from typing import Any, TextIO, TypeVar

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink
from cncc.dialects import Dialect, DialectError, load_dialect
from cncc.emit.dispatch import EMIT_KINDS, MACHINE_EMITS, run_backend
from cncc.emit.gcode import output_dialect, translation_prepare
from cncc.emit.plan import plan_trajectory
from cncc.emit.pulses import PULSE_BINARY_FORMATS, pulse_backend, pulse_option_problem, writes_own_output
from cncc.emit.timing import reversal_events, timing_runs
from cncc.ir import Command, Vec6
from cncc.ir.batch import Item
from cncc.ir.machine import MachineModel
from cncc.options import DEFAULT_DIALECT, DEFAULT_MACHINE, Options
from cncc.outfile import write_stream
from cncc.resolve import apply_dialect_to_machine, default_machine, dialect_file, resolve_dialect, resolve_machine
from cncc.source import NO_SPAN, SourceFile, SourceMap, Span

__all__ = [  # the driver's own, and the re-exported names its callers import from here
    "DEFAULT_DIALECT", "DEFAULT_MACHINE", "EMIT_KINDS", "MACHINE_EMITS", "PULSE_BINARY_FORMATS", "Options", "Result",
    "apply_dialect_to_machine", "check_pipeline", "compile_files", "decode", "default_machine", "dialect_file",
    "fast_syntax_only", "file_options", "front_end", "front_end_items", "interp_options", "macro_options",
    "new_sink", "output_dialect", "path_items", "path_passes", "pipeline_config", "plan_trajectory",
    "pulse_backend", "pulse_option_problem", "read_input", "resolve_dialect", "resolve_machine",
    "reversal_events", "run_backend", "timing_runs", "translation_prepare", "until_limit", "writes_own_output",
]

T = TypeVar("T")


@dataclass(slots=True)
class Result:
    sink: DiagnosticSink
    sources: SourceMap
    output: str = ""
    deps: dict[str, list[str]] = field(default_factory=dict)  # input -> program files its calls loaded (-M)
    runs: list[Any] = field(default_factory=list)  # --emit=timing: the planned columns (cncc.api reads them)
    dialects: dict[str, str] = field(default_factory=dict)  # input -> the dialect it was read in
    pass_report: str = ""  # --print-after dumps and the --time-passes table (the CLI writes them to stderr)

    @property
    def ok(self) -> bool:
        return not self.sink.has_errors


# ---- inputs --------------------------------------------------------------------------
def decode(data: bytes) -> str:
    """Program bytes to text: UTF-8, else Latin-1 (every byte maps to a character)."""
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        return data.decode("latin-1")


def read_input(path: str, sources: SourceMap, sink: DiagnosticSink, stdin: TextIO | None = None) -> SourceFile | None:
    if path == "-":
        stream = stdin if stdin is not None else sys.stdin
        buf = getattr(stream, "buffer", None)
        text = decode(buf.read()) if buf is not None else stream.read()
        return sources.add("<stdin>", text)
    try:
        with open(path, "rb") as fh:
            data = fh.read()
    except OSError as exc:
        sink.emit(dg.CANNOT_READ, NO_SPAN, f"cannot read {path}: {exc.strerror or exc}")
        return None
    return sources.add(path, decode(data))


# ---- offsets and tools -----------------------------------------------------------------
def load_tables(opts: Options, sink: DiagnosticSink
                ) -> tuple[dict[int, Vec6], dict[int, float], dict[int, float], frozenset[int] | None]:
    """Work offsets, tool lengths and radii, and the T numbers a LinuxCNC tool table (.tbl) lists (None:
    no such table; cncc's TOML tables list offset numbers, not tools)."""
    from cncc import tables

    work: dict[int, Vec6] = {}
    lengths: dict[int, float] = {}
    radii: dict[int, float] = {}
    if opts.offsets_file:
        try:
            work = tables.read_offsets(opts.offsets_file)
        except tables.TableError as exc:
            sink.emit(dg.BAD_OFFSETS_FILE, NO_SPAN, str(exc))
    listed: frozenset[int] | None = None
    if opts.tools_file:
        try:
            lengths, radii = tables.read_tools(opts.tools_file)
        except tables.TableError as exc:
            sink.emit(dg.BAD_OFFSETS_FILE, NO_SPAN, str(exc))
        else:
            if str(opts.tools_file).endswith(".tbl"):
                listed = frozenset(lengths) | frozenset(radii)
    return work, lengths, radii, listed


# ---- pipeline ---------------------------------------------------------------------------
def front_end(src: SourceFile, dialect: Dialect, machine: MachineModel, opts: Options,
              sink: DiagnosticSink, sources: SourceMap | None = None, deps: list[str] | None = None,
              ini: Any = None) -> Iterator[Command]:
    from cncc.frontend import lower

    if ini is None and opts.ini_file:
        ini = load_ini(opts, sink, sources)
    return lower(src, dialect, sink, interp_options(opts, machine, sink),
                 macro_options(opts, sink, sources, deps, ini))


def front_end_items(src: SourceFile, dialect: Dialect, machine: MachineModel, opts: Options,
                    sink: DiagnosticSink, sources: SourceMap | None = None, deps: list[str] | None = None,
                    ini: Any = None) -> Iterator[Item]:
    """:func:`front_end`, with runs of plain moves as :class:`cncc.ir.batch.MoveBatch` items where the
    front end makes them (what :func:`compile_files` streams through the passes)."""
    from cncc.frontend import lower

    if ini is None and opts.ini_file:
        ini = load_ini(opts, sink, sources)
    iopts = interp_options(opts, machine, sink)
    iopts.batches = True
    return lower(src, dialect, sink, iopts, macro_options(opts, sink, sources, deps, ini))


def interp_options(opts: Options, machine: MachineModel, sink: DiagnosticSink) -> Any:
    """The interpreter's tables: work offsets, tool lengths and radii, the machine's reference
    points and M codes, the start position (the CLI, the API and the language server alike)."""
    from cncc.dialects import code_tenths
    from cncc.frontend import InterpOptions

    work, lengths, radii, listed = load_tables(opts, sink)
    refs = tuple(tuple(r) + (0.0,) * (6 - len(r)) for r in machine.reference_positions_mm) or ((0.0,) * 6,)
    m_codes = {code_tenths(name[1:]): (m.meaning or "machine function") for name, m in machine.m_codes}
    iopts = InterpOptions(work_offsets_mm=work, tool_lengths_mm=lengths, tool_radii_mm=radii, tool_numbers=listed,
                          reference_mm=refs, block_delete=opts.block_delete, strict=opts.strict,  # type: ignore[arg-type]
                          machine_m_codes=m_codes)
    if opts.start_machine_mm is not None:  # the program position of that point in G54
        m, g54 = tuple(opts.start_machine_mm) + (0.0,) * 6, work.get(1, (0.0,) * 6)
        iopts.start_mm = (m[0] - g54[0], m[1] - g54[1], m[2] - g54[2], m[3] - g54[3], m[4] - g54[4], m[5] - g54[5])
    return iopts


def load_ini(opts: Options, sink: DiagnosticSink, sources: SourceMap | None) -> Any:
    """The --ini file's settings (cncc/inifile.py), or None."""
    if not opts.ini_file:
        return None
    from cncc.inifile import read_ini

    return read_ini(opts.ini_file, sources if sources is not None else SourceMap(), sink)


def ini_dialect(dialect: Dialect, ini: Any, opts: Options, sink: DiagnosticSink, first: bool = True) -> Dialect:
    """The dialect with the options the --ini file sets (its ``[ini]`` table; -f options win); its bad
    values are reported for the ``first`` file only."""
    table = dialect.raw.get("ini")
    if ini is None or not table:
        return dialect
    from cncc.diagnostics import DiagnosticSink as Sink
    from cncc.inifile import dialect_options

    got = dialect_options(ini, table, opts.dialect_options, sink if first else Sink())
    return dialect.with_options(got) if got else dialect


def macro_options(opts: Options, sink: DiagnosticSink, sources: SourceMap | None,
                  deps: list[str] | None = None, ini: Any = None) -> Any:
    """The macro executor's options: -D presets, -I folders, --max-steps, --io, --write-dir."""
    from cncc.frontend.macro import MacroOptions
    from cncc.frontend.macro.iofile import IoFileError, read_io

    io: dict[str, float] = {}
    if opts.io_file:
        try:
            io = read_io(opts.io_file)
        except IoFileError as exc:
            sink.emit(dg.MACRO_BAD_IO_FILE, NO_SPAN, str(exc))
    private = SourceMap()

    def load(path: str) -> SourceFile | None:
        if sources is not None:
            return read_input(path, sources, sink)
        src = read_input(path, private, sink)  # no shared map: ids far from the caller's
        return None if src is None else SourceFile(1_000_000 + src.source_id, src.name, src.text)

    protected = tuple(os.path.realpath(p) for p in opts.inputs if p != "-")
    include = tuple(opts.include_dirs) + (ini.subroutine_dirs() if ini is not None else ()) + dialect_library(opts)
    return MacroOptions(presets=dict(opts.defines), include_dirs=include, max_steps=opts.max_steps,
                        ini_parameters=ini.parameters() if ini is not None else {},
                        ini_no_fanuc_subs=ini is not None and ini.flag("RS274NGC", "DISABLE_FANUC_STYLE_SUB"),
                        io_inputs=io, write_dir=opts.write_dir, load_source=load, protected_paths=protected,
                        files_used=deps if deps is not None else [],
                        call_markers=opts.keep_subprograms and opts.emit == "gcode" and not opts.expand,
                        run_files=tuple(opts.inputs))


def dialect_library(opts: Options) -> tuple[str, ...]:
    """The dialect's own macro programs (SZGH's ProgramG cycles), searched after the -I folders."""
    try:
        lib = load_dialect(opts.dialect or DEFAULT_DIALECT).raw.get("macro", {}).get("library")
    except DialectError:
        return ()
    if not lib:
        return ()
    from cncc import dialects

    return (os.path.join(os.path.dirname(dialects.__file__), str(lib)),)


def with_line_map(cmds: Iterable[Command], sources: SourceMap) -> Iterator[Command]:
    """-E: a comment naming the source line before the commands of each new line."""
    from cncc.ir import Comment

    last: tuple[int, int] | None = None
    for cmd in cmds:
        src = sources.get(cmd.span.source_id)
        if src is not None and not isinstance(cmd, Comment):
            key = (src.source_id, src.position(cmd.span.start).line)
            if key != last:
                last = key
                yield Comment(cmd.span, cmd.frame, f"{src.name}:{key[1]}")
        yield cmd


def pipeline_config(opts: Options, keep: frozenset[str] = frozenset(),
                    transforms: frozenset[Any] = frozenset()) -> Any:
    """The pipeline builder's configuration for these options (cncc/pipeline/builder.py)."""
    from cncc.pipeline import PipelineConfig

    return PipelineConfig(machine_coords=opts.emit in MACHINE_EMITS, repair_arcs=opts.repair_arcs,
                          keep_cycles=keep, keep_transforms=transforms, keep_work=opts.emit == "canon",
                          spec=opts.passes)


def path_passes(cmds: Iterable[Command], dialect: Dialect, machine: MachineModel, opts: Options,
                sink: DiagnosticSink, manager: Any = None) -> Iterator[Command]:
    """The path stage of the pipeline (cncc/pipeline/builder.py) over the front end's commands;
    ``manager``: the compilation's :class:`cncc.pipeline.manager.PassManager` (instrumented)."""
    from cncc.ir.batch import expand

    return expand(path_items(cmds, dialect, machine, opts, sink, manager, batches=False))


def path_items(cmds: Iterable[Item], dialect: Dialect, machine: MachineModel, opts: Options,
               sink: DiagnosticSink, manager: Any = None, batches: bool = True) -> Iterator[Item]:
    """:func:`path_passes` over commands and batches of moves (:mod:`cncc.ir.batch`)."""
    from cncc.dialects.errors import controller_sink
    from cncc.passes import PassContext
    from cncc.pipeline.builder import path_passes as build_path
    from cncc.pipeline.manager import PassManager
    from cncc.pipeline.spec import SpecError

    pm = manager if manager is not None else PassManager()
    ctx = PassContext(sink=controller_sink(sink, dialect.raw.get("errors")), dialect=dialect, machine=machine,
                      batches=batches)
    keep: frozenset[str] = frozenset()
    transforms: frozenset[Any] = frozenset()
    if opts.emit == "gcode" and not opts.expand:  # translation: keep the cycles the target runs alike
        cmds, keep, transforms = translation_prepare(pm.source(cmds), dialect, opts, sink)
    else:
        cmds = pm.source(cmds)
    try:
        passes = build_path(pipeline_config(opts, keep, transforms), dialect)
    except SpecError as exc:  # compile_files checks the spec first; other callers learn here
        sink.emit(dg.BAD_PASS_SPEC, NO_SPAN, f"-p '{opts.passes}': {exc.message}")
        return iter(())
    return pm.run_items(passes, cmds, ctx)


def check_pipeline(opts: Options, sources: SourceMap, sink: DiagnosticSink) -> bool:
    """-p and --print-after name known passes with known options (E0991, pointing into the
    spec, which becomes a source of its own); False after an error."""
    from cncc.pipeline.builder import pass_names, requests
    from cncc.pipeline.spec import SpecError

    if opts.passes:
        try:
            requests(opts.passes)
        except SpecError as exc:
            src = sources.add("<-p>", opts.passes)
            sink.emit(dg.BAD_PASS_SPEC, Span(src.source_id, exc.start, min(exc.end, len(opts.passes))),
                      f"-p: {exc.message}")
            return False
        pass_list_omissions(opts, sources, sink)
    unknown = [n for n in opts.print_after if n not in pass_names()]
    if unknown:
        sink.emit(dg.BAD_PASS_SPEC, NO_SPAN, f"--print-after={unknown[0]}: unknown pass "
                                             f"(passes: {', '.join(pass_names())})")
        return False
    return True


def pass_list_omissions(opts: Options, sources: SourceMap, sink: DiagnosticSink) -> None:
    """W0973 when the -p list leaves out path passes the output is made of (not with -fsyntax-only
    or --emit=none, which make no output; the dialect of the first file is not known yet, so
    either compensation algorithm counts)."""
    from cncc.pipeline.builder import omitted_passes

    if opts.syntax_only or opts.emit == "none":
        return
    missing = omitted_passes(pipeline_config(opts))
    if missing:
        src = sources.add("<-p>", opts.passes)
        sink.emit(dg.PASSES_OMITTED, Span(src.source_id, 0, len(opts.passes)),
                  f"-p leaves out {', '.join(missing)}, which --emit={opts.emit} needs: its output is not the "
                  f"program's motion (name them in -p to keep them)")


def instrumentation(opts: Options, sources: SourceMap) -> Any:
    """The pass manager's instruments for --verify-each, --print-after and --time-passes."""
    from cncc.pipeline.manager import Instrumentation

    def printer(cmds: Any) -> str:
        from cncc.backends.irdump import dump_ir  # only for --print-after

        return "".join(dump_ir(cmds, sources))

    return Instrumentation(verify_each=opts.verify_each, print_after=frozenset(opts.print_after),
                           time_passes=opts.time_passes, sources=sources, printer=printer)


def pass_report(ins: Any, opts: Options, sink: DiagnosticSink) -> str:
    """The instruments' text for stderr (the dumps go to --print-file when given)."""
    ins.finish()
    dumps = "".join(ins.dumps)
    text = ""
    if opts.print_file and opts.print_after:  # kept with errors too: --verify-each finds them
        write_stream(opts.print_file, opts.inputs, sink, lambda fh: fh.write(dumps.encode("utf-8")),
                     keep_on_errors=True)
    else:
        text += dumps
    if opts.time_passes:
        text += ins.clock.report()
    return text


def guessed_dialect(src: SourceFile, opts: Options, sink: DiagnosticSink) -> Dialect | None:
    from cncc.frontend.detect import detect, numbers_warning

    found = detect(src.name, src.text)
    name, why = found.dialect, found.explain()
    if opts.verbose:
        sink.emit(dg.DIALECT_GUESSED, Span(src.source_id, 0, 0), f"dialect {name} ({why}); -x selects another")
    warning = numbers_warning(found, src.text)
    if warning is not None:
        sink.emit(dg.GUESS_CHANGES_NUMBERS, Span(src.source_id, 0, 0), warning)
    return resolve_dialect(Options(dialect=name, dialect_options=opts.dialect_options), sink)


# options -> cncc.toml keys (cncc/config.py)
CONFIG_FIELDS = {"dialect": "dialect", "target": "target", "machine": "machine", "offsets": "offsets_file",
                 "tools": "tools_file", "ini": "ini_file", "opt_level": "opt_level", "options": "dialect_options"}


def file_options(opts: Options, path: str, src: SourceFile, sink: DiagnosticSink) -> Options:
    """The options of one input: ``cncc.toml`` upward from it, its modeline, then the command line."""
    from dataclasses import replace

    from cncc import config

    if not opts.project_config:
        return opts
    given = {key: getattr(opts, f) for key, f in CONFIG_FIELDS.items() if f in opts.given}
    res = config.resolve(None if path == "-" else path, src.text, given)
    for problem in res.errors:
        sink.emit(dg.BAD_PROJECT_CONFIG, NO_SPAN, problem)
    fopts = replace(opts, **{CONFIG_FIELDS[k]: v for k, v in res.values.items()})
    if opts.verbose:
        at = Span(src.source_id, 0, 0)
        for key, f in CONFIG_FIELDS.items():
            value = getattr(fopts, f)
            if key == "options":
                for name, v in value.items():
                    sink.emit(dg.SETTING_ORIGIN, at, f"-f{name}={v} from {res.origins.get('options.' + name, '?')}")
            elif key in res.origins:
                sink.emit(dg.SETTING_ORIGIN, at, f"{key} {value} from {res.origins[key]}")
            elif value is not None and key != "dialect":  # an unset dialect is guessed (N0251 says how)
                sink.emit(dg.SETTING_ORIGIN, at, f"{key} {value} (default)")
        if res.config_path is None:
            sink.emit(dg.SETTING_ORIGIN, at, f"no {config.CONFIG_NAME} at or above the input's folder")
    return fopts


def until_limit(cmds: Iterable[T], sink: DiagnosticSink) -> Iterator[T]:
    """-fmax-errors=N: stop the program once N errors were reported."""
    for cmd in cmds:
        yield cmd
        if sink.limit_reached:
            return


def new_sink(opts: Options) -> DiagnosticSink:
    return DiagnosticSink(werror=opts.werror, policy=opts.policy)


def compile_files(opts: Options, stdin: TextIO | None = None, out: Callable[[str], Any] | None = None,
                  sink: DiagnosticSink | None = None) -> Result:
    """Compile ``opts.inputs``; the output text is ``Result.output``, or, with ``out``, handed to
    ``out`` piece by piece as the backend makes it (streaming: :func:`cncc.output_stream.compile_to`)."""
    sink = sink if sink is not None else new_sink(opts)
    sources = SourceMap()
    result = Result(sink, sources)
    if opts.emit not in EMIT_KINDS:
        sink.emit(dg.BAD_OPTION, NO_SPAN, f"unknown --emit={opts.emit} (choose from {', '.join(EMIT_KINDS)})")
        return result
    # a guessed dialect gets the -f options once it is known (the default need not have them)
    dialect = resolve_dialect(opts if opts.dialect else Options(), sink)
    machine = resolve_machine(opts.machine, sink)
    if dialect is None or machine is None:
        return result
    machine = apply_dialect_to_machine(machine, opts, sink)
    if not check_pipeline(opts, sources, sink):
        return result
    from cncc.pipeline.manager import PassManager

    ins = instrumentation(opts, sources)
    manager = PassManager(ins)
    parts: list[str] = []
    emit = out if out is not None else parts.append
    inis: dict[str, Any] = {}
    ini_seen: dict[str, bool] = {}  # its bad values reported once
    base_dialect, base_machine, base_opts = dialect, machine, opts
    for path in base_opts.inputs or ["-"]:
        if sink.limit_reached:
            break
        src = read_input(path, sources, sink, stdin)
        if src is None:
            continue
        setup = _file_setup(base_opts, base_dialect, base_machine, path, src, sink)
        if setup is None:
            continue
        opts, dialect, machine = setup
        ini = None
        if opts.ini_file:  # read once per run (its problems reported once)
            ini = inis[opts.ini_file] if opts.ini_file in inis else inis.setdefault(
                opts.ini_file, load_ini(opts, sink, sources))
            dialect = ini_dialect(dialect, ini, opts, sink, first=not ini_seen.get(opts.ini_file, False))
            ini_seen[opts.ini_file] = True
        result.dialects[src.name] = dialect.name
        ins.unit = src.name
        deps = result.deps.setdefault(src.name, [])
        if opts.list_deps:  # -M: run the front end, list the subprogram files it loaded
            for _ in until_limit(front_end(src, dialect, machine, opts, sink, sources, deps, ini), sink):
                pass
            continue
        if opts.syntax_only and fast_syntax_only(src, dialect, machine, opts, sink, sources, deps, ini, manager):
            continue
        if opts.expand:
            cmds: Iterator[Item] = with_line_map(path_passes(until_limit(
                front_end(src, dialect, machine, opts, sink, sources, deps, ini), sink), dialect, machine, opts,
                sink, manager), sources)
        else:
            cmds = path_items(until_limit(front_end_items(src, dialect, machine, opts, sink, sources, deps, ini),
                                          sink), dialect, machine, opts, sink, manager)
        if opts.syntax_only:
            for _ in cmds:
                pass
            continue
        row = f"backend (--emit={opts.emit})"
        backend = partial(run_backend, cmds, src, sources, dialect, machine, opts, sink, keep_runs=result.runs,
                          manager=manager)
        _hand_on(manager.timed(manager.call(row, backend), row), emit)
    result.output = "".join(parts)
    result.pass_report = pass_report(ins, opts, sink)
    return result


def _hand_on(pieces: Iterable[str], out: Callable[[str], Any]) -> None:
    for piece in pieces:
        out(piece)


def fast_syntax_only(src: SourceFile, dialect: Dialect, machine: MachineModel, opts: Options, sink: DiagnosticSink,
                     sources: SourceMap, deps: list[str], ini: Any, manager: Any) -> bool:
    """-fsyntax-only with the default passes on a fast-path dialect (:mod:`cncc.fast_syntax`, the
    same diagnostics as the whole stream); False (nothing done) when it does not apply."""
    from cncc import fast_syntax

    if not fast_syntax.wanted(src, dialect, opts):
        return False
    from cncc.pipeline.builder import path_options

    if ini is None and opts.ini_file:
        ini = load_ini(opts, sink, sources)
    iopts = interp_options(opts, machine, sink)
    mopts = macro_options(opts, sink, sources, deps, ini)

    def run_passes(cmds: Iterator[Command]) -> None:
        for _ in path_passes(until_limit(cmds, sink), dialect, machine, opts, sink, manager):
            pass

    fast_syntax.check(src, dialect, sink, iopts, mopts, path_options(pipeline_config(opts), dialect)["arc-check"],
                      run_passes)
    return True


def _file_setup(base_opts: Options, base_dialect: Dialect, base_machine: MachineModel, path: str,
                src: SourceFile, sink: DiagnosticSink) -> tuple[Options, Dialect, MachineModel] | None:
    """The options, dialect and machine of one input file (its own ``cncc:`` options, a guessed
    dialect); None when they cannot be resolved (reported)."""
    opts, dialect, machine = file_options(base_opts, path, src, sink), base_dialect, base_machine
    if opts.machine != base_opts.machine or opts.dialect_options != base_opts.dialect_options:
        model = resolve_machine(opts.machine, sink)
        if model is None:
            return None
        machine = apply_dialect_to_machine(model, opts, sink)
    if not src.text or src.text.isspace():  # (not strip(): no copy of a big file)
        sink.emit(dg.EMPTY_PROGRAM, Span(src.source_id, 0, 0), "the program contains no blocks")
    if opts.dialect is None:  # no -x: guess from the name and contents (reported with -v)
        guessed = guessed_dialect(src, opts, sink)
        if guessed is None:  # the -f options do not fit the guessed dialect (reported)
            return None
        dialect = guessed
    elif opts.dialect != base_opts.dialect or opts.dialect_options != base_opts.dialect_options:
        chosen = resolve_dialect(opts, sink)
        if chosen is None:
            return None
        dialect = chosen
    return opts, dialect, machine
