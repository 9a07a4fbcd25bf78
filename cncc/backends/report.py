"""Timing report (``--emit=timing``).

At ``-O0`` the times are nominal (length / feed, see :mod:`cncc.backends.nominal`).
Higher levels use the planner's Trajectory when the planning passes are installed;
the report says which level produced the figures.
"""

from __future__ import annotations

import json
from collections.abc import Iterator

from cncc.diagnostics import DiagnosticSink
from cncc.ir import Command
from cncc.ir.machine import MachineModel
from cncc.source import SourceFile, SourceMap


def _fmt_s(t: float) -> str:
    return f"{t:10.3f}"


def timing_report(cmds: list[Command], src: SourceFile, sources: SourceMap, machine: MachineModel,
                  level: int, fmt: str, sink: DiagnosticSink) -> Iterator[str]:
    from cncc.backends.nominal import nominal_timing

    nominal = nominal_timing(cmds, machine)
    by_line: dict[int, float] = {}
    for c, t, _cat in nominal.by_command:
        if c.span.source_id != src.source_id:
            continue
        line = src.position(c.span.start).line
        by_line[line] = by_line.get(line, 0.0) + t
    if fmt == "json":
        doc = {
            "schema": "cncc-timing/1",
            "file": src.name,
            "machine": machine.name,
            "level": 0,
            "total_s": nominal.total_s,
            "by_category_s": nominal.by_category_s,
            "by_line_s": {str(k): v for k, v in sorted(by_line.items())},
        }
        yield json.dumps(doc, indent=2) + "\n"
        return
    yield f"cycle time for {src.name} on {machine.name} (nominal, -O0: length / feed)\n"
    yield f"  total {nominal.total_s:.3f} s\n"
    for cat, t in sorted(nominal.by_category_s.items(), key=lambda kv: -kv[1]):
        yield f"  {cat:<12}{_fmt_s(t)} s\n"
    yield "  line        time [s]  block\n"
    for line, t in sorted(by_line.items()):
        yield f"  {line:>5} {_fmt_s(t)}  {src.line_text(line).strip()}\n"
