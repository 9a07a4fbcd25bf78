"""cncc batch benchmark: programs per second for -j 1, -j 2 and a 2-worker Dask LocalCluster.

Run: ``python bench/batch.py [--programs N] [-O LEVEL] [--quick]``.  One generated
library (bench/gen.py ``write_library``: several dialects, some with errors, no endless
loop) is run three times into fresh results files; each run includes starting its
sandbox children, the cluster's start is not counted (it is up before the clock).
Prints the machine load, then per mode: wall seconds, programs per second and its
ratio to -j 1 (wall figures: they scale only on cores nobody else uses), and the CPU
overhead per program: (CPU of every process of the run - compiler CPU) / programs,
i.e. what each program costs beyond its own compile (the parent, pipes, the sandbox
starts; for the cluster also the scheduler, the workers and their sandboxes), which a
loaded machine does not inflate.  The compiler CPU is the sum of the rows' ``cpu_s``;
the cluster's processes are measured with psutil (a dask.distributed dependency).
"of it idle": the part the processes spend when no task runs (the cluster's event
loops and heartbeats), which grows with the wall time, not with the programs.
"""

from __future__ import annotations

import argparse
import os
import resource
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "bench"))

from gen import write_library  # noqa: E402

from cncc.batch import RowOptions, run_batch  # noqa: E402
from cncc.batch.results import read_rows  # noqa: E402


def load() -> str:
    one, five, _ = os.getloadavg()
    return f"load average {one:.2f} (1 min), {five:.2f} (5 min) on {os.cpu_count()} CPUs"


def own_cpu_s() -> float:
    """CPU seconds of this process and of its children that have been waited for."""
    me, kids = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return me.ru_utime + me.ru_stime + kids.ru_utime + kids.ru_stime


def tree_cpu_s(pids: list[int]) -> float:
    """CPU seconds of the processes ``pids`` and of their living descendants (the workers' sandboxes)."""
    import psutil

    total = 0.0
    for pid in pids:
        try:
            proc = psutil.Process(pid)
            for p in [proc, *proc.children(recursive=True)]:
                t = p.cpu_times()
                total += t.user + t.system
        except psutil.Error:
            pass
    return total


IDLE_S = 5.0


def idle_rate(pids: list[int]) -> float:
    """CPU seconds per second that this process and ``pids`` spend doing nothing (a cluster's heartbeats)."""
    cpu0, tree0 = own_cpu_s(), tree_cpu_s(pids)
    time.sleep(IDLE_S)
    return (own_cpu_s() - cpu0 + tree_cpu_s(pids) - tree0) / IDLE_S


def timed(library: str, out: str, options: RowOptions, **how: Any) -> tuple[float, float, float, int, float]:
    """(wall s, CPU s of the run's processes, compiler CPU s, rows, idle CPU s per s) of one run."""
    client = how.get("client")
    pids = sorted(client.run(os.getpid).values()) if client is not None else []
    idle = idle_rate(pids)
    cpu0, tree0 = own_cpu_s(), tree_cpu_s(pids)
    t0 = time.perf_counter()
    with open(os.devnull, "w") as quiet:
        run_batch([library], ["generic-mill"], out, options=options, stream=quiet, **how)
    wall = time.perf_counter() - t0
    cpu = own_cpu_s() - cpu0 + tree_cpu_s(pids) - tree0
    rows = read_rows(out)
    return wall, cpu, sum(float(r["cpu_s"] or 0) for r in rows), len(rows), idle


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--programs", type=int, default=300)
    ap.add_argument("-O", dest="level", type=int, default=2)
    ap.add_argument("--quick", action="store_true", help="60 programs at -O1 (a smoke run, not for figures)")
    args = ap.parse_args()
    n, level = (60, 1) if args.quick else (args.programs, args.level)
    options = RowOptions(opt_level=level, max_steps=100_000, time_limit_s=60)
    print(f"before: {load()}")
    with tempfile.TemporaryDirectory() as tmp:
        library = os.path.join(tmp, "library")
        write_library(library, n, loop=False)
        results: dict[str, tuple[float, float, float, int, float]] = {}
        for label, jobs in (("-j 1", 1), ("-j 2", 2)):
            results[label] = timed(library, os.path.join(tmp, f"j{jobs}.csv"), options, jobs=jobs)
        try:
            from distributed import Client, LocalCluster
        except ImportError:
            print("LocalCluster: dask.distributed is not installed (pip install 'cncc[cluster]')")
        else:
            with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                              dashboard_address=None) as cluster, Client(cluster) as client:
                results["LocalCluster x2"] = timed(library, os.path.join(tmp, "dask.csv"), options,
                                                   client=client)
    base_rate = results["-j 1"][3] / results["-j 1"][0]
    print(f"{n} programs at -O{level} on generic-mill (one row each)")
    print(f"{'mode':<16} {'wall s':>8} {'programs/s':>11} {'ratio to -j 1':>14} {'CPU s':>8} {'compiler CPU s':>15} "
          f"{'CPU overhead ms/program':>24} {'of it idle':>11}")
    for label, (wall, cpu, compiler, rows, idle) in results.items():
        rate = rows / wall
        overhead_ms = (cpu - compiler) / rows * 1e3
        idle_ms = idle * wall / rows * 1e3
        print(f"{label:<16} {wall:8.2f} {rate:11.2f} {rate / base_rate:14.2f} {cpu:8.2f} {compiler:15.2f} "
              f"{overhead_ms:24.1f} {idle_ms:11.1f}")
    print(f"(idle: the processes' CPU while nothing runs, measured for {IDLE_S:g} s before each run, times its wall)")
    print(f"after: {load()}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
