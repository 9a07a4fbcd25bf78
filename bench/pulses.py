"""Pulse backend benchmark: steps generated per second and peak memory.

Builds a 3-axis program of straight S-curve moves (7 constant-jerk phases each) with
about ``--steps`` steps in total (default 10^8), streams it through
:func:`cncc.backends.pulses.generate_pulses` and prints steps/s, then the peak
memory traced during a further pass, beside the time a plain numpy pass (a cubic
evaluated at the same number of samples, in chunks of the same size) takes.  The
generation is run ``--repeat`` times; the best wall-clock time is reported with the
CPU time of that run and the load average, because the machine may be shared.

    python bench/pulses.py [--steps 100000000] [--mode exact|interp] [--chunk 262144] [--repeat 3]
    python bench/pulses.py --whole 100000     # whole process on the raster kind of bench/pathgen.py

``--whole N`` instead runs ``cncc raster.nc --emit=pulses --pulse-format=queue`` as a child
on the N-segment raster of ``bench/pathgen.py`` (``BENCH_MILL``: generic-mill with Z soft max
10 mm, since the program's clearance moves go to Z5, and X, Y within +-1 m): steps per CPU
second of the child (user + system, ``os.wait4``), its peak RSS, and the steps counted in the written queue (goal >= 1 M
steps/s whole process, streamed).

``--before TREE`` (e.g. ``/work/before3``) runs the same whole-process commands from that
tree too, in the same run, on three programs: the raster (``--whole`` segments, default
100k), an arc contour (``--arcs``, default 1k arcs) and a random walk (``--walk``, default
2k segments).  Per program and tree it prints the steps, the CPU s and peak RSS of
``--emit=pulses`` (queue and VCD), and the pulse stage alone: that CPU minus the CPU of
``--emit=timing`` on the same file (planning, verify and the report), as steps per second.

    python bench/pulses.py --before /work/before3 [--whole 100000 --arcs 1000 --walk 2000] [--only arcs,walk]
"""

from __future__ import annotations

import argparse
import contextlib
import os
import time
import tracemalloc
from pathlib import Path

import numpy as np

from cncc.backends.pulses import generate_pulses
from cncc.backends.pulses.generate import DEFAULT_CHUNK_STEPS
from cncc.ir.machine import Axis, MachineModel, StepOutput
from cncc.ir.trajectory import Trajectory

STEPS_PER_MM = 1000.0
V_MM_S, A_MM_S2, J_MM_S3 = 100.0, 1000.0, 20000.0


def program(total_steps: int, seed: int = 1) -> Trajectory:
    """Rest-to-rest S-curve moves in random directions, ~60 mm each."""
    rng = np.random.default_rng(seed)
    tj = A_MM_S2 / J_MM_S3
    ta = V_MM_S / A_MM_S2 - tj
    ramp_mm = V_MM_S * (ta + 2 * tj)  # distance of accel + decel
    length = 60.0
    cruise = (length - ramp_mm) / V_MM_S
    u = rng.normal(size=(max(1, int(total_steps / (length * STEPS_PER_MM * 1.5))), 3))
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    per_move = np.abs(u).sum(axis=1) * length * STEPS_PER_MM
    moves = int(np.searchsorted(np.cumsum(per_move), total_steps)) + 1
    u = u[:moves] if moves <= u.shape[0] else np.vstack([u] * (moves // u.shape[0] + 1))[:moves]
    dur1 = np.array([tj, ta, tj, cruise, tj, ta, tj])
    a1 = np.array([0.0, A_MM_S2, A_MM_S2, 0.0, 0.0, -A_MM_S2, -A_MM_S2])
    j1 = np.array([J_MM_S3, 0.0, -J_MM_S3, 0.0, -J_MM_S3, 0.0, J_MM_S3])
    v1 = np.zeros(7)
    s1 = np.zeros(7)
    for k in range(6):  # path-coordinate start states of the 7 phases
        t = dur1[k]
        s1[k + 1] = s1[k] + v1[k] * t + a1[k] * t * t / 2 + j1[k] * t**3 / 6
        v1[k + 1] = v1[k] + a1[k] * t + j1[k] * t * t / 2
    n = moves * 7
    dur = np.tile(dur1, moves)
    t0 = np.concatenate([[0.0], np.cumsum(dur)[:-1]])
    start = np.concatenate([np.zeros((1, 3)), np.cumsum(u * length, axis=0)[:-1]])
    uu = np.repeat(u, 7, axis=0)
    p0 = np.repeat(start, 7, axis=0) + uu * np.tile(s1, moves)[:, None]
    v0 = uu * np.tile(v1, moves)[:, None]
    a0 = uu * np.tile(a1, moves)[:, None]
    j = uu * np.tile(j1, moves)[:, None]
    cmd = np.repeat(np.arange(moves, dtype=np.int64), 7)
    return Trajectory(t0, dur, p0, v0, a0, j, cmd, np.zeros(n, np.int8), ("X", "Y", "Z"))


def machine() -> MachineModel:
    step = StepOutput(steps_per_mm=STEPS_PER_MM, max_step_rate_hz=2e6, pulse_width_ns=100, dir_setup_ns=200)
    return MachineModel("bench", tuple(Axis(a, step=step) for a in "XYZ"))


def run(traj: Trajectory, mode: str, chunk: int) -> tuple[int, float, float]:
    """(steps, wall-clock seconds, CPU seconds) of one generation pass."""
    t, c0 = time.perf_counter(), time.process_time()
    total = 0
    for c in generate_pulses(traj, machine(), mode=mode, chunk_steps=chunk):
        total += c.step_count
    return total, time.perf_counter() - t, time.process_time() - c0


def numpy_pass(samples: int, chunk: int) -> float:
    """A plain numpy pass: evaluate one cubic at ``samples`` points, ``chunk`` at a time."""
    t = time.perf_counter()
    p0, v0, a0, j = 1.0, 100.0, 1000.0, 20000.0
    acc = 0.0
    for lo in range(0, samples, chunk):
        tau = np.arange(lo, min(lo + chunk, samples), dtype=np.float64) * 1e-6
        p = p0 + tau * (v0 + tau * (a0 / 2 + tau * j / 6))
        acc += float(p[-1])
    return time.perf_counter() - t


BENCH_MILL = """base = "generic-mill"
name = "bench-mill"
[[axes]]
name = "X"
soft_min_mm = -1000.0
soft_max_mm = 1000.0
[[axes]]
name = "Y"
soft_min_mm = -1000.0
soft_max_mm = 1000.0
[[axes]]
name = "Z"
soft_max_mm = 10.0
"""
"""generic-mill with room for the benchmark programs: Z up to the clearance moves' Z5, X and Y
to +-1 m (the 1k-arc contour and the random walk leave generic-mill's X, Y >= -1 mm)."""


def whole_process(n: int, mode: str, limit_s: float = 1800.0) -> None:
    import sys
    import tempfile

    here = Path(__file__).resolve().parent
    sys.path.insert(0, str(here))
    from pathgen import KINDS
    from scale import run_cncc

    with tempfile.TemporaryDirectory() as tmp:
        src, mill, out = Path(tmp) / "raster.nc", Path(tmp) / "bench-mill.toml", Path(tmp) / "raster.queue"
        src.write_text(KINDS["raster"](n))
        mill.write_text(BENCH_MILL)
        load = os.getloadavg()
        r = run_cncc(src, ["-m", str(mill), "--emit=pulses", "--pulse-format=queue", f"--pulse-mode={mode}",
                           "-o", str(out)], limit_s)
        steps = 0
        if r.rc == 0:
            with out.open() as fh:
                for row in fh:
                    if row.startswith("queue_step"):
                        steps += int(row.split()[3])
        print(f"whole process, --emit=pulses --pulse-format=queue --pulse-mode={mode}, raster {n:,} segments, "
              f"load {load[0]:.1f}/{load[1]:.1f} on {os.cpu_count()} cores")
        if r.rc != 0:
            print(f"  exit {r.rc}: {r.stderr.strip()[-400:]}")
            return
        print(f"  {steps:,} steps in {r.cpu_s:.2f} CPU s: {steps / r.cpu_s / 1e6:.2f} M steps per CPU second "
              f"(goal >= 1), peak RSS {r.rss_mb:.0f} MB")


def _child(tree: Path, src: Path, args: list[str], limit_s: float) -> tuple[float, float, int]:
    """(CPU s, peak RSS MB, exit code; -1 killed) of ``cncc SRC ARGS`` run from ``tree``."""
    import signal
    import subprocess
    import sys
    import tempfile

    env = dict(os.environ, PYTHONPATH=str(tree))
    rss_file = src.with_suffix(".rss")
    timer = ["/usr/bin/time", "-f", "%M", "-o", str(rss_file)] if os.path.exists("/usr/bin/time") else []
    with tempfile.TemporaryFile() as err:
        proc = subprocess.Popen([*timer, sys.executable, "-m", "cncc", str(src), *args], stdout=subprocess.DEVNULL,
                                stderr=err, env=env, start_new_session=True, cwd=str(tree))
        start = time.monotonic()
        while True:
            pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
            if pid:
                break
            if time.monotonic() - start > limit_s:
                os.killpg(proc.pid, signal.SIGKILL)
                pid, status, usage = os.wait4(proc.pid, 0)
                return limit_s, float("nan"), -1
            time.sleep(0.02)
    rss = usage.ru_maxrss / 1024
    if timer:
        with contextlib.suppress(OSError, ValueError, IndexError):
            rss = int(rss_file.read_text().split()[-1]) / 1024
    return usage.ru_utime + usage.ru_stime, rss, os.waitstatus_to_exitcode(status)


def _queue_steps(path: Path) -> int:
    steps = 0
    with path.open() as fh:
        for row in fh:
            if row.startswith("queue_step"):
                steps += int(row.split()[3])
    return steps


def before_after(before: str, sizes: dict[str, int], limit_s: float) -> None:
    """Before/after of the whole process on each program (see the module docstring)."""
    import sys
    import tempfile
    here = Path(__file__).resolve().parent
    sys.path.insert(0, str(here))
    from pathgen import KINDS

    trees = (("before", Path(before).resolve()), ("after", here.parent))
    load = os.getloadavg()
    print(f"--emit=pulses whole process, before = {before}, after = {here.parent}; -O2, bench-mill "
          f"(generic-mill, soft limits Z <= 10, X, Y +-1000 mm); load {load[0]:.1f}/{load[1]:.1f} "
          f"on {os.cpu_count()} cores")
    print(f"{'program':<22} {'tree':<7} {'steps':>12} {'fmt':>6} {'CPU s':>8} {'RSS MB':>7} {'M steps/s':>10} "
          f"{'timing CPU s':>13} {'pulse stage M steps/s':>22}")
    with tempfile.TemporaryDirectory() as tmp:
        mill = Path(tmp) / "bench-mill.toml"
        mill.write_text(BENCH_MILL)
        for kind, n in sizes.items():
            src = Path(tmp) / f"{kind.replace(' ', '_')}_{n}.nc"
            src.write_text(KINDS[kind](n))
            for label, tree in trees:
                t_cpu, _, t_rc = _child(tree, src, ["-m", str(mill), "--emit=timing", "--report-format=json",
                                                    "-o", str(src.with_suffix(".json"))], limit_s)
                steps = 0
                for fmt in ("queue", "vcd"):
                    out = src.with_suffix(f".{label}.{fmt}")
                    cpu, rss, rc = _child(tree, src, ["-m", str(mill), "--emit=pulses", f"--pulse-format={fmt}",
                                                      "-o", str(out)], limit_s)
                    if rc != 0:
                        print(f"{kind + f' {n:,}':<22} {label:<7} {'':>12} {fmt:>6}  exit {rc}")
                        continue
                    if fmt == "queue":
                        steps = _queue_steps(out)
                    stage = cpu - t_cpu if t_rc == 0 else float("nan")
                    print(f"{kind + f' {n:,}':<22} {label:<7} {steps:>12,} {fmt:>6} {cpu:8.2f} {rss:7.0f} "
                          f"{steps / cpu / 1e6:10.2f} {t_cpu:13.2f} {steps / max(stage, 1e-9) / 1e6:22.2f}")
                    out.unlink(missing_ok=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--steps", type=int, default=100_000_000)
    ap.add_argument("--mode", default="exact", choices=["exact", "interp"])
    ap.add_argument("--chunk", type=int, default=DEFAULT_CHUNK_STEPS)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--whole", type=int, default=0, help="whole process on the N-segment raster instead")
    ap.add_argument("--before", default=None, help="another cncc tree: before/after on raster, arcs, random walk")
    ap.add_argument("--arcs", type=int, default=1000, help="--before: arcs of the arc contour")
    ap.add_argument("--walk", type=int, default=2000, help="--before: segments of the random walk")
    ap.add_argument("--limit", type=float, default=900.0, help="--before: seconds before a child is killed")
    ap.add_argument("--only", default="raster,arcs,walk", help="--before: programs to run (comma list)")
    args = ap.parse_args()
    if args.before:
        sizes = {"raster": args.whole or 100_000, "arcs": args.arcs, "random walk": args.walk}
        chosen = {k.strip() for k in args.only.split(",")}
        before_after(args.before, {k: n for k, n in sizes.items() if k.split()[-1] in chosen}, args.limit)
        return
    if args.whole:
        whole_process(args.whole, args.mode)
        return
    traj = program(args.steps)
    print(f"program: {traj.phase_count} phases, 3 axes, {traj.duration_total_s:.1f} s of motion, mode {args.mode}")
    load = os.getloadavg()[0]
    steps, gen_s, cpu_s = min((run(traj, args.mode, args.chunk) for _ in range(max(args.repeat, 1))),
                              key=lambda r: r[1])
    base_s = min(numpy_pass(steps, args.chunk) for _ in range(max(args.repeat, 1)))
    tracemalloc.start()
    run(traj, args.mode, args.chunk)
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    traj_mb = sum(a.nbytes for a in (traj.t0_s, traj.duration_s, traj.p0_mm, traj.v0_mm_s, traj.a0_mm_s2,
                                     traj.j_mm_s3, traj.cmd_index, traj.limit)) / 1e6
    print(f"steps generated      {steps:,}")
    print(f"generation           {gen_s:8.2f} s   {steps / gen_s / 1e6:7.1f} M steps/s   (goal >= 20; "
          f"best of {args.repeat})")
    print(f"  CPU time           {cpu_s:8.2f} s   {steps / cpu_s / 1e6:7.1f} M steps per CPU-second   "
          f"(load average {load:.1f} on {os.cpu_count()} cores)")
    print(f"plain numpy pass     {base_s:8.2f} s   {steps / base_s / 1e6:7.1f} M samples/s")
    print(f"ratio generation / numpy pass: {gen_s / base_s:.2f}x")
    print(f"peak traced memory   {peak / 1e6:8.1f} MB  (trajectory itself {traj_mb:.1f} MB; "
          f"all steps as int64 would be {steps * 8 / 1e6:.0f} MB)")


if __name__ == "__main__":
    main()
