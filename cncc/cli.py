"""The gcc-like command line: ``cncc [options] file...`` and ``cncc lsp``."""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Sequence
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
    p.add_argument("-t", "--target", help="target dialect for --emit=gcode (default: the input dialect)")
    p.add_argument("-m", "--machine", default="generic-mill", help="machine model name or TOML file")
    p.add_argument("--emit", default="canon", help="canon | ir | gcode | timing | pulses | none (default: canon)")
    p.add_argument("-o", dest="output", help="output file ('-' for standard output)")
    p.add_argument("-O", dest="opt_level", type=int, choices=range(4), default=2, metavar="LEVEL",
                   help="planner level: -O0 nominal, -O1 trapezoid, -O2 jerk-limited (default), -O3 optimal")
    p.add_argument("-f", dest="flags", action="append", default=[], metavar="FLAG",
                   help="-fsyntax-only, -fstrict, -frepair-arcs, -fno-block-delete, -fline-numbers, -fno-verify, "
                        "or a dialect option -fNAME=VALUE (e.g. -frapid_type=independent)")
    p.add_argument("-W", dest="warnings", action="append", default=[], metavar="WARN",
                   help="-Werror turns warnings into errors")
    p.add_argument("--offsets", dest="offsets_file", help="work offsets table (TOML)")
    p.add_argument("--tools", dest="tools_file", help="tool table (TOML or LinuxCNC .tbl)")
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
                   help="list the subprogram files the program calls, as 'program: file...'")
    m.add_argument("-E", dest="expand", action="store_true",
                   help="print the program flattened in its own dialect (macros, calls, loops and cycles "
                        "expanded; comments map blocks to source lines)")
    m.add_argument("--max-steps", type=int, default=5_000_000, metavar="N",
                   help="stop a program after N blocks and statements (default 5000000)")
    m.add_argument("--io", dest="io_file", metavar="FILE", help="input values for WAT, M input tests and #1000.. "
                   "(lines 'X12 = 1', 'M14 = on', '#1800 = 5')")
    m.add_argument("--write-dir", metavar="DIR",
                   help="the only folder SZGH FILEON/FILEMS may write programs into (default: write nothing)")
    p.add_argument("--version", action="version", version=f"cncc {__version__}")
    return p


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


def build_options(ns: argparse.Namespace, error: Any) -> Any:
    from cncc.driver import Options

    opts = Options(inputs=list(ns.inputs), dialect=ns.dialect, target=ns.target, machine=ns.machine,
                   emit=ns.emit, output=ns.output, opt_level=ns.opt_level, offsets_file=ns.offsets_file,
                   tools_file=ns.tools_file, report_format=ns.report_format,
                   compare=ns.compare, annotate_time=ns.annotate_time,
                   pulse_format=ns.pulse_format, pulse_mode=ns.pulse_mode)
    opts.verbose = ns.verbose
    for flag in ns.flags:
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
        elif "=" in flag:
            key, _, val = flag.partition("=")
            opts.dialect_options[key.replace("-", "_")] = _value(val)
        else:
            error(f"unknown flag -f{flag}")
    _macro_options(opts, ns, error)
    opts.units, opts.keep_subprograms = ns.units, ns.keep_subprograms
    for item in ns.target_option:
        key, sep, val = item.partition("=")
        if not sep or not key:
            error(f"--target-option {item}: expected NAME=VALUE")
        opts.target_options[key.replace("-", "_")] = _value(val)
    opts.decimals_mm, opts.decimals_inch = ns.decimals_mm, ns.decimals_inch
    for w in ns.warnings:
        if w == "error":
            opts.werror = True
        else:
            error(f"unknown warning option -W{w}")
    return opts


def main(argv: Sequence[str] | None = None) -> int:
    args = list(sys.argv[1:] if argv is None else argv)
    if args[:1] == ["lsp"]:
        from cncc.lsp import serve

        return serve(args[1:])
    if args[:1] == ["batch"]:  # program libraries (cncc/batch, docs/batch.md)
        from cncc.batch.command import main as batch_main

        return batch_main(args[1:])
    parser = _parser()
    ns = parser.parse_args(args)
    opts = build_options(ns, parser.error)
    try:
        return run(opts)
    except KeyboardInterrupt:
        return 130
    except Exception as exc:  # an internal error is a bug: say so without a traceback
        if os.environ.get("CNCC_DEBUG"):
            raise
        sys.stderr.write(f"cncc: internal compiler error: {type(exc).__name__}: {exc}\n"
                         "cncc: please report this with the input; CNCC_DEBUG=1 shows the traceback\n")
        return 4


def run(opts: Any) -> int:
    from cncc.driver import compile_files, write_output, writes_own_output
    from cncc.render import render

    result = compile_files(opts)
    to_stdout = opts.output in (None, "-")
    if not opts.syntax_only and not writes_own_output(opts) and (
            not result.sink.has_errors or (result.output and to_stdout)):
        write_output(result.output, opts.output, opts.inputs, result.sink)
    err = sys.stderr
    for d in result.sink:
        for chunk in render(d, result.sources):
            err.write(chunk)
    if result.sink.dropped:
        err.write(f"cncc: {result.sink.dropped} more diagnostics not shown\n")
    n_err = result.sink.error_count
    if n_err:
        err.write(f"{n_err} error{'s' if n_err != 1 else ''} generated.\n")
    return 1 if result.sink.has_errors else 0


if __name__ == "__main__":
    sys.exit(main())
