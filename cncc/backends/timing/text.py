"""The terminal timing report (``--report-format=text``, the default), drawn with rich.

Consumes a :class:`TimingReport`; produces text: a summary, time per category and
per tool, the slowest blocks with what limited them, and the per-line table (up to
:data:`MAX_LINES` lines; the JSON report always has every line).  Colour only when
the caller says the output is a terminal.  The tables fit ``width`` columns (the
terminal's, from the caller; :data:`WIDTH` when the output is a file or a pipe and
``COLUMNS`` is not set); totals are given as h:mm:ss beside the seconds; no line ends
in spaces.
"""

from __future__ import annotations

import io
import os
import re

from cncc.backends.timing.events import CATEGORIES
from cncc.backends.timing.model import LineRow, TimingReport, hms, to_s

MAX_LINES = 400
WIDTH = 120
MIN_WIDTH = 40
_TRAILING = re.compile(r"[ \t]+((?:\x1b\[[0-9;]*m)*)$", re.M)


def report_width(width: int | None) -> int:
    """``width`` if given, else ``$COLUMNS``, else :data:`WIDTH`; at least :data:`MIN_WIDTH`."""
    if width is None:
        env = os.environ.get("COLUMNS", "")
        width = int(env) if env.isdigit() else WIDTH
    return max(width, MIN_WIDTH)


def _s(ns: int) -> str:
    return f"{to_s(ns):.3f}"


def _gap(planned_ns: int, nominal_ns: int) -> str:
    if nominal_ns == 0:
        return "" if planned_ns == 0 else "n/a"
    return f"{(planned_ns - nominal_ns) / nominal_ns * 100:+.1f}%"


def render_text(rep: TimingReport, color: bool = False, width: int | None = None) -> str:
    from rich.console import Console
    from rich.markup import escape
    from rich.table import Table

    buf = io.StringIO()
    con = Console(file=buf, width=report_width(width), force_terminal=color, color_system="standard" if color else None,
                  highlight=False, emoji=False)
    cols = rep.columns
    labels = [c.run.label for c in cols]
    nom = rep.nominal
    p = rep.primary
    con.print(f"[bold]cycle time[/bold] of {escape(rep.file)} ({rep.dialect}) — primary column {labels[0]}: "
              f"{p.run.planner}, machine {p.run.machine.name}")
    for c in cols:
        con.print(f"  {escape(c.run.label):<8} total {_s(c.total_ns):>10} s ({hms(c.total_ns)}) = trajectory "
                  f"{_s(c.motion_ns)} s + events {_s(c.event_ns)} s")
    if nom is not None and nom != 0:
        con.print(f"  planned vs nominal: {_gap(p.total_ns, cols[nom].total_ns)} "
                  f"({_s(p.total_ns - cols[nom].total_ns)} s the length/feed estimate misses)")
    if p.operator_ns or bool(rep.lines.operator_dependent.any()):
        con.print(f"  * operator-dependent stops and waits: {_s(p.operator_ns)} s assumed (machine model)")

    def table(title: str, first: str) -> Table:
        t = Table(title=title, title_justify="left", show_edge=False, pad_edge=False, min_width=len(title))
        t.add_column(first)
        for lab in labels:
            t.add_column(f"{lab} [s]", justify="right")
        return t

    t = table("time per category", "category")
    t.add_column("share", justify="right")
    for cat in CATEGORIES:
        vals = [c.category_ns[cat] for c in cols]
        if any(vals):
            share = f"{vals[0] / p.total_ns * 100:.1f}%" if p.total_ns else ""
            t.add_row(cat.replace("_", " "), *map(_s, vals), share)
    t.add_row("[bold]total[/bold]", *(f"{_s(c.total_ns)} ({hms(c.total_ns)})" for c in cols), "")
    con.print(t)
    t = table("time per tool", "tool")
    for tool in sorted({k for c in cols for k, v in c.tool_ns.items() if any(v.values())}):
        t.add_row("none" if tool < 0 else f"T{tool}",
                  *(f"{_s(ns)} ({hms(ns)})" for ns in (sum(c.tool_ns.get(tool, {}).values()) for c in cols)))
    con.print(t)
    con.print(_line_table(rep, rep.top(), f"the {rep.top_n} slowest blocks", labels, con.width))
    blocks = rep.blocks()
    if len(blocks) < sum(1 for n in rep.lines.n if n) + (1 if any(not n for n in rep.lines.n) else 0):
        t = table("time per N block", "N")
        for n, ts in blocks:
            t.add_row(n or "(none)", *map(_s, ts))
        con.print(t)
    shown = rep.lines[:MAX_LINES]
    con.print(_line_table(rep, shown, "time per line", labels, con.width, elapsed=True))
    if len(rep.lines) > MAX_LINES:
        con.print(f"  ({len(rep.lines) - MAX_LINES} more lines: see --report-format=json)")
    return _TRAILING.sub(r"\1", buf.getvalue())


def _line_table(rep: TimingReport, rows: list[LineRow], title: str, labels: list[str], width: int,
                elapsed: bool = False) -> object:
    """Times, N and limit columns as wide as their contents; the block text gets the rest of ``width``."""
    from rich.cells import cell_len
    from rich.markup import escape
    from rich.table import Table

    multi_file = len(rep.lines.files) > 1
    heads = ["line", "N"] + (["elapsed [s]"] if elapsed else []) + [f"{lab} [s]" for lab in labels] + ["limited by"]
    body = []
    for r in rows:
        cells = [f"{r.file}:{r.line}" if multi_file else str(r.line), r.n]
        if elapsed:
            cells.append(_s(r.elapsed_ns))
        cells += [_s(v) for v in r.times_ns]
        cells.append(r.limited_by.replace("_", " ") + (" *" if r.operator_dependent else ""))
        body.append((cells, r.text))
    widths = [max([min(cell_len(h), 6)] + [cell_len(c[k]) for c, _ in body]) for k, h in enumerate(heads)]
    rest = width - sum(widths) - 3 * len(heads)
    t = Table(title=title, title_justify="left", show_edge=False, pad_edge=False)
    for k, (h, w) in enumerate(zip(heads, widths, strict=True)):
        t.add_column(h, justify="left" if k == 1 or k == len(heads) - 1 else "right", min_width=w, max_width=w)
    t.add_column("block", overflow="ellipsis", no_wrap=True, max_width=max(rest, 8))
    for cells, text in body:
        t.add_row(*(escape(c) for c in cells), escape(text))
    return t
