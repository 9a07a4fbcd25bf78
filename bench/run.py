"""Run every benchmark in this folder, one after the other, and print their reports.

    python bench/run.py [--quick]

Each script measures cncc beside a baseline in the same run (gcodeparser for the
front end, gcodeparser and pygcode as whole processes for the pipeline, the plain-block
rate for macros, a numpy pass for pulses, -O3 and exact
stop for the planner) and prints ratios, so the figures compare across machines.
``--quick`` passes smaller sizes to each script (for a smoke run, not for figures).
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPTS = [
    ("frontend.py", ["--lines", "1000000"], ["--lines", "50000", "--repeat", "2"]),
    ("macros.py", [], ["--rows", "100", "--cols", "100", "--plain-lines", "50000"]),
    ("planner.py", [], ["--quick"]),
    ("pulses.py", ["--steps", "100000000"], ["--steps", "2000000", "--repeat", "1"]),
    ("planner.py", ["--scale", "1000,10000,100000", "--scale-only", "--o3"], ["--scale", "1000", "--scale-only"]),
    ("pulses.py", ["--whole", "100000"], ["--whole", "10000"]),
    ("lsp.py", [], ["--lines", "2000", "--edits", "3"]),
    ("pipeline.py", [], ["--lines", "20000"]),
    ("report.py", [], ["--quick"]),
    ("batch.py", [], ["--quick"]),
    ("linuxcnc.py", [], ["--moves", "10000"]),
]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    failed = 0
    for name, full, quick in SCRIPTS:
        path = os.path.join(HERE, name)
        if not os.path.exists(path):
            print(f"== {name}: not present")
            continue
        print(f"== {name}", flush=True)
        t0 = time.perf_counter()
        p = subprocess.run([sys.executable, path, *(quick if args.quick else full)])
        print(f"== {name}: exit {p.returncode}, {time.perf_counter() - t0:.1f} s\n", flush=True)
        failed += p.returncode != 0
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
