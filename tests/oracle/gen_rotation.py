"""Generated programs for LinuxCNC's work-system XY rotation (``G10 L2 ... R``).

The rotation of the active system applies to every later move; the interpreter re-expresses
the tool's position when the active system's offsets or rotation change (G10 L2/L20 of the
active system, a select) and G53, G28/G30 and G10 L20/L10/L11 are taken in rotated terms.
The programs mix those with moves in G90/G91, arcs in every plane, G92 offsets and drilling
cycles; a share has ``R`` on G10 L20 (an rs274 error).
"""

from __future__ import annotations

import random

from tests.oracle import programs as base

_SYSTEMS = ("G54", "G55", "G56", "G59.3")


def _offset_words(rng: random.Random, k: float, letters: str = "XYZ") -> str:
    return " ".join(f"{ax}{base.num(rng.uniform(-30, 30) * k)}" for ax in rng.sample(letters, rng.randint(0, 2)))


def _step(rng: random.Random, k: float) -> list[str]:
    """One random statement of a rotated program."""
    c = rng.random()
    n = base.num
    if c < 0.16:
        p = rng.choice([0, 0, 1, 2, 9])
        return [f"G10 L2 P{p} {_offset_words(rng, k)} R{n(rng.uniform(-180, 180))}".replace("  ", " ")]
    if c < 0.22:
        words = _offset_words(rng, k, "XY") or f"X{n(rng.uniform(-5, 5) * k)}"
        r = f" R{n(rng.uniform(-90, 90))}" if rng.random() < 0.1 else ""
        return [f"G10 L20 P{rng.choice([0, 0, 1, 2])} {words}{r}"]
    if c < 0.30:
        return [rng.choice(_SYSTEMS)]
    if c < 0.46:
        return [f"{rng.choice(['G0', 'G1'])} X{n(rng.uniform(-40, 40) * k)} Y{n(rng.uniform(-40, 40) * k)}"
                + (f" Z{n(rng.uniform(-5, 5) * k)}" if rng.random() < 0.3 else "")]
    if c < 0.52:
        return [f"G91 G1 X{n(rng.uniform(-10, 10) * k)} Y{n(rng.uniform(-10, 10) * k)}", "G90"]
    if c < 0.60:
        r = rng.uniform(2, 10) * k
        return [f"G91 G{rng.choice([2, 3])} X{n(2 * r)} Y0 I{n(r)} J0", "G90"]
    if c < 0.64:
        return [f"G18 G91 G{rng.choice([2, 3])} Z{n(4 * k)} X0 K{n(2 * k)} I0", "G90 G17"]
    if c < 0.70:
        axes = " ".join(f"{ax}{n(rng.uniform(-20, 20) * k)}" for ax in rng.sample("XYZ", rng.randint(1, 2)))
        return [f"G53 {rng.choice(['G0', 'G1'])} {axes}"]
    if c < 0.76:
        mid = " ".join(f"{ax}{n(rng.uniform(-20, 20) * k)}" for ax in rng.sample("XYZ", rng.randint(0, 2)))
        return [f"{rng.choice(['G28', 'G30'])} {mid}".strip()]
    if c < 0.82:
        return [rng.choice([f"G92 X{n(rng.uniform(-10, 10) * k)} Y{n(rng.uniform(-10, 10) * k)}", "G92.1",
                            f"G52 X{n(rng.uniform(-10, 10) * k)}"])]
    if c < 0.88:
        return [f"G10 {rng.choice(['L10', 'L11'])} P1 Z{n(rng.uniform(-5, 5) * k)}", "G43 H1"]
    if c < 0.94:
        z = 5 * k
        return [f"G0 Z{n(z)}", f"G98 G81 X{n(rng.uniform(-20, 20) * k)} Y{n(rng.uniform(-20, 20) * k)} "
                f"Z{n(-z)} R{n(z / 2)}", f"X{n(rng.uniform(-20, 20) * k)}", "G80"]
    return [f"G2 X{n(rng.uniform(-20, 20) * k)} Y{n(rng.uniform(-20, 20) * k)} R{n(60 * k)}"]


def rotation(rng: random.Random) -> base.Program:
    u, k = base._units(rng)
    out = [f"{u} G90 G17 F{base.num(300 * k)}"]
    if rng.random() < 0.7:
        out.append(f"G10 L2 P1 {_offset_words(rng, k)} R{base.num(rng.uniform(-180, 180))}".replace("  ", " "))
    for _ in range(rng.randint(2, 8)):
        out += _step(rng, k)
    return base.Program(base._end(out, rng), base.TOOLS)
