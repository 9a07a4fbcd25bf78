"""An independent, generous lower bound of a program's motion time (no planner code).

The bound drops the jerk limit and gives the path the largest acceleration any direction
allows (``sqrt(3) * max axis acceleration``), then solves the acceleration-limited
time-optimal problem exactly on the polyline (one backward and one forward pass on
``v^2``).  Speed caps: the programmed feed (machine feed cap), the per-axis velocity
or rapid rates along each piece's direction, ``v^2 <= a r`` on arcs and, at a corner
of deflection ``theta`` between two commands, ``v^2 <= a R`` with ``R`` the largest
radius of a circle that stays within the blend tolerance plus the arc tolerance of the
corner (``R = d / (1 / cos(theta / 2) - 1)``).  Rest at the ends, at exact stops and at
the commands after which every controller stops (dwell, tool change, M0/M1...).  Any
trajectory within the machine's limits and tolerances takes at least this long.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from cncc.ir.commands import Arc, Command, Linear, PathMode, Rapid
from cncc.ir.machine import MachineModel
from cncc.passes.blend import forces_stop


def _arc_points(cmd: Arc, max_angle: float = 0.05) -> np.ndarray:
    f, s = cmd.plane.first, cmd.plane.second
    start, end = np.array(cmd.start, float), np.array(cmd.end, float)
    cf, cs = cmd.center[f], cmd.center[s]
    a0 = math.atan2(start[s] - cs, start[f] - cf)
    a1 = math.atan2(end[s] - cs, end[f] - cf)
    r0, r1 = math.hypot(start[f] - cf, start[s] - cs), math.hypot(end[f] - cf, end[s] - cs)
    turns = cmd.turns or 1
    if turns > 0:
        sweep = (a1 - a0) % (2 * math.pi) or 2 * math.pi
        sweep += 2 * math.pi * (turns - 1)
    else:
        sweep = -((a0 - a1) % (2 * math.pi) or 2 * math.pi)
        sweep -= 2 * math.pi * (-turns - 1)
    n = max(2, math.ceil(abs(sweep) / max_angle))
    frac = np.linspace(0, 1, n + 1)
    pts = start + (end - start) * frac[:, None]
    rad = r0 + (r1 - r0) * frac
    pts[:, f] = cf + rad * np.cos(a0 + sweep * frac)
    pts[:, s] = cs + rad * np.sin(a0 + sweep * frac)
    return pts


def lower_bound_s(cmds: Sequence[Command], machine: MachineModel) -> float:
    names = "XYZABC"
    axes = {a.name: a for a in machine.axes}
    vmax = np.array([axes[n].max_velocity_mm_min / 60 if n in axes else np.inf for n in names])
    rapid = np.array([axes[n].rapid_mm_min / 60 if n in axes else np.inf for n in names])
    acc = math.sqrt(3) * max(a.max_accel_mm_s2 for a in machine.axes)
    pieces: list[tuple[float, float]] = []  # (length, speed cap)
    vertex: list[float] = [0.0]  # squared-speed caps at the piece ends
    last_dir: np.ndarray | None = None
    last_tol = 0.0
    for cmd in cmds:
        if not isinstance(cmd, Rapid | Linear | Arc):
            if forces_stop(cmd, machine):
                vertex[-1] = 0.0
            continue
        pts = _arc_points(cmd) if isinstance(cmd, Arc) else np.array([cmd.start, cmd.end], float)
        d = np.diff(pts, axis=0)
        length = np.linalg.norm(d, axis=1)
        keep = length > 1e-9
        if not keep.any():
            continue
        d, length = d[keep], length[keep]
        u = d / length[:, None]
        rates = rapid if isinstance(cmd, Rapid) else vmax
        with np.errstate(divide="ignore"):
            axis_cap = np.min(np.where(np.abs(u) > 1e-12, rates / np.maximum(np.abs(u), 1e-300), np.inf), axis=1)
        cap = axis_cap if isinstance(cmd, Rapid) else np.minimum(axis_cap, min(cmd.feed_mm_min,
                                                                               machine.max_feed_mm_min) / 60)
        if isinstance(cmd, Arc):
            f, s = cmd.plane.first, cmd.plane.second
            r = max(math.hypot(cmd.start[f] - cmd.center[f], cmd.start[s] - cmd.center[s]), 1e-9)
            cap = np.minimum(cap, math.sqrt(acc * r))
        tol = cmd.motion.blend_tolerance_mm
        tol = machine.blend_tolerance_mm if tol is None else tol
        if last_dir is not None and vertex[-1] > 0:
            cos_t = float(np.clip(np.dot(last_dir, u[0]), -1, 1))
            half = math.acos(cos_t) / 2
            dev = max(last_tol, 0.0) + machine.arc_tolerance_mm
            if half > 1e-6:
                big_r = dev / (1 / math.cos(half) - 1) if half < math.pi / 2 - 1e-9 else 0.0
                vertex[-1] = min(vertex[-1], acc * big_r)
        for i in range(length.size):
            pieces.append((float(length[i]), float(cap[i])))
            vertex.append(math.inf)
        last_dir, last_tol = u[-1], tol
        if cmd.motion.mode is PathMode.EXACT_STOP or (isinstance(cmd, Rapid) and machine.rapid_ends_in_stop):
            vertex[-1] = 0.0
    if not pieces:
        return 0.0
    vertex[-1] = 0.0
    n = len(pieces)
    x = vertex[:]
    for i in range(n):  # caps of the neighbouring pieces
        x[i] = min(x[i], pieces[i][1] ** 2)
        x[i + 1] = min(x[i + 1], pieces[i][1] ** 2)
    for i in range(n - 1, -1, -1):
        x[i] = min(x[i], x[i + 1] + 2 * acc * pieces[i][0])
    for i in range(n):
        x[i + 1] = min(x[i + 1], x[i] + 2 * acc * pieces[i][0])
    total = 0.0
    for i, (length, cap) in enumerate(pieces):
        x0, x1 = x[i], x[i + 1]
        peak2 = min(cap * cap, (2 * acc * length + x0 + x1) / 2)
        peak = math.sqrt(max(peak2, x0, x1))
        v0, v1 = math.sqrt(x0), math.sqrt(x1)
        d_acc, d_dec = (peak * peak - x0) / (2 * acc), (peak * peak - x1) / (2 * acc)
        total += (peak - v0) / acc + (peak - v1) / acc + max(length - d_acc - d_dec, 0.0) / max(peak, 1e-300)
    return total


def program_bound_s(path: str, machine_name: str = "generic-mill") -> float:
    """Compile ``path`` as ``--emit=timing`` does, capture the planner's input, bound it."""
    import os

    from cncc.cli import main
    from cncc.machines import load_machine
    from cncc.passes import plan

    captured: list[list[Command]] = []
    real = plan.plan_commands

    def spy(cmds: Sequence[Command], machine: MachineModel, level: int = 2, sink: object = None,
            progress: object = None) -> object:
        captured.append(list(cmds))
        return real(cmds, machine, level, sink)  # type: ignore[arg-type]

    plan.plan_commands = spy  # type: ignore[assignment]
    try:
        main([path, "-m", machine_name, "--emit=timing", "-O1", "-fno-verify", "-o", os.devnull])
    finally:
        plan.plan_commands = real
    return lower_bound_s(captured[0], load_machine(machine_name)) if captured else math.nan


if __name__ == "__main__":
    import sys

    print(program_bound_s(sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else "generic-mill"))
