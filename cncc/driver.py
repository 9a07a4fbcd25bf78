"""The driver: builds the pipeline from options — the one place that knows every stage.

``compile_files(options)`` reads the inputs, lowers them with the front end, runs
the passes, and hands the result to the backend named by ``options.emit``.  It
never raises on bad input: everything goes into the :class:`DiagnosticSink`.
"""

from __future__ import annotations

import os
import shutil
import sys
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field
from functools import partial
from typing import Any, TextIO, TypeVar

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink, WarningPolicy
from cncc.dialects import Dialect, DialectError, load_dialect
from cncc.ir import Command, Frame, Units, Vec6
from cncc.ir.batch import Item
from cncc.ir.machine import Axis, MachineModel
from cncc.outfile import write_stream
from cncc.source import NO_SPAN, SourceFile, SourceMap, Span

T = TypeVar("T")
MACHINE_EMITS = ("timing", "pulses")  # backends that read machine coordinates
EMIT_KINDS = ("canon", "ir", "gcode", "timing", "pulses", "none")
DEFAULT_DIALECT = "syntec"
DEFAULT_MACHINE = "generic-mill"


@dataclass(slots=True)
class Options:
    inputs: list[str] = field(default_factory=list)
    dialect: str | None = None
    target: str | None = None
    machine: str = DEFAULT_MACHINE
    emit: str = "canon"
    output: str | None = None
    syntax_only: bool = False
    werror: bool = False
    strict: bool = False
    opt_level: int = 2
    offsets_file: str | None = None
    tools_file: str | None = None
    ini_file: str | None = None  # --ini: a LinuxCNC INI file (cncc/inifile.py)
    dialect_options: dict[str, Any] = field(default_factory=dict)
    block_delete: bool = True
    repair_arcs: bool = False
    report_format: str = "text"
    # macros and subprograms (cncc/frontend/macro): -D, -I, -M, -E, --max-steps, --io, --write-dir
    defines: dict[int, float] = field(default_factory=dict)
    include_dirs: list[str] = field(default_factory=list)
    list_deps: bool = False
    expand: bool = False
    max_steps: int = 5_000_000
    io_file: str | None = None
    write_dir: str | None = None
    compare: str = ""  # timing report columns: "O0,O1,O2" or machine names (NAME@O1)
    annotate_time: bool = False  # timing: the program with elapsed times as comments
    verbose: bool = False  # -v: notes on what the driver chose (the guessed dialect)
    start_machine_mm: tuple[float, ...] | None = None  # machine position at the start (default: the G54 zero)
    quiet: bool = False  # -q: no progress bars
    # translation (--emit=gcode -t, cncc/backends/gcode, docs/translation.md)
    units: str = ""  # --units: "" as programmed, "mm" or "inch"
    line_numbers: bool = False  # -fline-numbers
    keep_subprograms: bool = False  # --keep-subprograms: called programs kept where the target calls them
    target_options: dict[str, Any] = field(default_factory=dict)  # --target-option NAME=VALUE (the -t dialect)
    decimals_mm: int | None = None  # --decimals-mm
    decimals_inch: int | None = None  # --decimals-inch
    pulse_format: str = "vcd"  # --emit=pulses: vcd | csv | npz | queue
    pulse_mode: str = "exact"  # --emit=pulses: exact | interp (SZGH 2 ms interpolation)
    verify: bool = True  # -fno-verify: skip the verify pass after plan (timing, pulses)
    # the pass manager (cncc/pipeline, docs/architecture.md "Pipeline")
    passes: str = ""  # -p 'name{opt=value},name2': the passes instead of the default pipeline
    verify_each: bool = False  # --verify-each: check the IR invariants after every pass
    print_after: tuple[str, ...] = ()  # --print-after=NAME: the IR after these passes
    print_file: str | None = None  # --print-file=FILE: where --print-after writes (default: stderr)
    time_passes: bool = False  # --time-passes: the per-pass timing table on stderr
    keep_trajectory: bool = False  # --emit=timing: keep the trajectories in Result.runs (cncc.api), never stream
    # the command line (cncc/cli.py): project configuration and what the diagnostics options ask
    project_config: bool = False  # read cncc.toml and the modeline per input (cncc/config.py)
    given: frozenset[str] = frozenset()  # fields set on the command line (they beat cncc.toml and the modeline)
    policy: WarningPolicy = field(default_factory=WarningPolicy)  # -w, -Wno-CODE, -Werror=CODE, -fmax-errors


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


def resolve_dialect(opts: Options, sink: DiagnosticSink) -> Dialect | None:
    name = opts.dialect or DEFAULT_DIALECT
    try:
        dialect = dialect_file(name) if name.endswith(".toml") else load_dialect(name)
        unknown = [k for k in opts.dialect_options if k not in dialect.options]
        if unknown:
            from cncc.flags import unknown_option

            sink.emit(dg.BAD_OPTION, NO_SPAN, unknown_option(unknown[0], opts.dialect_options[unknown[0]],
                                                             dialect.options, dialect.name))
            return None
        if opts.dialect_options:
            dialect = dialect.with_options(opts.dialect_options)
    except DialectError as exc:
        sink.emit(dg.BAD_OPTION, NO_SPAN, str(exc))
        return None
    return dialect


def dialect_file(path: str) -> Dialect:
    """A dialect TOML file (a dialect of one's own, as the language server also reads)."""
    import tomllib

    from cncc.dialects import parse_dialect

    try:
        with open(path, "rb") as fh:
            return parse_dialect(tomllib.load(fh))
    except (OSError, tomllib.TOMLDecodeError) as exc:
        raise DialectError(f"{path}: {exc}") from None


def resolve_machine(name: str, sink: DiagnosticSink) -> MachineModel | None:
    try:
        from cncc import machines  # data + loader (may be absent in minimal builds)
    except ImportError:
        return default_machine()
    loader = getattr(machines, "load_machine", None)
    if loader is None:
        return default_machine()
    try:
        model: MachineModel = loader(name)
    except (ValueError, OSError) as exc:
        sink.emit(dg.BAD_OPTION, NO_SPAN, f"machine {name!r}: {exc}")
        return None
    return model


def apply_dialect_to_machine(machine: MachineModel, opts: Options, sink: DiagnosticSink) -> MachineModel:
    """The controller's rapid type (SYNTEC Pr411, SZGH P9_D6) overrides the machine's
    rapid mode when the user sets it (``-frapid_type=...``); the dialect's own default
    applies only to the machine model that emulates that controller."""
    from dataclasses import replace

    from cncc.ir.machine import RapidMode

    value = opts.dialect_options.get("rapid_type")
    if value is None:
        return machine
    try:
        mode = RapidMode(str(value))
    except ValueError:
        sink.emit(dg.BAD_OPTION, NO_SPAN, f"-frapid_type={value}: expected 'interpolated' or 'independent'")
        return machine
    return replace(machine, rapid_mode=mode)


def default_machine() -> MachineModel:
    return MachineModel("generic-mill", tuple(Axis(a) for a in "XYZ"))


# ---- offsets and tools -----------------------------------------------------------------
def load_tables(opts: Options, sink: DiagnosticSink) -> tuple[dict[int, Vec6], dict[int, float], dict[int, float]]:
    from cncc import tables

    work: dict[int, Vec6] = {}
    lengths: dict[int, float] = {}
    radii: dict[int, float] = {}
    if opts.offsets_file:
        try:
            work = tables.read_offsets(opts.offsets_file)
        except tables.TableError as exc:
            sink.emit(dg.BAD_OFFSETS_FILE, NO_SPAN, str(exc))
    if opts.tools_file:
        try:
            lengths, radii = tables.read_tools(opts.tools_file)
        except tables.TableError as exc:
            sink.emit(dg.BAD_OFFSETS_FILE, NO_SPAN, str(exc))
    return work, lengths, radii


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

    work, lengths, radii = load_tables(opts, sink)
    refs = tuple(tuple(r) + (0.0,) * (6 - len(r)) for r in machine.reference_positions_mm) or ((0.0,) * 6,)
    m_codes = {code_tenths(name[1:]): (m.meaning or "machine function") for name, m in machine.m_codes}
    iopts = InterpOptions(work_offsets_mm=work, tool_lengths_mm=lengths, tool_radii_mm=radii,
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


def output_dialect(dialect: Dialect, opts: Options, sink: DiagnosticSink) -> Dialect | None:
    """The dialect --emit=gcode writes: -t, else the input dialect."""
    if not opts.target or opts.target == dialect.name:
        if not opts.target_options:
            return dialect
        try:
            return dialect.with_options(opts.target_options)
        except DialectError as exc:
            sink.emit(dg.BAD_OPTION, NO_SPAN, str(exc))
            return None
    return resolve_dialect(Options(dialect=opts.target, dialect_options=opts.target_options), sink)


TRANSFORM_CODES = (("rotate_on", "rotate_off"), ("mirror_on", "mirror_off"), ("scale_on", "scale_off"))


def translation_prepare(cmds: Iterable[Item], dialect: Dialect, opts: Options,
                        sink: DiagnosticSink) -> tuple[Iterable[Item], frozenset[str], frozenset[Any]]:
    """Cycles the target cannot keep expanded now (before the transforms), notes for what cncc applies;
    the kept cycle kinds and the rotation, mirror and scaling records the target runs itself."""
    from cncc.backends.gcode import make_target
    from cncc.backends.gcode.keep_transforms import kept_transforms
    from cncc.backends.gcode.translate import kept_cycle_kinds, prepare
    from cncc.passes.expand_cycles import expand

    target = output_dialect(dialect, opts, sink)
    if target is None:
        return cmds, frozenset(), frozenset()
    tgt = make_target(target)
    if not any(tgt.has(on) and tgt.has(off) for on, off in TRANSFORM_CODES):  # nothing to keep: stream
        return prepare(cmds, tgt, expand, sink, frozenset()), kept_cycle_kinds(tgt), frozenset()
    from cncc.ir.batch import expand as expand_batches

    items = list(cmds)  # the keep decision looks at a whole transform before its first move
    if not any(x.frame.rotation is not None or x.frame.mirror is not None or x.frame.scaling is not None
               for x in items):
        return prepare(items, tgt, expand, sink, frozenset()), kept_cycle_kinds(tgt), frozenset()
    listed = list(expand_batches(items))

    def step_mm(units: Units) -> float:
        unit = Units.INCH if opts.units == "inch" else Units.MM if opts.units == "mm" else units
        default = tgt.decimals_inch if unit is Units.INCH else tgt.decimals_mm
        chosen = opts.decimals_inch if unit is Units.INCH else opts.decimals_mm
        return 10.0 ** -(default if chosen is None else chosen) * unit.mm_per_unit

    kept = kept_transforms(listed, tgt, step_mm)
    return prepare(listed, tgt, expand, sink, kept), kept_cycle_kinds(tgt), kept


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


def run_backend(items: Iterator[Item], src: SourceFile, sources: SourceMap, dialect: Dialect,
                machine: MachineModel, opts: Options, sink: DiagnosticSink,
                keep_runs: list[Any] | None = None, manager: Any = None) -> Iterator[str]:
    from cncc.ir.batch import expand as expand_batches

    frame0 = Frame(units=Units.INCH if dialect.default_units == "inch" else Units.MM)
    cmds = expand_batches(items)  # lazy: the backends that take batches of moves read ``items``
    if opts.emit == "canon":
        from cncc.backends.canon import emit_canon

        return emit_canon(items, frame0, dialect.raw.get("canon"))
    if opts.emit == "ir":
        from cncc.backends.irdump import dump_ir

        return dump_ir(cmds, sources)
    if opts.emit == "gcode":
        from cncc.backends.gcode import EmitOptions, emit_gcode
        from cncc.passes.expand_cycles import expand

        target = output_dialect(dialect, opts, sink)
        if target is None:
            return iter(())
        eopts = EmitOptions(decimals_mm=opts.decimals_mm, decimals_inch=opts.decimals_inch,
                            line_numbers=opts.line_numbers, units=opts.units,
                            same_dialect=target.name == dialect.name, expand_cycle=expand,
                            keep_subprograms=opts.keep_subprograms and not opts.expand, from_program_start=True)
        if opts.expand and opts.annotate_time:  # -E --annotate-time
            from cncc.backends.timing import annotated_commands

            cmd_list = list(cmds)
            runs = timing_runs(cmd_list, machine, opts, sink, manager)
            cmds = iter(annotated_commands(cmd_list, runs, sources, src.name, dialect))
        return emit_gcode(cmds if opts.expand and opts.annotate_time else items, target, eopts, sink)
    if opts.emit == "timing":
        from cncc.backends.timing import streamable, streamed_timing_report, timing_report
        from cncc.backends.timing.progress import track_source

        color = opts.output in (None, "-") and sys.stdout.isatty()
        width = shutil.get_terminal_size().columns if color else None  # the text report fits the terminal
        if streamable(opts, machine):  # -O0 from the batches, without a command list (timing/streamed.py)
            return streamed_timing_report(track_source(items, len(src.text), src.source_id), machine, src, sources,
                                          dialect, opts.report_format, sink, color=color, width=width)
        cmd_list = list(track_source(cmds, len(src.text), src.source_id))
        runs = timing_runs(cmd_list, machine, opts, sink, manager)
        if keep_runs is not None:
            keep_runs.extend(runs)
        return timing_report(cmd_list, runs, src, sources, dialect, opts.report_format, sink,
                             annotate=opts.annotate_time, color=color, width=width)
    if opts.emit == "pulses":
        return pulse_backend(cmds, machine, opts, sink, manager)
    if opts.emit == "none":
        for _ in items:
            pass
        return iter(())
    sink.emit(dg.NOT_SUPPORTED, NO_SPAN, f"--emit={opts.emit} is not available yet")
    for _ in cmds:
        pass
    return iter(())


def plan_trajectory(cmds: list[Command], machine: MachineModel, level: int, sink: DiagnosticSink,
                    verify: bool = True, soft_limits: bool = False, quiet: bool = False,
                    manager: Any = None, spec: str = "") -> tuple[Any, str]:
    """(Trajectory, how it was made): the planning stage of the pipeline -- blend, plan at
    ``level`` (-O0: the nominal estimate), verify (``verify``, -O1..-O3; its violations
    become diagnostics) -- as :func:`cncc.pipeline.builder.plan_passes` makes it.

    ``cmds`` are in machine coordinates (``to-machine`` ran in ``path_passes``); blend keeps
    their order and count, so ``Trajectory.cmd_index`` still indexes ``cmds``.  Soft limits
    are checked only when the work offsets are known (``soft_limits``: ``--offsets`` given):
    with the default zero offsets, program coordinates are no machine positions.
    ``manager``: the compilation's pass manager; ``spec``: its ``-p`` text.
    """
    from cncc.passes import PassContext
    from cncc.pipeline import PipelineConfig
    from cncc.pipeline.builder import plan_passes
    from cncc.pipeline.manager import PassManager

    pm = manager if manager is not None else PassManager()
    passes = plan_passes(PipelineConfig(machine_coords=True, spec=spec), level, verify=verify,
                         soft_limits=soft_limits, quiet=quiet)
    ctx = PassContext(sink=sink, machine=machine)
    for _ in pm.run(passes, cmds, ctx, stage="plan", label=f"-O{level} on {machine.name}"):
        pass
    if ctx.trajectory is None:  # a -p plan stage without plan: the nominal estimate, for the report
        from cncc.backends.nominal import nominal_trajectory

        return nominal_trajectory(cmds, machine), "nominal: length / feed (no plan pass in -p)"
    return ctx.trajectory, ctx.plan_how


PULSE_BINARY_FORMATS = ("npz",)


def writes_own_output(opts: Options) -> bool:
    """True when the backend streams straight into ``opts.output`` (pulses to a file)."""
    return opts.emit == "pulses" and opts.output not in (None, "-")


def pulse_option_problem(opts: Options, formats: tuple[str, ...], modes: tuple[str, ...]) -> str:
    """What is wrong with the --emit=pulses options ('' when nothing)."""
    to_stdout = opts.output in (None, "-")
    if opts.pulse_format not in formats:
        return f"unknown --pulse-format={opts.pulse_format} (choose from {', '.join(formats)})"
    if opts.pulse_mode not in modes:
        return f"unknown --pulse-mode={opts.pulse_mode} (choose from {', '.join(modes)})"
    if opts.pulse_format in PULSE_BINARY_FORMATS and to_stdout:
        return f"--pulse-format={opts.pulse_format} is binary: name the output file with -o FILE"
    if not to_stdout and len(opts.inputs) > 1:
        return "--emit=pulses -o FILE takes one input program"
    return ""


def pulse_backend(cmds: Iterator[Command], machine: MachineModel, opts: Options, sink: DiagnosticSink,
                  manager: Any = None) -> Iterator[str]:
    """--emit=pulses: plan at -O<level>, then step/dir pulses; text to stdout, or streamed into -o FILE."""
    import io

    from cncc.backends.pulses import FORMATS, MODES, generate_pulses, reversal_pauses, write_pulses
    from cncc.backends.pulses import progress as pulse_progress
    from cncc.backends.timing import event_pauses

    fmt, to_stdout = opts.pulse_format, opts.output in (None, "-")
    problem = pulse_option_problem(opts, FORMATS, MODES)
    cmd_list = list(cmds)
    if problem:
        sink.emit(dg.BAD_OPTION, NO_SPAN, problem)
        return iter(())
    traj, _ = plan_trajectory(cmd_list, machine, opts.opt_level, sink, verify=opts.verify,
                              soft_limits=opts.offsets_file is not None, quiet=opts.quiet, manager=manager,
                              spec=opts.passes)
    pauses = event_pauses(cmd_list, traj.cmd_index, machine)  # the timing report's event times
    reversals = reversal_pauses(traj, machine, mode=opts.pulse_mode)
    chunks = pulse_progress.track(
        generate_pulses(traj, machine, mode=opts.pulse_mode, spans=[c.span for c in cmd_list], sink=sink,
                        pauses=pauses, reversals=reversals),
        round(traj.duration_total_s * 1e9) + sum(ns for _, ns in pauses) + reversals.total_ns,
        pulse_progress.estimated_steps(traj, machine), quiet=opts.quiet)
    if to_stdout:
        buf = io.StringIO()
        write_pulses(chunks, fmt, buf)
        return iter((buf.getvalue(),))
    write_stream(opts.output or "-", opts.inputs, sink, lambda fh: write_pulses(chunks, fmt, fh))
    return iter(())


def timing_runs(cmds: list[Command], machine: MachineModel, opts: Options, sink: DiagnosticSink,
                manager: Any = None) -> list[Any]:
    """One planned Run per report column (``--compare``, else -O<level> and the nominal estimate)."""
    from cncc.backends.timing import Run, default_columns, parse_compare

    specs = parse_compare(opts.compare, opts.opt_level) if opts.compare else default_columns(opts.opt_level)
    if isinstance(specs, str):
        sink.emit(dg.BAD_OPTION, NO_SPAN, specs)
        return []
    runs = []
    for spec in specs:
        model = machine if spec.machine is None else resolve_machine(spec.machine, sink)
        if model is None:
            return []
        traj, how = plan_trajectory(cmds, model, spec.level, sink, verify=opts.verify,
                                    soft_limits=opts.offsets_file is not None, quiet=opts.quiet, manager=manager,
                                    spec=opts.passes)
        runs.append(Run(spec.label, model, spec.level, traj, how, nominal=spec.level == 0,
                        reversals=reversal_events(traj, model, opts)))
    return runs


def reversal_events(traj: Any, machine: MachineModel, opts: Options) -> tuple[tuple[int, int, str], ...]:
    """(command, ns, what) of the reversal pauses --emit=pulses inserts for ``traj`` on ``machine``."""
    if not any(a.step.reversal_delay_s > 0 for a in machine.axes):
        return ()
    from cncc.backends.pulses import MODES, reversal_pauses

    mode = opts.pulse_mode if opts.pulse_mode in MODES else "exact"
    return tuple(reversal_pauses(traj, machine, mode=mode).by_command(traj.cmd_index))
