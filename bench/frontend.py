"""Front-end throughput: cncc (parse + modal interpretation + lowering to IR)
beside gcodeparser (tokenising only) on the same generated CAM-style file.

    python bench/frontend.py [--lines N]

Prints blocks per second for both, their ratio (goal: cncc >= 2x gcodeparser), and
cncc's peak memory (goal: < 1 GB for 1,000,000 lines), measured with tracemalloc in
a separate run so it does not slow the timed one, and as the peak RSS of a fresh
process.  Each tool is timed as the best CPU time of ``--repeat`` runs.
"""

from __future__ import annotations

import argparse
import gc
import os
import subprocess
import sys
import time
import tracemalloc

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gen import cam_program


def run_cncc(text: str) -> int:
    from cncc.diagnostics import DiagnosticSink
    from cncc.dialects import load_dialect
    from cncc.frontend import lower
    from cncc.source import SourceMap

    src = SourceMap().add("bench.nc", text)
    sink = DiagnosticSink()
    n = 0
    for _ in lower(src, load_dialect("syntec"), sink):
        n += 1
    if sink.has_errors:
        raise SystemExit(f"cncc reported errors: {[d.message for d in list(sink)[:3]]}")
    return n


def run_gcodeparser(text: str) -> int:
    from gcodeparser import parse_gcode_lines

    n = 0
    for _ in parse_gcode_lines(text):
        n += 1
    return n


def best_of(fn, text: str, repeat: int) -> float:  # type: ignore[no-untyped-def]
    """Best CPU time (``time.process_time``) of ``repeat`` runs: on a shared machine the
    process's CPU time is far steadier than wall-clock time, and both tools are
    single-threaded, so their ratio is what a quiet machine would show."""
    best = float("inf")
    for _ in range(repeat):
        gc.collect()
        t0 = time.process_time()
        fn(text)
        best = min(best, time.process_time() - t0)
    return best


def peak_rss_child(n_lines: int) -> float:
    """Peak RSS (MB) of a fresh process that generates and lowers the file."""
    here = os.path.dirname(os.path.abspath(__file__))
    code = (
        f"import sys, resource; sys.path.insert(0, {here!r}); from gen import cam_program; "
        f"from frontend import run_cncc; t = cam_program({n_lines}); run_cncc(t); "
        "print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return float(out.stdout.strip())


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--lines", type=int, default=1_000_000)
    ap.add_argument("--repeat", type=int, default=2)
    args = ap.parse_args()
    text = cam_program(args.lines)
    n_lines = text.count("\n")
    t_g = best_of(run_gcodeparser, text, args.repeat)
    t_c = best_of(run_cncc, text, args.repeat)
    print(f"frontend: {n_lines:,} lines, {len(text) / 1e6:.1f} MB")
    print(f"  gcodeparser (tokenise only)        {n_lines / t_g:12,.0f} blocks/s  ({t_g:.2f} s CPU)")
    print(f"  cncc (parse + interpret + lower)   {n_lines / t_c:12,.0f} blocks/s  ({t_c:.2f} s CPU)")
    print(f"  ratio cncc / gcodeparser           {t_g / t_c:12.2f} x   (goal >= 2)")
    tracemalloc.start()
    run_cncc(text)
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    print(f"  cncc traced peak (excluding the text) {peak / 2**20:9.1f} MB")
    rss = peak_rss_child(args.lines)
    print(f"  cncc peak RSS, fresh process          {rss:9.1f} MB   (goal < 1024)")


if __name__ == "__main__":
    main()
