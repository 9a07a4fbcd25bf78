"""Hole patterns kept in translated G-code: the pattern block the target reads, or None.

Consumes a kept :class:`cncc.ir.Cycle` that a pattern code produced (``pattern`` names
the code, ``pattern_words`` carries its words as read: the origin by axis letter in
mm, I/J/K/P in mm, degrees or counts) and a :class:`Target`; produces the words of the
pattern block in the target's units and precision (:func:`pattern_block`).

A pattern is written as a pattern only when the target has the same code as a
``pattern`` op and the holes the target computes from the *written* numbers (its
shape rule, its ``g137_order`` option) are the cycle's holes within a nanometre-scale
tolerance; otherwise the caller writes the holes one by one.  This recomputation is
the semantic check: a target whose code means another shape, another order or another
count never passes it.
"""

from __future__ import annotations

import math

from cncc.backends.gcode.numbers import counts_text, quantize
from cncc.backends.gcode.target import Target
from cncc.dialects import CodeDef, code_tenths
from cncc.ir import AXES, Cycle, Vec6

ANGLE_DECIMALS = 6  # pattern angles: at 1000 mm radius, 1e-6 degrees is 17 nm
_TOL_MM = 1e-6
Points = list[tuple[float, float]]


def pattern_code(c: Cycle, target: Target) -> CodeDef | None:
    """The target's code of the same name when it is a pattern code of a shape cncc knows."""
    if not c.pattern or not c.pattern_words:
        return None
    letter, number = c.pattern[:1].upper(), c.pattern[1:]
    try:
        cdef = target.dialect.code(letter, code_tenths(number))
    except ValueError:
        return None
    if cdef is None or cdef.op != "pattern" or cdef.cycle not in _SHAPES:
        return None
    return cdef


def pattern_block(c: Cycle, target: Target, mm_per_unit: float, decimals: int, fold: Vec6) -> list[str] | None:
    """The pattern block's words (``G134 X Y I J K``), or None when the target would drill other holes."""
    cdef = pattern_code(c, target)
    if cdef is None:
        return None
    first, second = AXES[c.plane.first], AXES[c.plane.second]
    words: list[str] = [cdef.name]
    read: dict[str, float] = {}  # the values the target reads back (mm, deg, counts)
    lengths = {first, second, "I"} | ({"J"} if cdef.cycle == "grid" else set())
    for letter, value in c.pattern_words:
        shift = fold[c.plane.first] if letter == first else fold[c.plane.second] if letter == second else 0.0
        kind = cdef.words.get(letter, "length" if letter in lengths else "real")
        if letter in lengths:
            counts = quantize((value + shift) / mm_per_unit, decimals)
            words.append(letter + counts_text(counts, decimals))
            read[letter] = counts * mm_per_unit / 10**decimals - shift
        elif kind == "int":
            if value != int(value):
                return None
            words.append(f"{letter}{int(value)}")
            read[letter] = float(int(value))
        else:  # angles
            counts = quantize(value, ANGLE_DECIMALS)
            words.append(letter + counts_text(counts, ANGLE_DECIMALS))
            read[letter] = counts / 10**ANGLE_DECIMALS
    if first not in read or second not in read:
        return None
    points = _SHAPES[cdef.cycle](read, (read[first], read[second]), target)
    return words if points is not None and _same_holes(c, points) else None


def _same_holes(c: Cycle, points: Points) -> bool:
    if len(points) != len(c.holes):
        return False
    a, b, n = c.plane.first, c.plane.second, c.plane.normal
    for (u, v), hole in zip(points, c.holes, strict=True):
        if abs(u - hole[a]) > _TOL_MM or abs(v - hole[b]) > _TOL_MM:
            return False
        if any(hole[k] != c.start[k] for k in range(6) if k not in (a, b, n)):
            return False
    return True


def _count(read: dict[str, float], letter: str) -> int | None:
    v = read.get(letter)
    return int(v) if v is not None and v == int(v) and v != 0 else None


def _polar(centre: tuple[float, float], radius: float, angles_deg: list[float]) -> Points:
    return [(centre[0] + radius * math.cos(math.radians(a)), centre[1] + radius * math.sin(math.radians(a)))
            for a in angles_deg]


def _circle(read: dict[str, float], origin: tuple[float, float], target: Target) -> Points | None:
    k = _count(read, "K")
    if k is None:
        return None
    step = math.copysign(360.0 / abs(k), k)
    return _polar(origin, read.get("I", 0.0), [read.get("J", 0.0) + i * step for i in range(abs(k))])


def _line(read: dict[str, float], origin: tuple[float, float], target: Target) -> Points | None:
    k, pitch, angle = _count(read, "K"), read.get("I", 0.0), math.radians(read.get("J", 0.0))
    if k is None or k < 0:
        return None
    return [(origin[0] + i * pitch * math.cos(angle), origin[1] + i * pitch * math.sin(angle)) for i in range(k)]


def _arc(read: dict[str, float], origin: tuple[float, float], target: Target) -> Points | None:
    k = _count(read, "K")
    if k is None or k < 0:
        return None
    return _polar(origin, read.get("I", 0.0), [read.get("J", 0.0) + i * read.get("P", 0.0) for i in range(k)])


def _grid(read: dict[str, float], origin: tuple[float, float], target: Target) -> Points | None:
    n1, n2 = _count(read, "P"), _count(read, "K")
    if n1 is None or n2 is None or n1 < 0 or n2 < 0:
        return None
    serpentine = target.option("g137_order", "serpentine") == "serpentine"
    out: Points = []
    for b in range(n2):
        cols = range(n1 - 1, -1, -1) if serpentine and b % 2 else range(n1)
        out.extend((origin[0] + a * read.get("I", 0.0), origin[1] + b * read.get("J", 0.0)) for a in cols)
    return out


_SHAPES = {"circle": _circle, "line": _line, "arc": _arc, "grid": _grid}
