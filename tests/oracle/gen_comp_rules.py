"""Generated programs for what LinuxCNC refuses while cutter compensation is on (G53, G28/G30,
G28.1/G30.1, G92/G52, G10 L2/L20, work systems, G98/G99, G61/G64, M6, G43/G49, canned cycles,
G33, a second G41/G42, M48-M53, #5420-#5428) and what it allows (G10 L2 of another system,
G92.1-G92.3, T, DEBUG reading #5420); each code before the first compensated move or after
it, sometimes beside the G40 or G41 that decides whether compensation is on when it runs."""

from __future__ import annotations

import random

from tests.oracle import programs as base

_CODES = ["G53 G0 X{a}", "G28", "G30 X{a}", "G28.1", "G30.1", "G92 X{a}", "G52 Y{a}", "G10 L2 P1 X{a}",
          "G10 L2 P2 X{a}", "G10 L20 P0 Y{a}", "G10 L2 P0 Z{a}", "G55", "G54", "G98", "G99", "G61", "G64 P0.01",
          "G61.1", "T2 M6", "M6", "T2", "G43 H2", "G49", "G43.1 Z{a}", "G81 X{a} Y{a} Z-1 R1", "G92.1", "G92.2",
          "G92.3", "G41.1 D1", "G42 D2", "M48", "M49", "M50 P0", "M51 P1", "#1 = #5420", "#<y> = [#5421 + 1]",
          "(debug, x #5420 y #5421)", "M3 S500", "M8", "M9", "G4 P0.1", "G20", "G21", "G90.1", "G91.1"]


def comp_rules(rng: random.Random) -> base.Program:
    n = base.num
    out = ["G21 G90 G17 F200", "T1 M6", "G0 X-20 Y-20 Z5", "G1 Z-1"]
    side = rng.choice(["G41", "G42", "G41.1 D2", "G42.1 D2"])
    code = rng.choice(_CODES).format(a=n(rng.uniform(-5, 5)))
    where = rng.random()
    if where < 0.3:  # compensation on, no move yet
        out += [side, code, "G1 X0 Y0"]
    elif where < 0.45:  # in the block that turns it on
        alone = "#" in code or "(" in code or code.startswith("M")  # M48-M53 run before the G41: cncc lacks them
        out += [side, code, "G1 X0 Y0"] if alone else [f"{side} {code}", "G1 X0 Y0"]
    else:
        out.append(f"{side} G1 X0 Y0")
        out.append(code if rng.random() < 0.8 or "#" in code or "(" in code else f"G40 {code}")
    out += ["G1 X10 Y0", "G1 X10 Y10", "G40 G1 X30 Y30", "G0 Z5"]
    return base.Program(base._end(out, rng), base.TOOLS)
