"""Macro evaluator throughput: a macro-heavy program with nested WHILE loops that
produces N x M moves, beside the plain-block front-end rate on a flat program of
the same moves, measured in the same run.

    python bench/macros.py [--rows 1000] [--cols 1000] [--plain-lines 200000]

Prints, for the macro program: moves, executed steps (blocks + statements, the
unit of --max-steps), seconds, steps per second and moves per second; for the flat
program: blocks per second.  Both go through ``cncc.frontend.lower`` (parse,
macro execution, modal interpretation, IR commands), without the passes.
"""

from __future__ import annotations

import argparse
import sys
import time

MACRO_PROGRAM = """(NESTED-LOOP RASTER: #101 ROWS OF #102 MOVES)
#101={rows}. #102={cols}.
#1=0.
WHILE [#1 LT #101] DO 1
#2=0.
WHILE [#2 LT #102] DO 2
G01 X[#2*0.01] Y[#1*0.01+SIN[#2]*0.001] F1000.
#2=#2+1.
END 2
#1=#1+1.
END 1
M30
"""


def run(text: str, max_steps: int) -> tuple[int, int, float]:
    """(moves, steps, seconds) of lowering ``text`` with the syntec dialect."""
    from cncc.diagnostics import DiagnosticSink
    from cncc.dialects import load_dialect
    from cncc.frontend import InterpOptions, MacroOptions, lower
    from cncc.ir import MOTION_TYPES
    from cncc.source import SourceMap

    src = SourceMap().add("bench.nc", text)
    sink = DiagnosticSink()
    macro = MacroOptions(max_steps=max_steps)
    t0 = time.perf_counter()
    cmds = lower(src, load_dialect("syntec"), sink, InterpOptions(), macro)
    moves = sum(1 for c in cmds if isinstance(c, MOTION_TYPES))
    dt = time.perf_counter() - t0
    if sink.has_errors:
        print("errors:", [d.message for d in sink.items[:3]], file=sys.stderr)
    steps = rows_cols_steps(text)
    return moves, steps, dt


def rows_cols_steps(text: str) -> int:
    """Steps the macro program executes (each block 1, each statement 1 more)."""
    if "WHILE" not in text:
        return 0
    header = text.splitlines()[1].split()
    rows = int(float(header[0].split("=")[1]))
    cols = int(float(header[1].split("=")[1]))
    inner = 2 + 1 + 2 + 2  # WHILE, G01, assignment, END
    outer = 2 + 2 + 2 + 2  # WHILE, #2=0., #1=#1+1., END
    return rows * (cols * inner + 2 + outer) + 2 + 3 + 2


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rows", type=int, default=1000)
    ap.add_argument("--cols", type=int, default=1000)
    ap.add_argument("--plain-lines", type=int, default=200_000)
    args = ap.parse_args()

    text = MACRO_PROGRAM.format(rows=args.rows, cols=args.cols)
    moves, steps, dt = run(text, max_steps=20 * args.rows * args.cols + 1000)
    print(f"macro program : {moves:,} moves, {steps:,} steps in {dt:.2f} s -> "
          f"{steps / dt:,.0f} steps/s, {moves / dt:,.0f} moves/s")

    lines = ["G90 G01 F1000."]
    n = args.plain_lines
    for k in range(n):
        lines.append(f"X{(k % 1000) * 0.01:.3f} Y{(k // 1000) * 0.01:.3f}")
    lines.append("M30")
    plain_moves, _, pdt = run("\n".join(lines) + "\n", max_steps=10 * n)
    print(f"plain blocks  : {plain_moves:,} moves in {pdt:.2f} s -> {(n + 2) / pdt:,.0f} blocks/s")
    print(f"ratio         : the macro program runs at {(moves / dt) / ((n + 2) / pdt):.2f}x the plain-block rate "
          f"(per move)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
