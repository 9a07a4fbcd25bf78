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


def shop_program(n_lines: int, seed: int = 2) -> str:
    """A milling job of about ``n_lines`` lines (SYNTEC): T1 roughs a rectangular pocket by
    zig-zag raster passes at several depths, T2 finishes its contour (lines and arcs, cutter
    compensation D2), T3 drills a grid of holes with a G81 cycle.  Each tool has its H offset."""
    rnd = random.Random(seed)
    out = ["%", "O2000 (generated pocket, contour and drilling)", "G90 G17 G71 G94 G54",
           "T1 M06", "S8000 M03", "G43 H1 G00 Z10.0", "G00 X0.0 Y0.0"]
    holes = max(4, n_lines // 200)
    contour_lines = max(8, n_lines // 20)
    raster_lines = max(20, n_lines - contour_lines - holes - 40)
    width, height = 120.0, 80.0
    step = 0.5
    passes = int(height / step)
    levels = max(1, raster_lines // (2 * passes + 3))
    n = 0
    for level in range(levels):
        z = -0.5 * (level % 20 + 1)
        out += ["G00 X0.0 Y0.0", "G00 Z1.0", f"G01 Z{z:.3f} F400"]
        y = 0.0
        for k in range(passes):
            x_end = width if k % 2 == 0 else 0.0
            out.append(f"G01 X{x_end:.3f} Y{y:.3f} F{2400 if k % 7 else 1800}")
            y = round(y + step, 3)
            out.append(f"Y{y:.3f}")
            n += 2
            if n >= raster_lines:
                break
        out.append("G00 Z10.0")
        if n >= raster_lines:
            break
    out += ["T2 M06", "S10000 M03", "G43 H2 G00 Z10.0", "G00 X-5.0 Y-5.0", "G01 Z-10.0 F600", "G41 D2 G01 X0.0 Y0.0"]
    r = 5.0
    laps = max(1, contour_lines // 8)
    for lap in range(laps):
        d = 0.02 * (lap % 10)
        out += [f"G01 X{width - r:.3f} Y{-d:.3f} F1200",
                f"G03 X{width + d:.3f} Y{r:.3f} I0.0 J{r + d:.3f}",
                f"G01 Y{height - r:.3f}",
                f"G03 X{width - r:.3f} Y{height + d:.3f} I{-r - d:.3f} J0.0",
                f"G01 X{r:.3f}",
                f"G03 X{-d:.3f} Y{height - r:.3f} I0.0 J{-r - d:.3f}",
                f"G01 Y{r:.3f}",
                f"G03 X{r:.3f} Y{-d:.3f} I{r + d:.3f} J0.0"]
    out += ["G40 G01 X-5.0 Y-5.0", "G00 Z10.0", "T3 M06", "S3000 M03", "G43 H3 G00 Z10.0",
            f"G81 X10.0 Y10.0 Z-{rnd.choice((6, 8, 12))}.0 R2.0 F300"]
    cols = max(2, int(holes ** 0.5))
    for k in range(1, holes):
        out.append(f"X{10.0 + (k % cols) * 100.0 / cols:.3f} Y{10.0 + (k // cols) * 60.0 / cols:.3f}")
    out += ["G80", "G00 Z50.0", "G04 X1.0", "M05", "M30", "%"]
    return "\n".join(out) + "\n"
# ---- a program library (cncc batch: tests/batch, bench/batch.py, docs/batch.md) ----------------
def _moves(rnd: random.Random, n: int, arc: str, fmt: str = "{:.3f}") -> list[str]:
    """``n`` blocks of feeds and quarter arcs (``arc`` formats "G02 X.. Y.. I.. J.."), from X0 Y0 Z-1."""
    out = []
    x = y = 0.0
    for _ in range(n):
        if rnd.random() < 0.2:
            r = rnd.choice((2.0, 5.0))
            out.append(arc.format(x=fmt.format(x + r), y=fmt.format(y + r), i=fmt.format(r), j=fmt.format(0.0)))
            x, y = x + r, y + r
        else:
            x = round(x + rnd.uniform(-10, 10), 3)
            y = round(y + rnd.uniform(-10, 10), 3)
            out.append(f"G01 X{fmt.format(x)} Y{fmt.format(y)} F{rnd.choice((300, 800, 1500))}")
    return out


def library_program(kind: str, seed: int) -> tuple[str, str]:
    """(file name, text) of one small program: ``kind`` is a dialect, or ``error`` (a syntax error),
    ``unknown`` (a G code the dialect lacks), ``loop`` (a macro loop that never ends)."""
    rnd = random.Random(seed)
    tool = rnd.randint(1, 12)
    n = rnd.randint(5, 25)
    g03 = "G03 X{x} Y{y} I{i} J{j}"
    if kind == "linuxcnc":
        body = [f"T{tool} M06", "S2000 M03", "G00 X0 Y0 Z5", "G01 Z-1 F200", *_moves(rnd, n, g03),
                "G00 Z5", "M05", "M02"]
        return f"p{seed:04d}.ngc", "\n".join(["%", "G21 G90 G17", *body, "%"]) + "\n"
    if kind == "grbl":
        body = ["G21 G90", "M03 S10000", "G00 X0 Y0 Z5", "G01 Z-1 F200", *_moves(rnd, n, g03), "G00 Z5", "M05"]
        return f"p{seed:04d}.gcode", "\n".join(body) + "\n"
    if kind == "fanuc":
        body = [f"O{1000 + seed}", "G21 G90 G17", "#100=5.", f"T{tool} M06", "S1500 M03", "G00 X0. Y0. Z#100",
                "G01 Z-1. F200.", *_moves(rnd, n, g03), "G00 Z#100", "M05", "M30"]
        return f"O{1000 + seed}", "%\n" + "\n".join(body) + "\n%\n"
    if kind == "loop":
        body = [f"O{1000 + seed}", "G21 G90", "#1=0", "WHILE[1EQ1]DO1", "#1=#1+1", "END1", "M30"]
        return f"O{1000 + seed}", "%\n" + "\n".join(body) + "\n%\n"
    body = ["G90 G17 G71", f"T{tool} M06", "S1500 M03", "G00 X0. Y0. Z5.", "G01 Z-1. F200.", *_moves(rnd, n, g03),
            "G00 Z5.", "M05"]
    if kind == "error":
        body.insert(rnd.randint(5, len(body) - 1), "G01 X1..5 Y2.")
    elif kind == "unknown":
        body.insert(rnd.randint(5, len(body) - 1), "G145 X1.")
    return f"p{seed:04d}.nc", "\n".join([*body, "M30"]) + "\n"


LIBRARY_MIX = ("syntec",) * 4 + ("fanuc",) * 3 + ("linuxcnc",) * 2 + ("grbl", "error", "unknown")


def write_library(folder: str, n_programs: int, *, seed: int = 7, loop: bool = True,
                  big_lines: int = 0) -> list[str]:
    """``n_programs`` small programs of several dialects (some with errors) in ``folder``, in
    sub-folders of 50; with ``loop`` one endless macro loop, with ``big_lines`` one long CAM
    program (``big.nc``, to run over a time limit).  Their paths."""
    import os

    paths = []
    for k in range(n_programs):
        kind = "loop" if loop and k == n_programs // 2 else LIBRARY_MIX[k % len(LIBRARY_MIX)]
        name, text = library_program(kind, seed * 100_000 + k)
        sub = os.path.join(folder, f"part{k // 50:02d}")
        os.makedirs(sub, exist_ok=True)
        paths.append(os.path.join(sub, name))
        with open(paths[-1], "w", encoding="utf-8") as fh:
            fh.write(text)
    if big_lines:
        paths.append(os.path.join(folder, "big.nc"))
        with open(paths[-1], "w", encoding="utf-8") as fh:
            fh.write(cam_program(big_lines, seed))
    return paths
