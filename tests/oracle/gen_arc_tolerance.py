"""Generated programs for LinuxCNC's arc radius tolerance.

Centre-format arcs whose end radius differs from the start radius by an amount around each
of rs274 2.9's thresholds -- the absolute tolerance (its own value in G20 programs), the
relative one (0.1 % of the radius) and the cap of 100 absolute tolerances -- for small and
large radii in mm and inches; and R-format arcs whose chord is exactly 2R (or a hair
longer), which in G20 programs is a question of the inch to mm conversion.
"""

from __future__ import annotations

import math
import random

from tests.oracle import programs as base

ABS_MM, ABS_INCH, REL, CAP = 0.01 * math.sqrt(2) * 2, 0.001 * math.sqrt(2) * 2, 0.001, 100.0


def _centre_arc(rng: random.Random, inch: bool) -> str:
    n = base.num
    r = rng.choice([0.1, 0.5, 1.0, 3.0, 10.0, 40.0, 200.0, 1500.0]) * rng.uniform(0.8, 1.2)
    r *= 0.04 if inch else 1.0
    tol_abs = ABS_INCH if inch else ABS_MM
    threshold = rng.choice([tol_abs, REL * r, CAP * tol_abs])
    diff = threshold * rng.choice([0.7, 0.93, 1.07, 1.4]) * rng.choice([1, -1])
    a0 = rng.uniform(0, 2 * math.pi)
    sweep = rng.uniform(0.3, 2 * math.pi - 0.3)
    ccw = rng.random() < 0.5
    a1 = a0 + (sweep if ccw else -sweep)
    cx, cy = rng.uniform(-5, 5), rng.uniform(-5, 5)
    x0, y0 = cx + r * math.cos(a0), cy + r * math.sin(a0)
    r1 = max(r + diff, r * 0.1)
    x1, y1 = cx + r1 * math.cos(a1), cy + r1 * math.sin(a1)
    return f"G0 X{n(x0)} Y{n(y0)}\n{'G3' if ccw else 'G2'} X{n(x1)} Y{n(y1)} I{n(cx - x0)} J{n(cy - y0)}"


def _r_arc(rng: random.Random, inch: bool) -> str:
    n = base.num
    x0, y0 = round(rng.uniform(-3, 3), 4), round(rng.uniform(-3, 3), 4)
    x1, y1 = round(rng.uniform(-3, 3), 4), round(rng.uniform(-3, 3), 4)
    half = math.hypot(x1 - x0, y1 - y0) / 2
    if half < 0.01:
        x1 += 1.0
        half = math.hypot(x1 - x0, y1 - y0) / 2
    short = rng.choice([0.0, 0.0, 0.00004, 0.00006, 0.0001]) * (1 if inch else 25.4)
    r = round(half, 4) - short
    return f"G0 X{n(x0)} Y{n(y0)}\n{rng.choice(['G2', 'G3'])} X{n(x1)} Y{n(y1)} R{n(r)}"


def arc_tolerance(rng: random.Random) -> base.Program:
    inch = rng.random() < 0.5
    out = [f"{'G20' if inch else 'G21'} G90 G17 F{base.num(10 if inch else 250)}"]
    for _ in range(rng.randint(1, 2)):
        out.append(_centre_arc(rng, inch) if rng.random() < 0.7 else _r_arc(rng, inch))
    return base.Program(base._end(out, rng))
