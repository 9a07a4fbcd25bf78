"""The gcc-like command line: ``cncc [options] file...`` and ``cncc lsp``."""

from __future__ import annotations

import argparse
import difflib
import os
import sys
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from cncc import __version__

USAGE = "cncc [options] file...   |   cncc lsp"


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="cncc", usage=USAGE,
        description="Compile CNC programs: read a G-code dialect, run the passes, emit canon traces, "
                    "G-code, timing reports or step pulses.",
        epilog="Exit status: 0 success, 1 errors in the input, 2 bad command line, 4 internal error.")
    p.add_argument("inputs", nargs="*", metavar="file", help="program files ('-' for standard input)")
    p.add_argument("-x", "--dialect", help="input dialect (default: guessed from the file; -v says which)")
    p.add_argument("-v", "--verbose", action="store_true", help="notes on what was chosen (the guessed dialect)")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bars on long planning runs")
    p.add_argument("-t", "--target", help="target dialect for --emit=gcode (default: the input dialect)")
    p.add_argument("-m", "--machine", help="machine model name or TOML file (default: generic-mill)")
    p.add_argument("--emit", default="canon", help="canon | ir | gcode | timing | pulses | none (default: canon)")
    p.add_argument("-o", dest="output", help="output file ('-' for standard output)")
    p.add_argument("-O", dest="opt_level", type=int, choices=range(4), metavar="LEVEL",
                   help="planner level: -O0 nominal, -O1 trapezoid, -O2 jerk-limited (default), -O3 optimal")
    p.add_argument("-f", dest="flags", action="append", default=[], metavar="FLAG",
                   help="-fsyntax-only, -fstrict, -frepair-arcs, -fno-block-delete, -fline-numbers, -fno-verify, "
                        "-fdiagnostics-format=text|json|sarif, -fdiagnostics-color[=auto|always|never], "
                        "-fmax-errors=N, or a dialect option -fNAME=VALUE (e.g. -frapid_type=independent)")
    p.add_argument("-W", dest="warnings", action="append", default=[], metavar="WARN",
                   help="-Werror (warnings are errors), -Werror=CODE, -Wno-CODE (not reported), -Wall "
                        "(every warning; the default)")
    p.add_argument("-w", dest="no_warnings", action="store_true", help="report no warnings")
    p.add_argument("--offsets", dest="offsets_file", help="work offsets table (TOML)")
    p.add_argument("--tools", dest="tools_file", help="tool table (TOML or LinuxCNC .tbl)")
    p.add_argument("--ini", dest="ini_file", metavar="FILE",
                   help="LinuxCNC INI file: SUBROUTINE_PATH, #<_ini[section]name>, DISABLE_FANUC_STYLE_SUB")
    p.add_argument("--report-format", default="text", choices=["text", "json", "html"], help="timing report format")
    p.add_argument("--compare", default="", metavar="COLS",
                   help="timing report columns: planner levels and/or machines, e.g. O0,O1,O2 or szgh-990mdb@O1")
    p.add_argument("--annotate-time", action="store_true",
                   help="timing: output the program with each block's elapsed time as a comment")
    p.add_argument("--pulse-format", default="vcd", choices=["vcd", "csv", "npz", "queue"],
                   help="--emit=pulses writer (npz needs -o FILE; default: vcd)")
    p.add_argument("--pulse-mode", default="exact", choices=["exact", "interp"],
                   help="--emit=pulses: exact step times, or SZGH 2 ms interpolation (default: exact)")
    t = p.add_argument_group("translation (--emit=gcode -t DIALECT, docs/translation.md)")
    t.add_argument("--units", choices=["mm", "inch"], default="", help="write every length in this unit "
                   "(default: as programmed)")
    t.add_argument("--decimals-mm", type=int, choices=range(1, 7), metavar="N", help="decimals in mm (default 3)")
    t.add_argument("--decimals-inch", type=int, choices=range(1, 7), metavar="N",
                   help="decimals in inch (default 4)")
    t.add_argument("--target-option", action="append", default=[], metavar="NAME=VALUE",
                   help="set an [options] entry of the -t dialect (as -fNAME=VALUE does for -x)")
    t.add_argument("--keep-subprograms", action="store_true",
                   help="keep subprogram calls where the target can call them (docs/translation.md)")
    m = p.add_argument_group("macros and subprograms")
    m.add_argument("-D", dest="defines", action="append", default=[], metavar="#N=VALUE",
                   help="preset a macro variable, e.g. -D#100=5 (repeatable)")
    m.add_argument("-I", dest="include_dirs", action="append", default=[], metavar="DIR",
                   help="folder where called subprograms are found (repeatable, searched in order)")
    m.add_argument("-M", dest="list_deps", action="store_true",
                   help="print a make rule 'TARGET: program files-it-calls...' instead of compiling")
    m.add_argument("-MM", dest="list_deps_user", action="store_true",
                   help="as -M, without the dialect's own macro library (SZGH cycles)")
    m.add_argument("-MD", dest="write_deps", action="store_true",
                   help="compile, and write the make rule to the -MF file (default: TARGET's stem + .d)")
    m.add_argument("-MMD", dest="write_deps_user", action="store_true", help="as -MD, without the dialect library")
    m.add_argument("-MF", dest="deps_file", metavar="FILE", help="the file -M/-MD write the rule to")
    m.add_argument("-MT", dest="deps_targets", action="append", default=[], metavar="TARGET",
                   help="the rule's target (default: the -o file, else the input's stem + .EMIT)")
    m.add_argument("-MP", dest="deps_phony", action="store_true",
                   help="add an empty rule per called file (make then survives a deleted file)")
    m.add_argument("-E", dest="expand", action="store_true",
                   help="print the program flattened in its own dialect (macros, calls, loops and cycles "
                        "expanded; comments map blocks to source lines)")
    m.add_argument("--max-steps", type=int, default=5_000_000, metavar="N",
                   help="stop a program after N blocks and statements (default 5000000)")
    m.add_argument("--io", dest="io_file", metavar="FILE", help="input values for WAT, M input tests and #1000.. "
                   "(lines 'X12 = 1', 'M14 = on', '#1800 = 5')")
    m.add_argument("--write-dir", metavar="DIR",
                   help="the only folder SZGH FILEON/FILEMS may write programs into (default: write nothing)")
    _pass_arguments(p)
    p.add_argument("--version", action="version", version=f"cncc {__version__}")
    return p


def _pass_arguments(p: argparse.ArgumentParser) -> None:
    """The pass manager's options (cncc/pipeline, docs/architecture.md "Pipeline")."""
    g = p.add_argument_group("passes (docs/architecture.md, Pipeline)")
    g.add_argument("-p", "--passes", default="", metavar="SPEC",
                   help="run these passes instead of the default pipeline, e.g. "
                        "-p 'expand-cycles,arc-check{repair=true}' (an unknown name lists the passes)")
    g.add_argument("--verify-each", action="store_true",
                   help="after every pass check the IR: motions continuous, spans inside the file, "
                        "identity frames after to-machine (E0992)")
    g.add_argument("--print-after", action="append", default=[], metavar="NAME",
                   help="print the IR after pass NAME (as --emit=ir) to stderr; repeatable, or NAME,NAME")
    g.add_argument("--print-file", metavar="FILE", help="write the --print-after dumps to FILE instead")
    g.add_argument("--time-passes", action="store_true", help="print the CPU time of every pass on stderr")


def _value(text: str) -> Any:
    low = text.lower()
    if low in ("true", "on", "yes"):
        return True
    if low in ("false", "off", "no"):
        return False
    try:
        return int(text)
    except ValueError:
        pass
    try:
        return float(text)
    except ValueError:
        return text


def _macro_options(opts: Any, ns: argparse.Namespace, error: Any) -> None:
    """-D -I -M -E --max-steps --io --write-dir."""
    for d in ns.defines:
        name, sep, val = d.partition("=")
        number = name.strip().lstrip("#")
        try:
            opts.defines[int(number)] = float(val)
        except ValueError:
            error(f"-D{d}: expected -D#NUMBER=VALUE, e.g. -D#100=5")
        if not sep:
            error(f"-D{d}: expected -D#NUMBER=VALUE, e.g. -D#100=5")
    opts.include_dirs = list(ns.include_dirs)
    opts.list_deps = ns.list_deps
    if ns.expand:
        opts.expand = True
        opts.emit = "gcode"
        opts.target = None
    if ns.max_steps < 1:
        error("--max-steps must be at least 1")
    opts.max_steps = ns.max_steps
    opts.io_file = ns.io_file
    opts.write_dir = ns.write_dir


@dataclass(slots=True)
class Reporting:
    """How the diagnostics are shown: -fdiagnostics-format, -fdiagnostics-color, -fmax-errors."""

    fmt: str = "text"
    color: str = "auto"
    max_errors: int = 0


def _code(text: str, opt: str, error: Any) -> str:
    from cncc.diagnostics import CODES

    code = text.upper()
    if code not in CODES:
        close = difflib.get_close_matches(code, list(CODES), n=3, cutoff=0.6)
        error(f"{opt}: unknown diagnostic code {text!r}" + (f"; did you mean {' or '.join(close)}?" if close else
                                                            " (see docs/diagnostics.md)"))
    return code


def _warning_options(ns: argparse.Namespace, rep: Reporting, error: Any) -> Any:
    """-w, -Wall, -Werror, -Werror=CODE, -Wno-CODE, -fmax-errors -> the sink's WarningPolicy."""
    from cncc.diagnostics import CODES, Severity, WarningPolicy

    werror, disabled, as_errors = False, set(), set()
    for w in ns.warnings:
        if w == "error":
            werror = True
        elif w in ("all", "extra"):
            pass  # every cncc warning is on unless -w or -Wno-CODE turns it off
        elif w.startswith("error="):
            as_errors.add(_code(w[6:], f"-W{w}", error))
        elif w.startswith("no-"):
            code = _code(w[3:], f"-W{w}", error)
            if CODES[code].severity is Severity.ERROR:
                error(f"-W{w}: {code} is an error; only warnings and notes can be turned off")
            disabled.add(code)
        else:
            close = difflib.get_close_matches(w, ["error", "all", "extra"], n=1)
            error(f"unknown warning option -W{w}" + (f"; did you mean -W{close[0]}?" if close else ""))
    return werror, WarningPolicy(disabled=frozenset(disabled), as_errors=frozenset(as_errors),
                                 no_warnings=ns.no_warnings, max_errors=rep.max_errors)


def _reporting_flag(flag: str, rep: Reporting, error: Any) -> bool:
    """-fdiagnostics-format=, -fdiagnostics-color[=], -fno-diagnostics-color, -fmax-errors= (True if one)."""
    from cncc.colors import CHOICES
    from cncc.diagout import FORMATS

    key, sep, val = flag.partition("=")
    if key == "diagnostics-format":
        if val not in FORMATS:
            error(f"-f{flag}: expected one of {', '.join(FORMATS)}")
        rep.fmt = val
    elif key == "diagnostics-color" or flag == "no-diagnostics-color":
        val = "never" if flag == "no-diagnostics-color" else (val if sep else "always")
        if val not in CHOICES:
            error(f"-f{flag}: expected one of {', '.join(CHOICES)}")
        rep.color = val
    elif key == "max-errors":
        if not val.isdigit():
            error(f"-f{flag}: expected a number of errors (0: no limit)")
        rep.max_errors = int(val)
    else:
        return False
    return True


def build_options(ns: argparse.Namespace, error: Any, rep: Reporting | None = None) -> Any:
    from cncc.driver import DEFAULT_MACHINE, Options
    from cncc.flags import FLAGS, suggest

    rep = rep if rep is not None else Reporting()
    given = {f for f, v in (("dialect", ns.dialect), ("target", ns.target), ("machine", ns.machine),
                             ("offsets_file", ns.offsets_file), ("tools_file", ns.tools_file),
                             ("ini_file", ns.ini_file),
                             ("opt_level", ns.opt_level)) if v is not None}
    opts = Options(inputs=list(ns.inputs), dialect=ns.dialect, target=ns.target,
                   machine=ns.machine or DEFAULT_MACHINE, emit=ns.emit, output=ns.output,
                   opt_level=2 if ns.opt_level is None else ns.opt_level, offsets_file=ns.offsets_file,
                   tools_file=ns.tools_file, ini_file=ns.ini_file, report_format=ns.report_format,
                   compare=ns.compare, annotate_time=ns.annotate_time,
                   pulse_format=ns.pulse_format, pulse_mode=ns.pulse_mode)
    opts.verbose = ns.verbose
    opts.project_config = True
    opts.quiet = ns.quiet
    for flag in ns.flags:
        if _reporting_flag(flag, rep, error):
            continue
        if flag == "syntax-only":
            opts.syntax_only = True
        elif flag == "strict":
            opts.strict = True
        elif flag == "repair-arcs":
            opts.repair_arcs = True
        elif flag == "no-block-delete":
            opts.block_delete = False
        elif flag == "line-numbers":  # --emit=gcode: N10, N20 ... on every block
            opts.line_numbers = True
        elif flag == "no-verify":  # timing, pulses: skip the verify pass after plan
            opts.verify = False
        elif "=" in flag and flag.partition("=")[0] in FLAGS:
            error(f"-f{flag}: -f{flag.partition('=')[0]} is a cncc flag that takes no value")
        elif "=" in flag:  # a dialect option; the driver checks it against the dialect
            key, _, val = flag.partition("=")
            opts.dialect_options[key.replace("-", "_")] = _value(val)
            given.add("dialect_options")
        else:
            error(f"unknown flag -f{flag}" + (suggest(flag, (), "") if flag not in FLAGS else
                                              f" (-f{flag} takes a value: -f{flag}=VALUE)"))
    _macro_options(opts, ns, error)
    opts.units, opts.keep_subprograms = ns.units, ns.keep_subprograms
    for item in ns.target_option:
        key, sep, val = item.partition("=")
        if not sep or not key:
            error(f"--target-option {item}: expected NAME=VALUE")
        opts.target_options[key.replace("-", "_")] = _value(val)
    opts.decimals_mm, opts.decimals_inch = ns.decimals_mm, ns.decimals_inch
    opts.passes, opts.verify_each, opts.time_passes = ns.passes, ns.verify_each, ns.time_passes
    opts.print_after = tuple(n.strip() for item in ns.print_after for n in item.split(",") if n.strip())
    opts.print_file = ns.print_file
    opts.werror, opts.policy = _warning_options(ns, rep, error)
    opts.given = frozenset(given)
    _check_choices(opts, error)
    return opts


def _check_choices(opts: Any, error: Any) -> None:
    """-x and --emit name things the command line knows: a bad value is a usage error (exit 2)."""
    from cncc.dialects import available
    from cncc.driver import EMIT_KINDS

    for what, value, known in (("-x", opts.dialect, available()), ("-t", opts.target, available())):
        if value is None or value in known or (value.endswith(".toml") and os.path.isfile(value)):
            continue
        close = difflib.get_close_matches(value, known, n=1)
        error(f"{what} {value}: unknown dialect (choose from {', '.join(known)}, or a dialect .toml file)"
              + (f"; did you mean {close[0]}?" if close else ""))
    if opts.emit not in EMIT_KINDS:
        close = difflib.get_close_matches(opts.emit, EMIT_KINDS, n=1)
        error(f"--emit={opts.emit}: choose from {', '.join(EMIT_KINDS)}" + (f"; did you mean {close[0]}?"
                                                                             if close else ""))


def _deps_mode(ns: argparse.Namespace, opts: Any) -> None:
    if ns.list_deps or ns.list_deps_user:
        opts.list_deps = True


def main(argv: Sequence[str] | None = None) -> int:
    from cncc.argfiles import ArgfileError, expand

    args = list(sys.argv[1:] if argv is None else argv)
    if args[:1] == ["lsp"]:
        from cncc.lsp import serve

        return serve(args[1:])
    if args[:1] == ["batch"]:  # program libraries (cncc/batch, docs/batch.md)
        from cncc.batch.command import main as batch_main

        return batch_main(args[1:])
    parser = _parser()
    try:
        args = expand(args)
    except ArgfileError as exc:
        parser.error(str(exc))
    ns = parser.parse_intermixed_args(args)  # options and files in any order, as gcc
    rep = Reporting()
    opts = build_options(ns, parser.error, rep)
    _deps_mode(ns, opts)
    if not opts.inputs and sys.stdin.isatty():  # gcc: no file and nothing piped in
        sys.stderr.write("cncc: fatal error: no input files\ncompilation terminated.\n")
        return 2
    try:
        return run(opts, rep, ns)
    except KeyboardInterrupt:
        return 130
    except Exception as exc:  # an internal error is a bug: say so without a traceback
        if os.environ.get("CNCC_DEBUG"):
            raise
        sys.stderr.write(f"cncc: internal compiler error: {type(exc).__name__}: {exc}\n"
                         "cncc: please report this with the input; CNCC_DEBUG=1 shows the traceback\n")
        return 4


def report(result: Any, rep: Reporting, stream: Any = None) -> None:
    """The diagnostics of ``result`` on ``stream`` (stderr) in the chosen format, sorted by position."""
    from cncc.render import by_position

    err = stream if stream is not None else sys.stderr
    diags = by_position(result.sink)
    if rep.fmt == "json":
        from cncc.diagout.jsonout import render_json

        err.write(render_json(diags, result.sources))
        return
    if rep.fmt == "sarif":
        from cncc.diagout.sarif import render_sarif

        err.write(render_sarif(diags, result.sources))
        return
    from cncc.colors import palette
    from cncc.render import render

    pal = palette(rep.color, err)
    for d in diags:
        for chunk in render(d, result.sources, pal):
            err.write(chunk)
    if result.sink.dropped:
        err.write(f"cncc: {result.sink.dropped} more diagnostics not shown\n")
    if result.sink.over_limit or result.sink.limit_reached:
        err.write(f"compilation terminated due to -fmax-errors={rep.max_errors}.\n")
    n_err = result.sink.error_count
    if n_err:
        err.write(f"{n_err} error{'s' if n_err != 1 else ''} generated.\n")


def write_rules(result: Any, opts: Any, ns: argparse.Namespace) -> None:
    """-M/-MM (instead of the output) and -MD/-MMD (beside it): the make rules of the inputs."""
    from cncc import dialects
    from cncc.makedeps import default_target, rule, under
    from cncc.outfile import write_output

    library = os.path.dirname(dialects.__file__)
    user_only = ns.list_deps_user or ns.write_deps_user
    text = ""
    output = None if opts.list_deps else opts.output  # -M -o FILE: FILE is the rule's file, as for gcc
    for program, deps in result.deps.items():
        files = [d for d in deps if not (user_only and under(d, library))]
        targets = ns.deps_targets or [default_target(program, output, opts.emit)]
        text += rule(targets, program, files, phony=ns.deps_phony)
    if opts.list_deps:
        write_output(text, ns.deps_file or opts.output, opts.inputs, result.sink)
        return
    if ns.deps_file:
        path = ns.deps_file
    else:
        first = ns.deps_targets[0] if ns.deps_targets else default_target(
            opts.inputs[0] if opts.inputs else "stdin", opts.output, opts.emit)
        path = os.path.splitext(first)[0] + ".d"
    write_output(text, path, opts.inputs, result.sink)


def run(opts: Any, rep: Reporting | None = None, ns: argparse.Namespace | None = None) -> int:
    from cncc import diagnostics as dg
    from cncc.driver import compile_files, writes_own_output
    from cncc.numwarn import recorded, to_diagnostics
    from cncc.outfile import write_output
    from cncc.output_stream import compile_to, streams_output

    rep = rep if rep is not None else Reporting()
    streamed = streams_output(opts)
    with recorded() as caught:  # numpy's RuntimeWarnings become W0909 diagnostics, as in cncc.api
        result = compile_to(opts)[0] if streamed else compile_files(opts)
    to_diagnostics(caught, result.sink)
    to_stdout = opts.output in (None, "-")
    if opts.list_deps and ns is not None:
        write_rules(result, opts, ns)
    elif not streamed and not opts.syntax_only and not writes_own_output(opts) and (
            not result.sink.has_errors or (result.output and to_stdout)):
        write_output(result.output, opts.output, opts.inputs, result.sink)
    if ns is not None and (ns.write_deps or ns.write_deps_user) and not opts.list_deps:
        write_rules(result, opts, ns)
    sys.stderr.write(result.pass_report)
    report(result, rep)
    if any(d.code in (dg.BAD_OPTION, dg.BAD_PASS_SPEC) for d in result.sink):
        return 2  # a bad option value (a machine, -f dialect option, --compare ...) is a usage error
    return 1 if result.sink.has_errors else 0


if __name__ == "__main__":
    sys.exit(main())
