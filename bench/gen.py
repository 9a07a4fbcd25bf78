"""Generators of benchmark programs (shared by the bench scripts)."""

from __future__ import annotations

import math
import random


def cam_program(n_lines: int, seed: int = 1) -> str:
    """A CAM-style program: mostly ``G1 X Y Z`` (G1 written on every block, as most
    CAM posts do), some G2/G3 with I J, some feed changes."""
    rnd = random.Random(seed)
    out = ["%", "O1000 (generated CAM-style program)", "G90 G17 G71 G94", "G00 X0.0 Y0.0 Z5.0", "G01 Z-1.0 F800"]
    x = y = 0.0
    z = -1.0
    for _ in range(n_lines - len(out) - 2):
        r = rnd.random()
        if r < 0.04:
            # arc through a quarter turn of radius 2 around a centre to the left
            ang = rnd.uniform(0, 2 * math.pi)
            cx, cy = x + 2 * math.cos(ang), y + 2 * math.sin(ang)
            a1 = ang + math.pi + math.pi / 2
            ex, ey = cx + 2 * math.cos(a1), cy + 2 * math.sin(a1)
            code = "G03" if rnd.random() < 0.5 else "G02"
            if code == "G02":
                a1 = ang + math.pi - math.pi / 2
                ex, ey = cx + 2 * math.cos(a1), cy + 2 * math.sin(a1)
            out.append(f"{code} X{ex:.3f} Y{ey:.3f} I{cx - x:.3f} J{cy - y:.3f}")
            x, y = round(ex, 3), round(ey, 3)
        elif r < 0.06:
            out.append(f"G01 X{x + rnd.uniform(-1, 1):.3f} Y{y + rnd.uniform(-1, 1):.3f} F{rnd.randint(300, 3000)}")
            x, y = float(out[-1].split()[1][1:]), float(out[-1].split()[2][1:])
        else:
            x = round(x + rnd.uniform(-0.5, 0.5), 3)
            y = round(y + rnd.uniform(-0.5, 0.5), 3)
            z = round(min(0.0, z + rnd.uniform(-0.05, 0.05)), 3)
            out.append(f"G1 X{x:.3f} Y{y:.3f} Z{z:.3f}")
    out += ["G00 Z5.0", "M30"]
    return "\n".join(out) + "\n"
