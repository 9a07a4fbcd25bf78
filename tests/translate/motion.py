"""Motion of a compiled program, for round-trip comparisons (tests only).

``motion(cmds)`` lists the moves and dwells in machine terms (work, local and G92
offsets and the tool length added), so that a translation that folds an offset
into the coordinates compares equal to one that sets it with a code.  Arcs that a
target needed split (quadrants, R form, full circles) are merged back: consecutive
arcs with the same centre, direction, plane and feed are one arc whose sweep is the
sum.
"""

from __future__ import annotations

import math
from typing import Any

from cncc.ir import Arc, Command, Dwell, Linear, Rapid

Move = tuple[Any, ...]


def _base(c: Any) -> tuple[float, ...]:
    f = c.frame
    o = list(f.total_offset_mm)
    o[f.tool_length_axis] += f.tool_length_mm
    return tuple(o)


def _add(p: tuple[float, ...], o: tuple[float, ...]) -> tuple[float, ...]:
    return tuple(a + b for a, b in zip(p, o, strict=True))


def _sweep(c: Arc) -> float:
    i, j = c.plane.first, c.plane.second
    a0 = math.atan2(c.start[j] - c.center[j], c.start[i] - c.center[i])
    a1 = math.atan2(c.end[j] - c.center[j], c.end[i] - c.center[i])
    d = ((a1 - a0) if c.turns > 0 else (a0 - a1)) % (2 * math.pi)
    if d < 1e-6 or (2 * math.pi - d < 1e-6 and abs(c.end[i] - c.start[i]) + abs(c.end[j] - c.start[j]) < 1e-6):
        d = 2 * math.pi
    return d + (abs(c.turns) - 1) * 2 * math.pi


def motion(cmds: list[Command]) -> list[Move]:
    out: list[Move] = []
    for c in cmds:
        if isinstance(c, Rapid):
            out.append(("rapid", _add(c.end, _base(c))))
        elif isinstance(c, Linear):
            out.append(("feed", _add(c.end, _base(c)), c.feed_mm_min))
        elif isinstance(c, Arc):
            b = _base(c)
            centre = _add(c.center, b)  # in the plane: the normal component is the start's, not the arc's
            arc = ("arc", _add(c.end, b), (centre[c.plane.first], centre[c.plane.second]), c.turns > 0, c.plane,
                   c.feed_mm_min, _sweep(c))
            prev = out[-1] if out else None
            if (prev is not None and prev[0] == "arc" and prev[3:5] == arc[3:5] and close(prev[2], arc[2], 2e-3)
                    and abs(prev[5] - arc[5]) <= 1e-3 * arc[5]):  # pieces of a helix: Z rounded per piece
                out[-1] = ("arc", arc[1], prev[2], prev[3], prev[4], prev[5], prev[6] + arc[6])
            else:
                out.append(arc)
        elif isinstance(c, Dwell):
            out.append(("dwell", c.seconds))
    return out


def close(a: tuple[float, ...], b: tuple[float, ...], tol_mm: float) -> bool:
    return all(abs(x - y) <= tol_mm for x, y in zip(a, b, strict=True))


def difference(want: list[Move], got: list[Move], tol_mm: float = 1e-3, feed_rel: float = 1e-4) -> str:
    """"" when ``got`` is ``want`` within the tolerances, else what differs first."""
    if len(want) != len(got):
        return f"{len(want)} moves in the source, {len(got)} in the translation"
    for k, (w, g) in enumerate(zip(want, got, strict=True)):
        why = _differs(w, g, tol_mm, feed_rel)
        if why:
            return f"move {k}: {why}: want {w}, got {g}"
    return ""


def _differs(w: Move, g: Move, tol_mm: float, feed_rel: float) -> str:
    if w[0] != g[0]:
        return "kind"
    if w[0] == "dwell":
        return "" if abs(w[1] - g[1]) <= 1e-3 else "dwell"
    if not close(w[1], g[1], tol_mm):
        return "end point"
    if w[0] == "feed" and abs(w[2] - g[2]) > feed_rel * w[2]:
        return "feed"
    if w[0] == "arc":
        if not close(w[2], g[2], tol_mm):
            return "centre"
        if w[3:5] != g[3:5]:
            return "direction or plane"
        if abs(w[5] - g[5]) > feed_rel * w[5]:
            return "feed"
        radius = math.hypot(w[1][w[4].first] - w[2][0], w[1][w[4].second] - w[2][1])
        if abs(w[6] - g[6]) > 1e-3 and abs(w[6] - g[6]) * radius > 2 * tol_mm:  # as a length along the arc
            return "sweep"
    return ""
