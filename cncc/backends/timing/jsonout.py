"""The JSON timing report (``--report-format=json``), described by ``schema.json``.

Every time is given twice: ``*_ns`` integers, which add up exactly (the lines' times
sum to the total, the total is the trajectory's duration plus the events), and
``*_s`` floats for people and plotting.  Times that depend on the plan are lists with
one entry per column (``columns``; the first is the primary).
"""

from __future__ import annotations

import json
from collections.abc import Iterator
from importlib import resources
from json.encoder import encode_basestring_ascii
from typing import Any

from cncc.backends.timing.events import CATEGORIES
from cncc.backends.timing.model import LIMIT_KEYS, NS_PER_S, Column, TimingReport, to_s

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
        "phases": r.phase_count,
        "by_category": {cat: _t(c.category_ns[cat]) for cat in CATEGORIES},
    }


def report_dict(rep: TimingReport, with_lines: bool = True) -> dict[str, Any]:
    """The report as JSON-ready data (``with_lines=False``: a placeholder where the lines go)."""
    cols = rep.columns
    lines = rep.lines
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
        } for r in rep.lines] if with_lines else _LINES,
        "blocks": [{"n": n, "times_ns": list(ts), "times_s": [to_s(t) for t in ts]} for n, ts in rep.blocks()],
        "top": [{"file": r.file, "line": r.line, "n": r.n, "time_s": to_s(r.times_ns[0]),
                 "limited_by": r.limited_by} for r in rep.top()],
        "events": [{
            "file": lines.files[int(lines.file_of[k])], "line": int(lines.line[k]),
            "category": cat, "what": what, "operator_dependent": op, **_t(ns),
        } for i, ns, cat, op, what in p.event_list for k in (int(rep.index.cmd_line[i]),)],
    }


INDENT_MAX_LINES = 2_000
"""Larger reports are written compactly (indenting makes json use its slow Python encoder)."""

_LINES = "\u0000lines of the report\u0000"
"""Placeholder for the lines in :func:`report_dict` (``with_lines=False``); no real value holds it."""

LINES_PER_CHUNK = 4096


def render_json(rep: TimingReport) -> str:
    return "".join(iter_json(rep))


def iter_json(rep: TimingReport) -> Iterator[str]:
    """The JSON report in pieces: byte for byte what ``json.dumps(report_dict(rep))`` writes
    (indented up to :data:`INDENT_MAX_LINES` lines), with the lines formatted from the
    report's arrays a chunk at a time instead of as one dict per line."""
    if len(rep.lines) <= INDENT_MAX_LINES:
        yield json.dumps(report_dict(rep), indent=1) + "\n"
        return
    head, tail = json.dumps(report_dict(rep, with_lines=False)).split(json.dumps(_LINES))
    yield head + "["
    for lo in range(0, len(rep.lines), LINES_PER_CHUNK):
        yield ", ".join(_line_json(rep, lo, min(lo + LINES_PER_CHUNK, len(rep.lines))))
        if lo + LINES_PER_CHUNK < len(rep.lines):
            yield ", "
    yield "]" + tail + "\n"


def _line_json(rep: TimingReport, lo: int, hi: int) -> list[str]:
    """Lines ``lo:hi`` as json.dumps writes each line's dict (default separators, ASCII)."""
    import numpy as np

    tab = rep.lines
    enc = encode_basestring_ascii
    files = [f'{{"file": {enc(f)}, "line": ' for f in tab.files]
    cats = [enc(c) for c in tab.categories] + [enc("")]  # index -1: ""
    limits = [enc(k) for k in LIMIT_KEYS] + [enc("")]
    limit_names = [enc(k) + ": " for k in LIMIT_KEYS]
    width = len(limits)
    mid = [f'"category": {c}, "limited_by": {lim}, "limits_ns": {{' for c in cats for lim in limits]
    mid_of = (np.where(tab.category[lo:hi] < 0, len(cats) - 1, tab.category[lo:hi]).astype(np.int64) * width
              + np.where(tab.limited_by[lo:hi] < 0, width - 1, tab.limited_by[lo:hi]))
    t_ns = tab.times_ns[lo:hi]
    if t_ns.shape[1] == 1:
        times = [f'"times_ns": [{v}], "times_s": [{v / NS_PER_S!r}], ' for v in t_ns[:, 0].tolist()]
    else:
        times = [f'"times_ns": [{", ".join(map(repr, ts))}], "times_s": [{", ".join(repr(v / NS_PER_S) for v in ts)}], '
                 for ts in t_ns.tolist()]
    block = tab.limits_ns[lo:hi]
    given = [""] * (hi - lo)
    rows, cols = np.nonzero(block)
    for r, c, v in zip(rows.tolist(), cols.tolist(), block[rows, cols].tolist(), strict=True):
        given[r] = f"{given[r]}, {limit_names[c]}{v}" if given[r] else f"{limit_names[c]}{v}"
    rows_ = zip(tab.file_of[lo:hi].tolist(), tab.line[lo:hi].tolist(), tab.n[lo:hi], tab.text[lo:hi], times,
                mid_of.tolist(), given, tab.elapsed_ns[lo:hi].tolist(), tab.operator_dependent[lo:hi].tolist(),
                strict=True)
    flag = (', "operator_dependent": false}', ', "operator_dependent": true}')
    return [f'{files[f]}{line}, "n": {enc(n)}, "text": {enc(text)}, {ts}{mid[m]}{lns}}}, "elapsed_s": '
            f'{end / NS_PER_S!r}{flag[op]}' for f, line, n, text, ts, m, lns, end, op in rows_]
