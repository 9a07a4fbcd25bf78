"""Whole-process CPU time of ``cncc -x linuxcnc --emit=canon`` on long LinuxCNC programs (issue 24's
169k-move program), beside LinuxCNC 2.9's ``rs274`` on the same files when it is installed.

    python bench/linuxcnc.py [--moves 169000]

Programs: ``plain`` (one G1 per line), ``loops`` (a while loop of plain moves with a repeat
of subroutine calls and an if/break inside), ``owords`` (many short while loops whose moves
are expressions).  CPU seconds of the child process (user + system), one run each.
"""

from __future__ import annotations

import argparse
import os
import random
import resource
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def programs(moves: int) -> dict[str, str]:
    r = random.Random(1)
    plain = ["G21 G90 G17 F500"] + [f"G1 X{r.uniform(-50, 50):.3f} Y{r.uniform(-50, 50):.3f}" for _ in range(moves)]
    per_pass = 80  # 40 plain moves and 20 calls of two moves
    loops = ["G21 G90 G17 F500", "#<n>=0", "o100 sub", "G1 X[#1] Y[#2]", "G1 X[#1+1] Y#2", "o100 endsub",
             f"o1 while [#<n> LT {moves // per_pass}]"]
    loops += [f"G1 X{r.uniform(-50, 50):.3f} Y{r.uniform(-50, 50):.3f}" for _ in range(40)]
    loops += ["o2 repeat [20]", "o100 call [#<n>/10] [2]", "o3 if [#<n> GT 1000000000]", "o1 break", "o3 endif",
              "o2 endrepeat", "#<n>=[#<n>+1]", "o1 endwhile"]
    owords = ["G21 G90 G17 F500"]
    for k in range(moves // 30):
        owords += ["#<i>=0", f"o{k + 1000} while [#<i> LT 30]", f"G1 X[#<i>] Y{r.uniform(-5, 5):.3f}",
                   f"o{k + 200000} if [#<i> GT 40]", f"o{k + 1000} break", f"o{k + 200000} endif", "#<i>=[#<i>+1]",
                   f"o{k + 1000} endwhile"]
    return {name: "\n".join([*lines, "M2"]) + "\n" for name, lines in
            (("plain", plain), ("loops", loops), ("owords", owords))}


def cpu_s(cmd: list[str], env: dict[str, str] | None = None) -> float:
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env, check=False)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--moves", type=int, default=169_000)
    args = ap.parse_args()
    sys.path.insert(0, ROOT)
    from tests.oracle.harness import rs274_path

    rs274 = rs274_path()
    env = {**os.environ, "PYTHONPATH": ROOT}
    with tempfile.TemporaryDirectory(prefix="cncc-bench-") as tmp:
        tbl = os.path.join(tmp, "tool.tbl")
        open(tbl, "w").close()
        for name, text in programs(args.moves).items():
            path = os.path.join(tmp, f"{name}.ngc")
            with open(path, "w") as fh:
                fh.write(text)
            ours = cpu_s([sys.executable, "-m", "cncc", "-x", "linuxcnc", path, "--emit=canon", "-o", os.devnull], env)
            theirs = cpu_s([str(rs274), "-t", tbl, "-g", path]) if rs274 else float("nan")
            print(f"{name:7} {text.count(chr(10)):7d} lines  cncc {ours:6.2f} s CPU  rs274 {theirs:6.2f} s CPU")
    return 0


if __name__ == "__main__":
    sys.exit(main())
