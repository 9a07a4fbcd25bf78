"""Generated programs for LinuxCNC's cutter radius compensation (G41/G42, G41.1/G42.1, G40).

Closed or open contours around the origin with convex and concave corners, lines and arcs
(bulging out or in), Z-only or rotary moves in the middle of the contour, lead-ins from
several directions as a line or an arc (compensation turned on in a G2/G3 block), exits
by a line, by G40 alone and then a move, or by an arc; tools from the table, the loaded
tool (no D), or G41.1/G42.1 with a diameter that may be negative.  Some contours are too
tight for the tool on purpose: rs274 then reports gouging or a too-small arc.
"""

from __future__ import annotations

import math
import random

from tests.oracle import programs as base


def _contour(rng: random.Random, k: float) -> list[tuple[float, float]]:
    """Vertices of a star-shaped polygon around the origin (counter-clockwise)."""
    n = rng.randint(3, 7)
    angles = sorted(rng.uniform(0, 2 * math.pi) for _ in range(n))
    pts = []
    for a in angles:
        r = rng.uniform(10, 35) * k
        pts.append((round(r * math.cos(a), 3), round(r * math.sin(a), 3)))
    if rng.random() < 0.5:
        pts.reverse()
    return pts


def _arc_words(rng: random.Random, p0: tuple[float, float], p1: tuple[float, float], k: float) -> str:
    chord = math.dist(p0, p1)
    g = rng.choice(["G2", "G3"])
    n = base.num
    if rng.random() < 0.5:  # R form
        r = chord / 2 * rng.choice([1.0001, rng.uniform(1.05, 3.0)])
        if rng.random() < 0.2:
            r = -r
        return f"{g} X{n(p1[0])} Y{n(p1[1])} R{n(r)}"
    # centre form: a centre on the chord's bisector
    mx, my = (p0[0] + p1[0]) / 2, (p0[1] + p1[1]) / 2
    dx, dy = p1[0] - p0[0], p1[1] - p0[1]
    t = rng.uniform(-1.5, 1.5)
    cx, cy = mx - dy * t, my + dx * t
    return f"{g} X{n(p1[0])} Y{n(p1[1])} I{n(cx - p0[0])} J{n(cy - p0[1])}"


def _comp_on(rng: random.Random, k: float, tool: int) -> str:
    side = rng.choice(["G41", "G42"])
    kind = rng.random()
    if kind < 0.35:
        d = rng.uniform(1, 8) * k * rng.choice([1, 1, -1])
        return f"{side}.1 D{base.num(d)}"
    if kind < 0.5:
        return side
    return f"{side} D{rng.choice([tool, tool, 1, 2, 3])}"


def cutter_comp(rng: random.Random) -> base.Program:
    u, k = base._units(rng)
    n = base.num
    tool = rng.randint(1, 3)
    z_top, z_cut = 5 * k, -1 * k
    pts = _contour(rng, k)
    closed = rng.random() < 0.7
    lead = rng.uniform(8, 25) * k
    ang = math.atan2(pts[0][1], pts[0][0]) + rng.uniform(-1.2, 1.2)
    start = (round(pts[0][0] + lead * math.cos(ang), 3), round(pts[0][1] + lead * math.sin(ang), 3))
    out = [f"{u} G90 G17 F{n(300 * k)}", f"T{tool} M6 G43", f"G0 X{n(start[0])} Y{n(start[1])} Z{n(z_top)}",
           f"G1 Z{n(z_cut)}"]
    on = _comp_on(rng, k, tool)
    if rng.random() < 0.2:  # compensation turned on in an arc block
        out.append(f"{on} {_arc_words(rng, start, pts[0], k)}")
    elif rng.random() < 0.15:  # on in a block of its own, the lead-in after it
        out += [on, f"G1 X{n(pts[0][0])} Y{n(pts[0][1])}"]
    else:
        out.append(f"{on} G1 X{n(pts[0][0])} Y{n(pts[0][1])}")
    path = pts[1:] + ([pts[0]] if closed else [])
    prev = pts[0]
    z = z_cut
    for p in path:
        if rng.random() < 0.15:  # a move off the plane at the corner
            z = round(z + rng.choice([-0.5, 0.5, 1.0]) * k, 3)
            out.append(rng.choice([f"G1 Z{n(z)}", f"G0 Z{n(z)}", f"G1 A{n(rng.uniform(-30, 30))}"]))
        if rng.random() < 0.35:
            out.append(_arc_words(rng, prev, p, k))
        else:
            out.append(f"G1 X{n(p[0])} Y{n(p[1])}" + (f" Z{n(z)}" if rng.random() < 0.1 else ""))
        prev = p
    far = math.hypot(*prev) + rng.uniform(8, 20) * k
    a = math.atan2(prev[1], prev[0]) + rng.uniform(-0.8, 0.8)
    end = (far * math.cos(a), far * math.sin(a))
    exit_kind = rng.random()
    if exit_kind < 0.6:
        out.append(f"G40 G1 X{n(end[0])} Y{n(end[1])}")
    elif exit_kind < 0.85:
        out += ["G40", f"G0 Z{n(z_top)}", f"G0 X{n(end[0])} Y{n(end[1])}"]
    else:
        out.append(f"G40 {_arc_words(rng, prev, (round(end[0], 3), round(end[1], 3)), k)}")
    out.append(f"G0 Z{n(z_top)}")
    return base.Program(base._end(out, rng), base.TOOLS)
