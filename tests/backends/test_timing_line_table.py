"""The timing report's line arrays and the streamed JSON writer.

Checked against independent computations: the streamed JSON against ``json.dumps`` of
the report's dict (the schema's reference form), the array aggregations (per N block,
top lines) against the row-by-row definitions.
"""

from __future__ import annotations

import json
import math
import random

import pytest

from cncc.api import compile_commands
from cncc.backends.timing.aggregate import build_report
from cncc.backends.timing.jsonout import INDENT_MAX_LINES, LINES_PER_CHUNK, iter_json, render_json, report_dict
from cncc.backends.timing.model import Run
from cncc.driver import resolve_machine
from cncc.ir.machine import MachineModel
from tests.backends.test_timing_report import synthetic_plan


def machine() -> MachineModel:
    m = resolve_machine("generic-mill", None)  # type: ignore[arg-type]
    assert m is not None
    return m


def program(n_lines: int, seed: int) -> str:
    """Moves, arcs, N words (some repeated), dwells, tool changes, M00 and a non-ASCII comment."""
    rnd = random.Random(seed)
    out = ["%", "O1000 (line table)", "G90 G17 G71 G94", "T1 M06", "S1000 M03", "G00 X0 Y0 Z5", "G01 Z-1 F500"]
    x = 0.0
    for i in range(n_lines):
        x += rnd.uniform(0.1, 2.0)
        n = f"N{rnd.choice([10, 20, 30, i])} " if rnd.random() < 0.3 else ""
        r = rnd.random()
        if r < 0.05:
            out.append(f"{n}G04 X{rnd.uniform(0.1, 1):.2f}")
        elif r < 0.07:
            out.append(f"{n}M00")
        elif r < 0.09:
            out.append(f"{n}T{rnd.randint(1, 9)} M06 (Werkzeug wechseln — µ)")
        elif r < 0.2:
            out.append(f"{n}G02 X{x:.3f} Y0 R{rnd.uniform(5, 10):.3f} F{rnd.randint(100, 900)}")
        else:
            out.append(f"{n}G01 X{x:.3f} Y{rnd.uniform(-1, 1):.3f}")
    out += ["M30", "%"]
    return "\n".join(out) + "\n"


def report_of(text: str, columns: int = 1):  # type: ignore[no-untyped-def]
    cmds, res = compile_commands(text)
    assert res.ok, [d.message for d in res.sink]
    traj = synthetic_plan(cmds)
    runs = [Run(f"O{k}", machine(), k, traj, "synthetic") for k in range(columns)]
    return build_report(cmds, runs, res.sources, "<text>", "syntec")


@pytest.mark.parametrize(("n_lines", "columns", "seed"), [(INDENT_MAX_LINES + 500, 1, 1), (INDENT_MAX_LINES + 50, 2, 2),
                                                         (9000, 1, 3)])
def test_streamed_json_is_json_dumps_of_the_report(n_lines: int, columns: int, seed: int) -> None:
    rep = report_of(program(n_lines, seed), columns)
    assert len(rep.lines) > INDENT_MAX_LINES  # the streamed form, not the indented one
    streamed = "".join(iter_json(rep))
    assert streamed == json.dumps(report_dict(rep)) + "\n"
    pieces = list(iter_json(rep))
    assert len(pieces) >= 2 + math.ceil(len(rep.lines) / LINES_PER_CHUNK)  # really in pieces
    doc = json.loads(streamed)
    assert sum(line["times_ns"][0] for line in doc["lines"]) == doc["total_ns"]


def test_small_reports_stay_indented() -> None:
    rep = report_of(program(50, 4))
    assert render_json(rep) == json.dumps(report_dict(rep), indent=1) + "\n"


def test_array_aggregations_match_the_row_definitions() -> None:
    rep = report_of(program(3000, 5), columns=2)
    rows = list(rep.lines)
    assert len(rows) == len(rep.lines) and rows[-1] == rep.lines[-1] and rows[:3] == rep.lines[:3]
    by_n: dict[str, list[int]] = {}
    for r in rows:
        acc = by_n.setdefault(r.n, [0, 0])
        acc[0] += r.times_ns[0]
        acc[1] += r.times_ns[1]
    assert rep.blocks() == [(n, tuple(v)) for n, v in by_n.items()]
    ranked = sorted(rows, key=lambda r: (-r.times_ns[0], r.index))
    assert rep.top() == [r for r in ranked[: rep.top_n] if r.times_ns[0] > 0]
    src = program(3000, 5).split("\n")
    for r in rows[:200]:
        assert r.text == src[r.line - 1].strip()
        assert r.n == (src[r.line - 1].split()[0] if src[r.line - 1].startswith("N") else "")
    with pytest.raises(IndexError):
        rep.lines[len(rep.lines)]
