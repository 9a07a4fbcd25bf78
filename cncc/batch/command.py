"""``cncc batch``: audit and time a library of programs (docs/batch.md)."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from cncc import diagnostics as dg
from cncc.batch.options import DEFAULT_MEMORY_LIMIT_MB, DEFAULT_TIME_LIMIT_S, EMITS, RowOptions
from cncc.source import NO_SPAN

USAGE = "cncc batch DIR|GLOB|FILE... -m MACHINE [-m MACHINE...] [--emit=timing|lint] -o results.(csv|jsonl|parquet)"


def parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="cncc batch", usage=USAGE, description=(
        "One row per program and machine: diagnostics by code, cycle time at -O<level> by category, "
        "tools, extents, soft-limit violations, CPU time.  Rows are appended as they arrive; a rerun "
        "with the same -o computes only the programs it has no row for."))
    ap.add_argument("inputs", nargs="+", metavar="DIR|GLOB|FILE")
    ap.add_argument("-m", "--machine", action="append", dest="machines", metavar="MACHINE",
                    help="a machine model (repeat for several; default generic-mill)")
    ap.add_argument("--emit", choices=EMITS, default="timing",
                    help="timing: plan every program (default); lint: diagnostics only, no plan")
    ap.add_argument("-o", "--output", required=True, metavar="FILE", help="results.csv, .jsonl or .parquet")
    ap.add_argument("-O", dest="opt_level", type=int, choices=(0, 1, 2, 3), default=2, metavar="LEVEL",
                    help="the planner level of the cycle time (default 2)")
    ap.add_argument("-x", dest="dialect", metavar="DIALECT", help="the programs' dialect (default: guessed per file)")
    ap.add_argument("-j", "--jobs", type=int, default=1, metavar="N", help="local worker processes (default 1)")
    ap.add_argument("--dask", metavar="SCHEDULER_ADDRESS", help="run on a Dask cluster (tcp://host:8786)")
    ap.add_argument("--time-limit", type=float, default=DEFAULT_TIME_LIMIT_S, metavar="SECONDS",
                    help=f"CPU seconds per program (default {DEFAULT_TIME_LIMIT_S:g}; 0: none)")
    ap.add_argument("--memory-limit", type=int, default=DEFAULT_MEMORY_LIMIT_MB, metavar="MB",
                    help=f"address space of a compiling process (default {DEFAULT_MEMORY_LIMIT_MB}; 0: none)")
    ap.add_argument("--max-steps", type=int, default=5_000_000, metavar="N",
                    help="macro steps per program before E0301 (default 5000000)")
    ap.add_argument("--offsets", action="append", default=[], metavar="[MACHINE=]FILE",
                    help="work offsets (TOML) for every machine or for one; the soft limits are checked with them")
    ap.add_argument("--strict", action="store_true", help="as cncc --strict")
    return ap


def fail(code: str, message: str) -> int:
    sys.stderr.write(f"cncc batch: error: {message} [{code}]\n")
    return 1


def main(argv: Sequence[str]) -> int:
    ns = parser().parse_args(list(argv))
    from cncc.batch.engine import run_batch
    from cncc.batch.results import ResultsError, format_of
    from cncc.diagnostics import DiagnosticSink
    from cncc.driver import Options as DriverOptions
    from cncc.driver import resolve_dialect, resolve_machine

    machines = ns.machines or ["generic-mill"]
    sink = DiagnosticSink()
    for m in machines:
        resolve_machine(m, sink)
    if ns.dialect:
        resolve_dialect(DriverOptions(dialect=ns.dialect), sink)
    if ns.jobs < 1:
        sink.emit(dg.BAD_OPTION, NO_SPAN, "-j takes a count of 1 or more")
    for d in sink:
        return fail(d.code, d.message)
    offsets: dict[str | None, str] = {}
    for item in ns.offsets:
        machine, sep, path = item.rpartition("=")
        if sep and machine not in machines:
            return fail(dg.BAD_OPTION, f"--offsets {item}: {machine} is not one of the -m machines")
        try:
            with open(path, encoding="utf-8") as fh:
                offsets[machine or None] = fh.read()
        except OSError as exc:
            return fail(dg.CANNOT_READ, f"cannot read {path}: {exc.strerror or exc}")
    options = {m: RowOptions(emit=ns.emit, opt_level=ns.opt_level, max_steps=ns.max_steps,
                             time_limit_s=ns.time_limit, memory_limit_mb=ns.memory_limit,
                             offsets_text=offsets.get(m, offsets.get(None)), strict=ns.strict) for m in machines}
    try:
        format_of(ns.output)
        client = None
        if ns.dask:
            from cncc.batch.cluster import connect

            client = connect(ns.dask)
        try:
            summary = run_batch(ns.inputs, machines, ns.output, options=options, dialect=ns.dialect,
                                jobs=ns.jobs, client=client)
        finally:
            if client is not None:
                client.close()
    except ResultsError as exc:
        return fail(dg.BATCH_RESULTS, str(exc))
    except LookupError as exc:
        return fail(dg.BATCH_NO_PROGRAMS, str(exc))
    except (RuntimeError, OSError) as exc:  # no dask installed, no scheduler at that address
        return fail(dg.BATCH_RESULTS, str(exc) or type(exc).__name__)
    return 130 if summary.interrupted else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
