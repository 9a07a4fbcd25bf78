"""The JSON timing report (``--report-format=json``), described by ``schema.json``.

Every time is given twice: ``*_ns`` integers, which add up exactly (the lines' times
sum to the total, the total is the trajectory's duration plus the events), and
``*_s`` floats for people and plotting.  Times that depend on the plan are lists with
one entry per column (``columns``; the first is the primary).
"""

from __future__ import annotations

import json
from importlib import resources
from typing import Any

from cncc.backends.timing.events import CATEGORIES
from cncc.backends.timing.model import Column, TimingReport, to_s

SCHEMA_ID = "cncc-timing/1"


def schema() -> dict[str, Any]:
    """The JSON Schema (draft 2020-12) of the report."""
    text = resources.files(__package__).joinpath("schema.json").read_text(encoding="utf-8")
    doc: dict[str, Any] = json.loads(text)
    return doc


def _t(ns: int) -> dict[str, Any]:
    return {"time_s": to_s(ns), "time_ns": ns}


def _column(c: Column) -> dict[str, Any]:
    r = c.run
    return {
        "label": r.label, "machine": r.machine.name, "level": r.level, "planner": r.planner, "nominal": r.nominal,
        "total_s": to_s(c.total_ns), "total_ns": c.total_ns,
        "trajectory_s": to_s(c.motion_ns), "trajectory_ns": c.motion_ns,
        "events_s": to_s(c.event_ns), "events_ns": c.event_ns,
        "operator_dependent_s": to_s(c.operator_ns), "operator_dependent_ns": c.operator_ns,
        "phases": r.trajectory.phase_count,
        "by_category": {cat: _t(c.category_ns[cat]) for cat in CATEGORIES},
    }


def report_dict(rep: TimingReport) -> dict[str, Any]:
    cols = rep.columns
    p = rep.primary
    tools = sorted({t for c in cols for t in c.tool_ns})
    return {
        "schema": SCHEMA_ID,
        "file": rep.file,
        "dialect": rep.dialect,
        "columns": [_column(c) for c in cols],
        "nominal_column": rep.nominal,
        "total_s": to_s(p.total_ns),
        "total_ns": p.total_ns,
        "by_tool": [{
            "tool": None if t < 0 else t,
            "times_ns": [sum(c.tool_ns.get(t, {}).values()) for c in cols],
            "times_s": [to_s(sum(c.tool_ns.get(t, {}).values())) for c in cols],
            "by_category_ns": {cat: p.tool_ns.get(t, {}).get(cat, 0) for cat in CATEGORIES},
        } for t in tools],
        "lines": [{
            "file": r.file, "line": r.line, "n": r.n, "text": r.text,
            "times_ns": list(r.times_ns), "times_s": [to_s(t) for t in r.times_ns],
            "category": r.category, "limited_by": r.limited_by, "limits_ns": r.limits_ns,
            "elapsed_s": to_s(r.elapsed_ns), "operator_dependent": r.operator_dependent,
        } for r in rep.lines],
        "blocks": [{"n": n, "times_ns": list(ts), "times_s": [to_s(t) for t in ts]} for n, ts in rep.blocks()],
        "top": [{"file": r.file, "line": r.line, "n": r.n, "time_s": to_s(r.times_ns[0]),
                 "limited_by": r.limited_by} for r in rep.top()],
        "events": [{
            "file": rep.lines[int(rep.index.cmd_line[i])].file, "line": rep.lines[int(rep.index.cmd_line[i])].line,
            "category": cat, "what": what, "operator_dependent": op, **_t(ns),
        } for i, ns, cat, op, what in p.event_list],
    }


INDENT_MAX_LINES = 2_000
"""Larger reports are written compactly (indenting makes json use its slow Python encoder)."""


def render_json(rep: TimingReport) -> str:
    indent = 1 if len(rep.lines) <= INDENT_MAX_LINES else None
    return json.dumps(report_dict(rep), indent=indent) + "\n"
