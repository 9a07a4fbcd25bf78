"""Whole-pipeline throughput: the commands users run, as whole processes.

    python bench/pipeline.py [--lines 100000,1000000] [--kinds plain,arcs,transformed]
                             [--commands syntax,canon,grbl,timing0] [--before TREE]

For each generated CAM file (a plain G1 raster, G1 with 10 % G2/G3 arcs whose centres
are consistent, and a program under G68 rotation + G51 scaling + G41 cutter comp)
this runs, each as a fresh process:

* ``cncc -fsyntax-only F``
* ``cncc F --emit=canon -o /dev/null``
* ``cncc -t grbl F --emit=gcode -o /dev/null``
* ``cncc F --emit=timing -O0 --report-format=json -o /dev/null``

and, as baselines in the same run, ``gcodeparser`` (tokenising only) and ``pygcode``
(parsing only) over the same file, also as fresh processes.  It prints CPU seconds
(user + system of the child, from ``os.wait4``) and peak RSS (the child's
``ru_maxrss``) for each, and the ratio baseline CPU / cncc CPU (> 1 means cncc is
faster).  Goals (issue 15, plain 1M-line file): -fsyntax-only >= 4x gcodeparser,
canon and grbl >= 2x, timing -O0 >= 1x, peak RSS < 300 MB each; the transformed
program within 2x of the plain one.

``--before TREE`` also runs every cncc command from another checkout (e.g. an export of
``main``) on the same file in the same run and prints the before/after CPU ratio.

Byte code: the baselines are installed packages, whose modules load from ``__pycache__``;
cncc runs from source trees, and with ``PYTHONDONTWRITEBYTECODE`` set (as in the
development shell) every cncc process would compile its ~240 modules first (about 0.4 s).
So that every program is measured as installed, the children get a byte-code cache
(``PYTHONPYCACHEPREFIX`` in the bench's temporary directory, filled by ``compileall`` for
each tree before the first run); ``--no-bytecode-cache`` measures the compiling instead.
"""

from __future__ import annotations

import argparse
import math
import os
import random
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

COMMANDS: dict[str, list[str]] = {
    "syntax": ["-fsyntax-only"],
    "canon": ["--emit=canon", "-o", os.devnull],
    "grbl": ["-t", "grbl", "--emit=gcode", "-o", os.devnull],
    "timing0": ["--emit=timing", "-O0", "--report-format=json", "-o", os.devnull],
}

GCODEPARSER = """
import sys
from gcodeparser import parse_gcode_lines
n = 0
with open(sys.argv[1]) as f:
    for _ in parse_gcode_lines(f.read()):
        n += 1
print(n)
"""

PYGCODE = """
import sys
from pygcode import Line
n = 0
with open(sys.argv[1]) as f:
    for text in f:
        Line(text)
        n += 1
print(n)
"""


def raster(n_lines: int, arcs: bool, seed: int = 7) -> list[str]:
    """A zig-zag raster of 0.5 mm G1 steps; with ``arcs``, about 10 % of the blocks are
    G2/G3 semicircle turnarounds between passes (centre = midpoint, so I/J are exact)."""
    rnd = random.Random(seed)
    body: list[str] = []
    x, y = 0.0, 0.0
    direction = 1.0
    pass_len = 20 if arcs else 200  # blocks per pass: with arcs, ~1 turn per 10 blocks
    k = 0
    while len(body) < n_lines:
        k += 1
        if k % pass_len == 0:
            step = 1.0
            if arcs:
                code = "G03" if direction > 0 else "G02"
                body.append(f"{code} X{x:.3f} Y{y + step:.3f} I0.0 J{step / 2:.3f}")
            else:
                body.append(f"G1 Y{y + step:.3f}")
            y += step
            direction = -direction
            continue
        x = round(x + direction * 0.5, 3)
        z = round(-1.0 + 0.05 * math.sin(k / 50.0) + rnd.uniform(-0.001, 0.001), 3)
        body.append(f"G1 X{x:.3f} Z{z:.3f}")
    return body


def program(kind: str, n_lines: int) -> str:
    head = ["%", "O1000 (cncc pipeline bench)", "G90 G17 G71 G94", "G00 X0.0 Y0.0 Z5.0", "S12000 M03"]
    if kind == "plain":
        pre, body, post = ["G01 Z-1.0 F1500"], raster(n_lines - 9, arcs=False), []
    elif kind == "arcs":
        pre, body, post = ["G01 Z-1.0 F1500"], raster(n_lines - 9, arcs=True), []
    elif kind == "transformed":
        pre = ["G68 X0.0 Y0.0 R15.0", "G51 X0.0 Y0.0 P0.8", "G01 G41 D1 X1.0 Y1.0 Z-1.0 F1500"]
        body = raster(n_lines - 13, arcs=True)
        post = ["G40 G01 X0.0 Y0.0", "G50", "G69"]
    else:  # pragma: no cover - argparse restricts it
        raise SystemExit(f"unknown kind {kind}")
    tail = ["G00 Z5.0", "M05", "M30", "%"]
    return "\n".join(head + pre + body + post + tail) + "\n"


PYCACHE: dict[str, str] = {}  # PYTHONPYCACHEPREFIX for the children ({} : none)


def run(argv: list[str], cwd: str = ROOT) -> tuple[float, float, int]:
    """CPU seconds (user + sys), peak RSS in MB and exit status of one child process."""
    env = dict(os.environ, PYTHONPATH=cwd)
    if PYCACHE:
        env.pop("PYTHONDONTWRITEBYTECODE", None)
        env.update(PYCACHE)
    proc = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, cwd=cwd, env=env)
    assert proc.stderr is not None
    err = proc.stderr.read()
    _, status, ru = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    if proc.returncode != 0:
        sys.stderr.write(f"{' '.join(argv[-3:])}: exit {proc.returncode}\n{err.decode(errors='replace')[-1500:]}\n")
    return ru.ru_utime + ru.ru_stime, ru.ru_maxrss / 1024.0, proc.returncode


def main() -> int:
    if sys.argv[1:2] == ["--write"]:  # --write KIND LINES PATH (the generator, in a child process)
        kind, n, path = sys.argv[2], int(sys.argv[3]), sys.argv[4]
        with open(path, "w") as f:
            f.write(program(kind, n))
        return 0
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--lines", default="100000,1000000")
    ap.add_argument("--kinds", default="plain,arcs,transformed")
    ap.add_argument("--commands", default=",".join(COMMANDS))
    ap.add_argument("--tools", default=None, help="tool table for the comp program (default: a generated one)")
    ap.add_argument("--before", default=None, help="another cncc tree to run the same commands from (before/after)")
    ap.add_argument("--no-bytecode-cache", action="store_true", help="let every cncc process compile its modules")
    args = ap.parse_args()
    before = os.path.abspath(args.before) if args.before else None
    sizes = [int(s) for s in args.lines.split(",") if s]
    kinds = [k for k in args.kinds.split(",") if k]
    commands = [c for c in args.commands.split(",") if c]
    cncc = [sys.executable, "-m", "cncc"]
    with tempfile.TemporaryDirectory(prefix="cncc-bench-") as tmp:
        if not args.no_bytecode_cache:
            PYCACHE["PYTHONPYCACHEPREFIX"] = os.path.join(tmp, "pycache")
            warm = os.path.join(tmp, "warm.nc")
            with open(warm, "w") as f:
                f.write(program("arcs", 200))
            for tree in [ROOT] + ([before] if before else []):
                run([sys.executable, "-m", "compileall", "-q", os.path.join(tree, "cncc")], cwd=tree)
                for name in commands:  # one warm-up run of each command (file cache, lazily imported modules)
                    run([*cncc, "-x", "syntec", *COMMANDS[name], warm], cwd=tree)
        tools = os.path.join(tmp, "tools.toml")
        with open(tools, "w") as f:
            f.write("units = \"mm\"\n[tools.1]\nlength_mm = 0.0\nradius_mm = 0.2\n")
        print(f"{'file':>22} {'command':>12} {'cpu s':>8} {'peak MB':>8} {'exit':>4} "
              f"{'vs gcodeparser':>15} {'vs pygcode':>11}")
        plain_cpu: dict[tuple[int, str], float] = {}
        for n in sizes:
            for kind in kinds:
                path = os.path.join(tmp, f"{kind}-{n}.nc")
                # written by a child: a child's peak RSS starts from its parent's at fork (Linux keeps
                # the high-water mark across exec), so this process must stay small
                subprocess.run([sys.executable, __file__, "--write", kind, str(n), path], check=True)
                base_gp, rss_gp, _code = run([sys.executable, "-c", GCODEPARSER, path])
                base_pg, rss_pg, _code = run([sys.executable, "-c", PYGCODE, path])
                label = f"{kind} {n:,}"
                print(f"{label:>22} {'gcodeparser':>12} {base_gp:8.2f} {rss_gp:8.0f} {'':>4}")
                print(f"{label:>22} {'pygcode':>12} {base_pg:8.2f} {rss_pg:8.0f} {'':>4}")
                for name in commands:
                    extra = ["-x", "syntec", "--tools", tools] if kind == "transformed" else ["-x", "syntec"]
                    cpu, rss, code = run([*cncc, *extra, *COMMANDS[name], path])
                    if kind == "plain":
                        plain_cpu[(n, name)] = cpu
                    rel = ""
                    if kind == "transformed" and (n, name) in plain_cpu:
                        rel = f"  ({cpu / plain_cpu[(n, name)]:.2f}x plain)"
                    if before is not None:
                        old_cpu, old_rss, old_code = run([*cncc, *extra, *COMMANDS[name], path], cwd=before)
                        print(f"{label:>22} {name + ' before':>19} {old_cpu:8.2f} {old_rss:8.0f} {old_code:>4} "
                              f"{base_gp / old_cpu:14.2f}x {base_pg / old_cpu:10.2f}x", flush=True)
                        rel += f"  ({old_cpu / cpu:.2f}x faster than before)"
                    print(f"{label:>22} {name:>12} {cpu:8.2f} {rss:8.0f} {code:>4} "
                          f"{base_gp / cpu:14.2f}x {base_pg / cpu:10.2f}x{rel}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
