"""Planner benchmark: throughput, -O2/-O3 optimality, corner strategies, verify.

Run: ``python bench/planner.py [--quick] [--repeat N]``.  Prints the machine load, then

(a) segments per second at -O1 and -O2 on a 100,000-segment CAM path (goal -O2 >= 10,000);
(b) cycle time -O2 / -O3 on short paths (goal <= 1.03 each);
(c) -O2 against jerk-limited exact stop at every corner and against -O1, as ratios;
(d) the number of verify violations of every plan (goal 0);
(e) with ``--scale N,N,...``: whole-process runs (``cncc FILE --emit=timing
    --report-format=json``) on generated programs of every kind (``bench/pathgen.py``)
    at each size: CPU s and peak RSS at -O1 and -O2, their ratio, -O2 segments per CPU
    second, CPU microseconds per segment (flat from 1k to 100k: linear), the cycle time
    -O2/-O1, -O2 against the jerk-aware lower bound of ``bench/bound.py`` (independent, no
    planner code; goal <= 1.15) and -O1 against the acceleration-only bound, the -O2 exit
    code and, where -O2 is slower than -O1, why: "jerk forces it" when the jerk-aware bound
    is above -O1's time (goals: -O2 >= 20,000 segments/s at 100k, -O2 CPU <= 3x -O1,
    RSS < 300 MB, exit 0).  ``--scale-only`` skips (a)-(d);
(f) with ``--o3``: -O2/-O3 whole process on the arc and random-walk kinds at 1k;
(g) with ``--scale N,... --before DIR``: instead of (e), a before/after table in one run:
    per kind and size, -O1 and -O2 CPU s and peak RSS of the tree ``DIR`` (e.g.
    /work/before3) and of this tree, this tree's -O2/-O1 CPU ratio, -O2 segments per CPU
    second and CPU microseconds per segment, and the -O2 cycle time after / before.
"""

from __future__ import annotations

import argparse
import math
import os
import re
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import itertools

from cncc.diagnostics import DiagnosticSink
from cncc.ir.commands import Arc, Command, Linear
from cncc.ir.frame import IDENTITY_FRAME, Plane
from cncc.ir.machine import MachineModel
from cncc.machines import effective_corner_rule, load_machine
from cncc.passes.plan import plan_commands
from cncc.passes.verify import verify_trajectory
from cncc.source import NO_SPAN

Pt = tuple[float, float, float]


def _v6(p: Pt) -> tuple[float, float, float, float, float, float]:
    return (p[0], p[1], p[2], 0.0, 0.0, 0.0)


def polyline(points: list[Pt], feed: float) -> list[Command]:
    return [Linear(NO_SPAN, IDENTITY_FRAME, _v6(a), _v6(b), feed) for a, b in itertools.pairwise(points)]


def cam_path(n_segments: int) -> list[Command]:
    """A 3-axis raster finishing path over z = 2 sin(x/7) cos(y/9), 0.25 mm steps."""
    per_row = 1000
    rows = n_segments // per_row + 1
    pts: list[Pt] = []
    for r in range(rows):
        y = 10 + 0.5 * r
        xs = np.linspace(10, 10 + 0.25 * per_row, per_row)
        xs = xs if r % 2 == 0 else xs[::-1]
        pts.extend((float(x), y, float(-3 + 2 * math.sin(x / 7) * math.cos(y / 9))) for x in xs)
    return polyline(pts[: n_segments + 1], 3000)


def short_paths() -> dict[str, list[Command]]:
    c = (60.0, 60.0, -1.0)

    def arc(start: Pt, end: Pt, center: Pt, turns: int, feed: float) -> Arc:
        return Arc(NO_SPAN, IDENTITY_FRAME, _v6(start), _v6(end), _v6(center), turns, Plane.XY, feed)

    spiral = [(c[0] + (2 + 0.4 * t) * math.cos(t), c[1] + (2 + 0.4 * t) * math.sin(t), -1.0)
              for t in np.linspace(0, 4 * math.pi, 80)]
    curve = [(20 + t, 40 + 8 * math.sin(t / 6), -1.0) for t in np.linspace(0, 40, 120)]
    return {
        "square pocket": polyline([(40, 40, -1), (60, 40, -1), (60, 60, -1), (40, 60, -1), (40, 40, -1),
                                   (45, 45, -1), (55, 45, -1), (55, 55, -1), (45, 55, -1), (45, 45, -1)], 2000),
        "circle": [arc((70, 60, -1), (70, 60, -1), c, 1, 3000)],
        "spiral": polyline(spiral, 2500),
        "zig-zag": polyline([(20 + 3 * i, 30 + 10 * (i % 2), -1) for i in range(15)], 3000),
        "fine polyline": polyline(curve, 4000),
        "helix": [arc((70, 60, -1), (70, 60, -4), c, 2, 1500)],
        "short fast segments": polyline([(20 + 0.3 * i, 30 + 0.05 * (i % 3), -1) for i in range(60)], 9000),
        "slot": polyline([(20, 20, -1), (80, 20, -1), (80, 22, -1), (20, 22, -1)], 2500),
        "triangle": polyline([(20, 20, -1), (60, 20, -1), (40, 50, -1), (20, 20, -1)], 3000),
        "plunge and cut": polyline([(30, 30, 0), (30, 30, -3), (50, 30, -3), (50, 35, -3)], 1200),
        "star": polyline([(50 + 15 * math.cos(a) * (1 if i % 2 == 0 else 0.4),
                           50 + 15 * math.sin(a) * (1 if i % 2 == 0 else 0.4), -1)
                          for i, a in enumerate(np.linspace(0, 2 * math.pi, 11))], 2500),
        "feed change": polyline([(20, 20, -1), (40, 20, -1)], 1000) + polyline([(40, 20, -1), (70, 20, -1)], 5000),
    }


STRICT_COUNTS: dict[int, int] = {}  # violations under verify{strict_continuity} per -O level


def timed_plan(cmds: list[Command], machine: MachineModel, level: int) -> tuple[float, float, float, int]:
    """(cycle time, wall seconds, CPU seconds, verify violations)."""
    sink = DiagnosticSink()
    t0, c0 = time.perf_counter(), time.process_time()
    traj = plan_commands(cmds, machine, level, sink)
    elapsed, cpu = time.perf_counter() - t0, time.process_time() - c0
    report = verify_trajectory(traj, cmds, machine, sink, corner_rule=effective_corner_rule(machine, level),
                               check_dynamics=level > 0, jerk_limited=level >= 2)
    strict = verify_trajectory(traj, cmds, machine, DiagnosticSink(), corner_rule=effective_corner_rule(machine, level),
                               check_dynamics=level > 0, jerk_limited=level >= 2, strict_continuity=True)
    STRICT_COUNTS[level] = STRICT_COUNTS.get(level, 0) + strict.count
    return traj.duration_total_s, elapsed, cpu, report.count


def _load() -> str:
    one, five, _ = os.getloadavg()
    return f"load {one:.1f}/{five:.1f} on {os.cpu_count()} cores"


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="10,000 segments and no -O3")
    ap.add_argument("--repeat", type=int, default=3, help="throughput runs per level (the best is shown)")
    ap.add_argument("--scale", default="", help="sizes for the whole-process runs, e.g. 1000,10000,100000")
    ap.add_argument("--scale-only", action="store_true", help="only the whole-process runs")
    ap.add_argument("--kinds", default="", help="comma-separated subset of the path kinds")
    ap.add_argument("--limit", type=float, default=300.0, help="seconds before a whole-process run is killed")
    ap.add_argument("--o3", action="store_true", help="with --scale: also (f) -O2/-O3 on the 1k arc and walk kinds")
    ap.add_argument("--before", default="", help="with --scale: (g) before/after table against this source tree")
    args = ap.parse_args()
    if args.scale and args.before:
        compare_runs([int(x) for x in args.scale.split(",")], args.kinds, args.limit, Path(args.before))
        if args.scale_only:
            return
    elif args.scale:
        scale_runs([int(x) for x in args.scale.split(",")], args.kinds, args.limit, args.o3)
        if args.scale_only:
            return
    machine = load_machine("generic-mill")
    violations = 0
    n = 10_000 if args.quick else 100_000
    cam = cam_path(n)
    print(f"planner benchmark, {_load()}")
    print(f"(a) throughput on a {n:,}-segment CAM path (generic-mill), best of {args.repeat}")
    for level in (1, 2):
        runs = [timed_plan(cam, machine, level) for _ in range(max(1, args.repeat))]
        cycle, bad = runs[0][0], max(r[3] for r in runs)
        wall, cpu = min(r[1] for r in runs), min(r[2] for r in runs)
        violations += bad
        print(f"    -O{level}: {n / wall:10,.0f} segments/s wall ({wall:.2f} s), {n / cpu:10,.0f} per CPU second "
              f"(cycle {cycle:.1f} s, {bad} violations)")
    print("(b) -O2 / -O3 cycle time (-O3 CPU s)   (c) -O2 / exact stop   -O2 / -O1")
    stop_machine = load_machine("generic-mill", {"corner_rule": "exact-stop"})
    worst = 0.0
    for name, cmds in short_paths().items():
        t2, _, _, b2 = timed_plan(cmds, machine, 2)
        t1, _, _, b1 = timed_plan(cmds, machine, 1)
        ts, _, _, bs = timed_plan(cmds, stop_machine, 2)
        violations += b1 + b2 + bs
        if args.quick:
            r23 = "   n/a        "
        else:
            t3, _, c3, b3 = timed_plan(cmds, machine, 3)
            violations += b3
            worst = max(worst, t2 / t3)
            r23 = f"{t2 / t3:6.3f} ({c3:5.1f})"
        print(f"    {name:22s} {r23}   (O2 {t2:6.3f} s)   {t2 / ts:6.3f}       {t2 / t1:6.3f}", flush=True)
    if not args.quick:
        print(f"    worst -O2 / -O3: {worst:.3f}")
    print(f"(d) verify violations over all plans: {violations}; with strict_continuity, per level: "
          + ", ".join(f"-O{k} {v}" for k, v in sorted(STRICT_COUNTS.items())))
    print(f"done, {_load()}")


def _bound(path: Path, machine: str = "generic-mill") -> tuple[float, float, float]:
    """(jerk-aware bound, acceleration-only bound, CPU s) from bench/bound.py in a child
    (the bench process must stay small: children inherit its RSS)."""
    import subprocess

    t0 = os.times()
    out = subprocess.run([sys.executable, str(Path(__file__).parent / "bound.py"), str(path), machine],
                         capture_output=True, text=True,
                         env=dict(os.environ, PYTHONPATH=str(Path(__file__).resolve().parents[1]))).stdout.split()
    t1 = os.times()
    cpu = (t1.children_user - t0.children_user) + (t1.children_system - t0.children_system)
    if len(out) != 2:
        return math.nan, math.nan, cpu
    return float(out[0]), float(out[1]), cpu


def _reason(c1: float, c2: float, jb: float) -> str:
    """Why -O2's cycle is above -O1's (issue 26): the jerk-aware bound above -O1 means no
    jerk-limited plan can match -O1 (trapezoids, no jerk limit); below it, nothing is proven
    either way (the planner may be slow, or the bound loose: it leaves out the centripetal
    jerk of a turn and couples the axes only through the middles' accelerations)."""
    if not c2 > c1 * 1.0005:
        return ""
    return "jerk forces it" if jb > c1 else "not proven (bound < -O1)"


def scale_runs(sizes: list[int], kinds: str, limit_s: float, o3: bool = False) -> None:
    import tempfile

    from pathgen import KINDS
    from scale import timing_run

    wanted = [k for k in KINDS if not kinds or k in kinds.split(",")]
    print(f"(e) whole process, cncc FILE --emit=timing --report-format=json, generic-mill, {_load()}")
    print("    CPU s and peak RSS per run, CPU us per segment; cycle: -O2 motion time / -O1's and / the jerk-aware")
    print("    lower bound of bench/bound.py (no planner code; 'acc' the acceleration-only bound / -O1);")
    print("    goals: -O2 >= 20,000 seg/s at 100k, CPU O2/O1 <= 3, RSS < 300 MB, O2/bound <= 1.15")
    print(f"    {'kind':12s} {'segments':>9s} {'-O1 CPU s':>10s} {'MB':>5s} {'us/seg':>6s} {'-O2 CPU s':>10s} "
          f"{'MB':>5s} {'us/seg':>6s} {'O2/O1':>6s} {'seg/s':>8s} {'cyc O2/O1':>9s} {'O2/bound':>8s} "
          f"{'O1/acc':>6s} rc  why -O2 > -O1")
    with tempfile.TemporaryDirectory() as tmp:
        for kind in wanted:
            for n in sizes:
                path = Path(tmp) / f"{kind.replace(' ', '_').replace('.', '')}_{n}.nc"
                path.write_text(KINDS[kind](n))
                r1, c1 = timing_run(path, 1, limit_s)
                r2, c2 = timing_run(path, 2, limit_s)
                jb, ab, _ = _bound(path)

                def cpu(r: object) -> str:
                    assert hasattr(r, "rc") and hasattr(r, "cpu_s")
                    return f">{limit_s:.0f}" if r.rc == -1 else f"{r.cpu_s:.2f}"

                ratio = "" if r1.rc == -1 or r2.rc == -1 else f"{r2.cpu_s / r1.cpu_s:6.2f}"
                rate = "" if r2.rc == -1 else f"{n / r2.cpu_s:8,.0f}"
                codes = sorted(set(re.findall(r"[EW]0\d{3}", r2.stderr)))
                print(f"    {kind:12s} {n:9,d} {cpu(r1):>10s} {r1.rss_mb:5.0f} {1e6 * r1.cpu_s / n:6.0f} "
                      f"{cpu(r2):>10s} {r2.rss_mb:5.0f} {1e6 * r2.cpu_s / n:6.0f} {ratio:>6s} {rate:>8s} "
                      f"{c2 / c1:9.3f} {c2 / jb:8.3f} {c1 / ab:6.3f} {r2.rc:2d}  {_reason(c1, c2, jb)} "
                      f"{' '.join(codes)}", flush=True)
        if o3:
            o3_runs(Path(tmp), limit_s)


def compare_runs(sizes: list[int], kinds: str, limit_s: float, before: Path) -> None:
    """(g) the before/after table (see the module docstring)."""
    import tempfile

    from pathgen import KINDS
    from scale import timing_run

    def cpu(r: object) -> str:
        assert hasattr(r, "rc") and hasattr(r, "cpu_s")
        return f">{limit_s:.0f}" if r.rc == -1 else f"{r.cpu_s:.2f}"

    wanted = [k for k in KINDS if not kinds or k in kinds.split(",")]
    print(f"(g) whole process, cncc FILE --emit=timing --report-format=json, generic-mill, CPU s / peak MB; "
          f"before = {before}, {_load()}")
    print(f"    {'kind':12s} {'segments':>9s} | {'before -O1':>13s} {'before -O2':>13s} | {'after -O1':>13s} "
          f"{'after -O2':>13s} | {'O2/O1':>5s} {'O2 seg/s':>8s} {'us/seg':>6s} {'cycle a/b':>9s} | "
          f"{'cyc O2/O1 b':>11s} {'a':>6s} {'O2/bound b':>10s} {'a':>6s} | why -O2 > -O1 (after)")
    print("    cycle: -O2 motion time / -O1's of the same tree; bound: bench/bound.py of this tree (jerk-aware,")
    print("    no planner code) for both trees; goals cyc O2/O1 <= 1 except where jerk forces more, O2/bound <= 1.15")
    with tempfile.TemporaryDirectory() as tmp:
        for kind in wanted:
            for n in sizes:
                path = Path(tmp) / f"{kind.replace(' ', '_').replace('.', '')}_{n}.nc"
                path.write_text(KINDS[kind](n))
                b1, cb1 = timing_run(path, 1, limit_s, root=before)
                b2, cb = timing_run(path, 2, limit_s, root=before)
                a1, ca1 = timing_run(path, 1, limit_s)
                a2, ca = timing_run(path, 2, limit_s)
                jb, _, _ = _bound(path)
                codes = sorted(set(re.findall(r"[EW]0\d{3}", a2.stderr)))
                ratio = "" if a1.rc == -1 or a2.rc == -1 else f"{a2.cpu_s / a1.cpu_s:5.2f}"
                rate = "" if a2.rc == -1 else f"{n / a2.cpu_s:8,.0f}"
                per = "" if a2.rc == -1 else f"{1e6 * a2.cpu_s / n:6.0f}"
                print(f"    {kind:12s} {n:9,d} | {cpu(b1):>7s} {b1.rss_mb:5.0f} {cpu(b2):>7s} {b2.rss_mb:5.0f} | "
                      f"{cpu(a1):>7s} {a1.rss_mb:5.0f} {cpu(a2):>7s} {a2.rss_mb:5.0f} | {ratio:>5s} {rate:>8s} "
                      f"{per:>6s} {ca / cb:9.4f} | {cb / cb1:11.3f} {ca / ca1:6.3f} {cb / jb:10.3f} {ca / jb:6.3f} | "
                      f"{_reason(ca1, ca, jb)} {' '.join(codes)}", flush=True)


def o3_runs(tmp: Path, limit_s: float) -> None:
    """(f) -O2 / -O3 whole process on the arc and random-walk kinds at 1k segments."""
    from pathgen import KINDS
    from scale import timing_run

    print(f"(f) -O2 / -O3 whole process at 1,000 segments (goal <= 1.03), {_load()}")
    for kind in ("arcs", "random walk"):
        path = tmp / f"o3_{kind.replace(' ', '_')}.nc"
        path.write_text(KINDS[kind](1000))
        _, c2 = timing_run(path, 2, limit_s)
        r3, c3 = timing_run(path, 3, limit_s)
        jb, _, _ = _bound(path)
        codes = sorted(set(re.findall(r"[EW]0\d{3}", r3.stderr)))
        cpu3 = f">{limit_s:.0f}" if r3.rc == -1 else f"{r3.cpu_s:.1f}"
        print(f"    {kind:12s} -O2 {c2:9.3f} s  -O3 {c3:9.3f} s ({cpu3} CPU s, rc {r3.rc})  -O2/-O3 {c2 / c3:6.3f}  "
              f"-O3/bound {c3 / jb:6.3f}  {' '.join(codes)}", flush=True)


if __name__ == "__main__":
    main()
