"""The per-program work: program text + options -> one row (a pure function).

``program_row(task)`` is what every batch runs, on one machine (``-j N``) or on a
Dask cluster, so both give the same rows.  It compiles through :mod:`cncc.api`
(the driver's pipeline) and never raises on a bad program: the diagnostics are
counted by code.  The CPU time and the limits are the sandbox's business
(:mod:`cncc.batch.sandbox`), not this function's.
"""

from __future__ import annotations

import contextlib
import json
import math
import os
import tempfile
from collections import Counter
from collections.abc import Iterable, Iterator
from typing import Any

from cncc import diagnostics as dg
from cncc.backends.timing.events import CATEGORIES
from cncc.batch.options import Task
from cncc.ir import Arc, Linear, Rapid, SelectTool, ToolChange

Row = dict[str, Any]

AXES = ("x", "y", "z")
COLUMNS: tuple[str, ...] = (
    "key", "path", "machine", "sha256", "dialect", "dialect_from", "emit", "opt_level", "status", "reason",
    "errors", "warnings", "codes", "cycle_s", *(f"{c}_s" for c in CATEGORIES), "tools",
    *(f"{a}_{end}_mm" for a in AXES for end in ("min", "max")), "soft_limit_violations", "cpu_s",
)
"""The columns of a results file, in order (``codes``: {code: count}; ``tools``: list)."""

SOFT_LIMIT_CODES = frozenset({dg.VERIFY_SOFT_LIMIT, dg.SOFT_LIMIT})
STATUSES = ("ok", "error", "timeout", "memory", "crash")


def empty_row(task: Task) -> Row:
    row: Row = dict.fromkeys(COLUMNS)
    row.update(key=task.key, path=task.path, machine=task.machine, sha256=task.sha256, dialect=task.dialect,
               dialect_from=task.dialect_from, emit=task.options.emit, opt_level=task.options.opt_level,
               errors=0, warnings=0, codes={}, tools=[], soft_limit_violations=0)
    return row


def failed_row(task: Task, status: str, code: str, reason: str, cpu_s: float | None = None) -> Row:
    """The row of a program the sandbox could not finish (time, memory, crash)."""
    row = empty_row(task)
    row.update(status=status, reason=f"{reason} [{code}]", errors=1, codes={code: 1}, cpu_s=cpu_s)
    return row


def program_row(task: Task) -> Row:
    """Compile ``task.text`` for ``task.machine`` and fill its row (``cpu_s`` left empty)."""
    from cncc.api import compile_commands, compile_text

    o = task.options
    if task.read_error:
        return failed_row(task, "error", dg.CANNOT_READ, task.read_error)
    row = empty_row(task)
    with _offsets_file(o.offsets_text) as offsets:
        common: dict[str, Any] = dict(
            dialect=row["dialect"], machine=task.machine, opt_level=o.opt_level, max_steps=o.max_steps,
            strict=o.strict, dialect_options=dict(o.dialect_options), include_dirs=list(task.include_dirs),
            offsets_file=offsets)
        cmds, _ = compile_commands(task.text, **common)  # the path, for the tools and extents
        if o.emit == "timing":  # the driver's diagnostics: the front end's, then the plan's
            result = compile_text(task.text, emit="timing", report_format="json", compare=f"O{o.opt_level}",
                                  **common)
            _fill_timing(row, result.output)
        else:
            result = compile_text(task.text, emit="none", **common)
    diags = list(result.sink)
    codes = Counter(d.code for d in diags if d.severity >= dg.Severity.WARNING)
    first = next((d for d in diags if d.severity is dg.Severity.ERROR), None)
    row.update(
        status="error" if first is not None else "ok",
        reason=f"{first.message} [{first.code}]" if first is not None else "",
        errors=sum(d.severity is dg.Severity.ERROR for d in diags) + result.sink.dropped,
        warnings=sum(d.severity is dg.Severity.WARNING for d in diags),
        codes=dict(sorted(codes.items())),
        soft_limit_violations=sum(d.code in SOFT_LIMIT_CODES for d in diags),
        tools=sorted({c.tool for c in cmds if isinstance(c, SelectTool | ToolChange)}),
    )
    row.update(extents_mm(cmds))
    return row


@contextlib.contextmanager
def _offsets_file(text: str | None) -> Iterator[str | None]:
    """``--offsets`` text as a temporary file (the driver reads offsets from a file)."""
    if text is None:
        yield None
        return
    fd, path = tempfile.mkstemp(prefix="cncc-batch-", suffix=".toml")
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(text)
        yield path
    finally:
        os.unlink(path)


def _fill_timing(row: Row, output: str) -> None:
    if not output.strip():
        return
    doc = json.loads(output)
    col = doc["columns"][0]
    row["cycle_s"] = col["total_ns"] / 1e9
    for cat in CATEGORIES:
        row[f"{cat}_s"] = col["by_category"][cat]["time_ns"] / 1e9


def extents_mm(cmds: Iterable[object]) -> Row:
    """Program-coordinate extents (mm) of X, Y and Z over every move, arcs' bulges included."""
    lo = [math.inf] * 3
    hi = [-math.inf] * 3

    def see(p: tuple[float, ...]) -> None:
        for i in range(3):
            lo[i] = min(lo[i], p[i])
            hi[i] = max(hi[i], p[i])

    for c in cmds:
        if isinstance(c, Rapid | Linear | Arc):
            see(c.start)
            see(c.end)
            if isinstance(c, Arc):
                for p in _arc_extremes(c):
                    see(p)
    out: Row = {}
    for i, a in enumerate(AXES):
        out[f"{a}_min_mm"] = round(lo[i], 6) if lo[i] <= hi[i] else None
        out[f"{a}_max_mm"] = round(hi[i], 6) if lo[i] <= hi[i] else None
    return out


def _arc_extremes(arc: Arc) -> list[tuple[float, ...]]:
    """The points where the arc crosses the in-plane axis directions (0, 90, 180, 270 degrees)."""
    i, j, _ = arc.plane.value
    ci, cj = arc.center[i], arc.center[j]
    r = math.hypot(arc.start[i] - ci, arc.start[j] - cj)
    a0 = math.atan2(arc.start[j] - cj, arc.start[i] - ci)
    a1 = math.atan2(arc.end[j] - cj, arc.end[i] - ci)
    ccw = arc.turns > 0
    sweep = (a1 - a0) % (2 * math.pi) if ccw else (a0 - a1) % (2 * math.pi)
    if sweep < 1e-12:
        sweep = 2 * math.pi
    sweep += (abs(arc.turns) - 1) * 2 * math.pi
    out = []
    for k in range(4):
        ang = k * math.pi / 2
        off = (ang - a0) % (2 * math.pi) if ccw else (a0 - ang) % (2 * math.pi)
        if off <= sweep:
            p = list(arc.start)
            p[i], p[j] = ci + r * math.cos(ang), cj + r * math.sin(ang)
            out.append(tuple(p))
    return out
