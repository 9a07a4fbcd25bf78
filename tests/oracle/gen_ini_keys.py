"""Generated programs for the INI keys that change what rs274 does (cncc/inifile.py, the dialect's [ini]):
CENTER_ARC_RADIUS_TOLERANCE_MM/_INCH (inside and outside the range rs274 accepts, with arcs around the
tolerance), RETAIN_G43 (tool changes with G43 in force, T0 unloading), [TRAJ] SPINDLES (the $ word), and
keys rs274 ignores.  The verdict comes from rs274."""

from __future__ import annotations

import random

from tests.oracle import programs as base


def _arc_tolerance(rng: random.Random) -> tuple[list[str], list[str]]:
    inch = rng.random() < 0.4
    if inch:
        tol = rng.choice([0.00003, 0.00004, 0.0001, 0.0005, 0.001, 0.0028, 0.003])
        key, u, r = "CENTER_ARC_RADIUS_TOLERANCE_INCH", "G20 F10", rng.choice([0.13, 1.37, 23.3])
    else:
        tol = rng.choice([0.0005, 0.001, 0.002, 0.005, 0.01, 0.02, 0.028, 0.05])
        key, u, r = "CENTER_ARC_RADIUS_TOLERANCE_MM", "G21 F100", rng.choice([1.37, 13.7, 1370.0])
    out = [u, "G0 X0 Y0"]  # (radii that put no difference exactly on 0.1 %: that tie is decided by rounding)
    x = 0.0
    for _ in range(rng.randint(1, 3)):
        d = tol * rng.choice([0.5, 0.9, 1.1, 2.0, 50, 90, 110]) * rng.choice([1, -1])
        end = x + 2 * r + d
        out.append(f"{rng.choice(['G2', 'G3'])} X{base.num(end)} Y0 I{base.num(r)} J0")
        out.append(f"G0 X{base.num(end)} Y0")
        x = end
    return [f"{key} = {tol:g}"], out


def _retain_g43(rng: random.Random) -> tuple[list[str], list[str]]:
    out = [rng.choice(["G21", "G20"]), f"T{rng.randint(1, 3)} M6"]
    if rng.random() < 0.85:
        out.append("G43")
    for _ in range(rng.randint(1, 4)):
        out.append(rng.choice([f"T{rng.randint(0, 3)} M6", f"T{rng.randint(1, 3)}", "M6"]))
        # every move names Z: the stand-alone rs274 re-reads its position at every block with RETAIN_G43, so
        # the program Z of an unmoved tool does not follow a G43 there (docs/dialects-notes.md)
        out.append(f"G0 {rng.choice('XY')}{base.num(rng.uniform(-5, 5))} Z{base.num(rng.uniform(-5, 5))}")
    return [f"RETAIN_G43 = {rng.choice([0, 1, 1])}"], out


def _spindles(rng: random.Random) -> tuple[list[str], list[str]]:
    n = rng.randint(1, 4)  # (SPINDLES = 0: rs274 2.9 checks no $ word; cncc warns and keeps one spindle)
    out = ["G21 G90 F300"]
    for _ in range(rng.randint(1, 3)):
        d = f"${rng.choice([-1, 0, 0, 1, 2, 3, 4])}"
        out.append(rng.choice([f"S{rng.randint(100, 900)} {d} M3", f"M5 {d}", f"S{rng.randint(100, 900)} {d}"]))
        out.append(f"G1 X{rng.randint(-9, 9)}")
    return [f"SPINDLES = {n}"], out


def ini_keys(rng: random.Random) -> base.Program:
    kind = rng.random()
    if kind < 0.45:
        entries, body = _arc_tolerance(rng)
        ini = ["[RS274NGC]", *entries]
    elif kind < 0.75:
        entries, body = _retain_g43(rng)
        ini = ["[RS274NGC]", *entries]
    else:
        entries, body = _spindles(rng)
        ini = ["[TRAJ]", *entries]
    if rng.random() < 0.3:  # keys rs274 reads but that change nothing here, and keys it does not know
        ini += ["[RS274NGC]", "OWORD_NARGS = 1", "NO_DOWNCASE_OWORD = 1", "UNKNOWN_KEY = 7", "[NOSUCH]", "A = b"]
    return base.Program(base._end(body, rng), base.TOOLS, ini="\n".join(ini) + "\n")
