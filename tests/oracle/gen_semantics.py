"""Generated programs for issue 24's semantic items that no other generator reaches.

G52 and G92 on the same offset (with G92.1/.2/.3), G43 and G41 without H/D (the loaded
tool), G0 or G1 with G80 in one block, an A/B/C word in a canned-cycle block, MOD with
negative operands, an assignment without brackets, a G90.1 arc missing a centre word, and
the end of a program: M2/M30, a closing ``%`` (text after it), or no end at all.
"""

from __future__ import annotations

import random

from tests.oracle import programs as base


def _piece(rng: random.Random) -> list[str]:
    n = base.num
    c = rng.random()
    if c < 0.2:
        out = [f"{rng.choice(['G92', 'G52'])} X{n(rng.uniform(-9, 9))}"]
        out += [rng.choice(["G52 Y2", "G92 Z1", "G92.1", "G92.2", "G92.3", "G52 X0"]), f"G0 X{n(rng.uniform(-9, 9))}"]
        return out
    if c < 0.35:
        t = rng.randint(1, 3)
        return [f"T{t} M6", "G43", f"G0 Z{n(rng.uniform(1, 9))}", f"G41 G1 F100 X{n(rng.uniform(10, 20))} Y0",
                "G1 Y10", "G40 G1 X30 Y-5", "G49"]
    if c < 0.5:
        return [f"{rng.choice(['G0 G80', 'G80 G0', 'G1 F100 G80', 'G80 G1 F100'])} X{n(rng.uniform(-9, 9))}"]
    if c < 0.65:
        letter = rng.choice("ABC")
        first = rng.random() < 0.5
        cyc = f"G0 Z5\nG81 X1 Y1 Z-1 R1 F100{f' {letter}3' if first else ''}"
        return [cyc, f"X2{'' if first else f' {letter}3'}", "G80"]
    if c < 0.75:  # G90.1: both centre words of the plane are needed (in G91.1 a missing one is 0)
        plane, pair = rng.choice([("G17", "IJ"), ("G18", "IK"), ("G19", "JK")])
        words = {"I": "I2", "J": "J0", "K": "K0"} if plane != "G19" else {"J": "J2", "K": "K0", "I": "I0"}
        drop = rng.choice(pair + "-")
        centre = " ".join(words[ch] for ch in pair if ch != drop)
        end = {"G17": "X4 Y0", "G18": "X4 Z0", "G19": "Y4 Z0"}[plane]
        return [f"G0 X0 Y0 Z0 F100 {plane}", f"{rng.choice(['G90.1', 'G91.1'])} G2 {end} {centre}", "G91.1 G17"]
    if c < 0.9:
        a, b = rng.choice([7, -7, 7.5, -2]), rng.choice([3, -3, 2.5, -4])
        return [f"#1 = [{a} MOD {b}]", "G0 X#1"]
    return [f"#2 = {rng.randint(1, 5)} {rng.choice(['*', '+', '-', '/'])} {rng.randint(1, 5)}", "G0 Y#2"]


def semantics(rng: random.Random) -> base.Program:
    body = ["G21 G90 G17"]
    for _ in range(rng.randint(1, 2)):
        body += _piece(rng)
    end = rng.random()
    if end < 0.6:
        text = base._end(body, rng)
    elif end < 0.8:
        text = "%\n" + "\n".join(body) + "\n%\n" + rng.choice(["", "G0 X99\n", "M2\n"])
    elif end < 0.9:
        text = "%\n" + "\n".join(body) + "\n"  # opened with % and never closed
    else:
        text = "\n".join(body) + "\n"  # no M2, M30 or %
    return base.Program(text, base.TOOLS)
