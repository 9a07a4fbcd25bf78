"""G-code generators for the planner's scale bench: one program per path kind.

Every generator takes the number of motion segments ``n`` and returns program text in
the default dialect (metric, absolute, XY plane).  The shapes are those of issue 14:
raster, arcs (tangent and not), random walk with sharp corners, 0.01 mm segments,
helices and a mixed part (pocket, contour, drilling cycles).
"""

from __future__ import annotations

import math
import random
from collections.abc import Callable

HEAD = ["%", "G21 G90 G17 G94", "G0 X10 Y10 Z5", "G1 Z-1 F600"]
TAIL = ["G0 Z5", "M30", "%"]


def _wrap(body: list[str]) -> str:
    return "\n".join(HEAD + body + TAIL) + "\n"


def raster(n: int) -> str:
    """0.2 mm G1 steps over z = 2 sin(x/7) cos(y/9), rows of 1000, U-turns."""
    per_row = 1000
    out = []
    for i in range(n):
        r, c = divmod(i, per_row)
        c = c if r % 2 == 0 else per_row - 1 - c
        x, y = 10 + 0.2 * c, 10 + 0.5 * r
        z = -3 + 2 * math.sin(x / 7) * math.cos(y / 9)
        out.append(f"G1 X{x:.4f} Y{y:.4f} Z{z:.4f} F3000")
    return _wrap(out)


def arcs(n: int) -> str:
    """A contour of arcs of radius 1..5 mm, every other join tangent, the others at a corner."""
    rnd = random.Random(3)
    out = ["G1 X20 Y20 F2000"]
    x, y, heading = 20.0, 20.0, 0.0
    for i in range(n):
        r = rnd.uniform(1, 5)
        ccw = rnd.random() < 0.5
        if i % 2:
            heading += rnd.uniform(0.5, 2.0) * (1 if rnd.random() < 0.5 else -1)  # a corner
        nx, ny = -math.sin(heading), math.cos(heading)  # left normal
        sign = 1 if ccw else -1
        cx, cy = x + sign * r * nx, y + sign * r * ny
        sweep = rnd.uniform(0.3, 1.5)
        a0 = math.atan2(y - cy, x - cx)
        a1 = a0 + sign * sweep
        ex, ey = cx + r * math.cos(a1), cy + r * math.sin(a1)
        if not (0 < ex < 550 and 0 < ey < 350):  # turn back towards the middle
            cx, cy = x - sign * r * nx, y - sign * r * ny
            ccw, sign = not ccw, -sign
            a0 = math.atan2(y - cy, x - cx)
            a1 = a0 + sign * sweep
            ex, ey = cx + r * math.cos(a1), cy + r * math.sin(a1)
        out.append(f"G{3 if ccw else 2} X{ex:.4f} Y{ey:.4f} I{cx - x:.4f} J{cy - y:.4f}")
        heading += sign * sweep
        x, y = float(f"{ex:.4f}"), float(f"{ey:.4f}")
    return _wrap(out)


def random_walk(n: int) -> str:
    """1 mm G1 steps in random directions (sharp corners), kept inside the table."""
    rnd = random.Random(5)
    x, y = 200.0, 200.0
    out = []
    for _ in range(n):
        ang = rnd.uniform(0, 2 * math.pi)
        x = min(max(x + math.cos(ang), 20.0), 500.0)
        y = min(max(y + math.sin(ang), 20.0), 350.0)
        out.append(f"G1 X{x:.4f} Y{y:.4f} F3000")
    return _wrap(out)


def tiny(n: int) -> str:
    """0.01 mm segments zig-zagging by 2 um around a line (a CAM point cloud)."""
    out = []
    for i in range(n):
        out.append(f"G1 X{20 + 0.01 * i:.4f} Y{20 + 0.002 * (i % 2):.4f} F2000")
    return _wrap(out)


def helices(n: int) -> str:
    """Full-turn helices of radius 4 mm descending 0.2 mm per turn (thread milling), one per segment."""
    out = ["G1 X24 Y20 F1500"]
    z = -1.0
    for i in range(n):
        z -= 0.2
        if i % 40 == 39:
            out.append("G1 Z-1")
            z = -1.0
        else:
            out.append(f"G3 X24 Y20 Z{z:.3f} I-4 J0")
    return _wrap(out)


def mixed(n: int) -> str:
    """A real-style part repeated: pocket zig-zag, rounded contour, a row of drilled holes (G81/G83)."""
    out: list[str] = []
    k = 0
    while len(out) < n:
        ox, oy = 20 + 60 * (k % 8), 20 + 60 * ((k // 8) % 5)
        k += 1
        out.append(f"G0 X{ox:.3f} Y{oy:.3f} Z2")
        out.append("G1 Z-2 F300")
        for r in range(10):  # pocket
            y = oy + 2 * r
            out.append(f"G1 X{ox + 40 if r % 2 == 0 else ox:.3f} Y{y:.3f} F1800")
            out.append(f"G1 Y{y + 2:.3f}")
        out.append(f"G1 X{ox:.3f} Y{oy - 2:.3f}")  # contour with rounded corners
        out.append(f"G1 X{ox + 40:.3f}")
        out.append(f"G3 X{ox + 42:.3f} Y{oy:.3f} I0 J2")
        out.append(f"G1 Y{oy + 20:.3f}")
        out.append(f"G3 X{ox + 40:.3f} Y{oy + 22:.3f} I-2 J0")
        out.append(f"G1 X{ox:.3f}")
        out.append(f"G3 X{ox - 2:.3f} Y{oy + 20:.3f} I0 J-2")
        out.append(f"G1 Y{oy:.3f}")
        out.append(f"G3 X{ox:.3f} Y{oy - 2:.3f} I2 J0")
        out.append("G0 Z2")
        out.append(f"G81 X{ox + 5:.3f} Y{oy + 30:.3f} Z-5 R1 F200")
        for h in range(1, 6):
            out.append(f"X{ox + 5 + 6 * h:.3f}")
        out.append("G80")
        out.append("G0 Z5")
    return _wrap(out[:n])


KINDS: dict[str, Callable[[int], str]] = {
    "raster": raster, "arcs": arcs, "random walk": random_walk, "0.01 mm": tiny, "helices": helices,
    "mixed part": mixed,
}
