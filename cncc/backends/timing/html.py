"""The HTML timing report (``--report-format=html``): one self-contained page.

Consumes a :class:`TimingReport`; produces a page with inline CSS, inline SVG plots
(:mod:`.plots`) and a few lines of inline JavaScript (sortable tables).  It fetches
nothing, so it opens offline and can be mailed as one file.  When its script has
run, ``<body>`` carries ``data-ready="1"`` (the browser test looks for it).
"""

from __future__ import annotations

from collections.abc import Sequence
from html import escape

from cncc.backends.timing.events import CATEGORIES
from cncc.backends.timing.model import LineRow, TimingReport, to_s
from cncc.backends.timing.plots import feed_plot, path_plot, tool_plot
from cncc.ir import Command

MAX_LINES = 2000

_CSS = """
body{font-family:sans-serif;margin:24px;color:#222;max-width:1200px}
h1{font-size:20px}h2{font-size:16px;margin-top:28px}
table{border-collapse:collapse;font-size:12px}
th,td{padding:2px 8px;border-bottom:1px solid #eee;text-align:right}
th{background:#f4f4f4;cursor:pointer;position:sticky;top:0}
td.l,th.l{text-align:left}td.code{font-family:monospace;text-align:left;white-space:pre}
.plots{display:flex;flex-wrap:wrap;gap:16px}.note{color:#666;font-size:12px}
"""

_JS = """
(function(){
  function key(td){var v=td.getAttribute('data-v');return v===null?td.textContent:parseFloat(v);}
  document.querySelectorAll('table.sortable').forEach(function(tbl){
    tbl.querySelectorAll('th').forEach(function(th,col){
      th.addEventListener('click',function(){
        var body=tbl.tBodies[0],rows=Array.prototype.slice.call(body.rows);
        var dir=th.getAttribute('data-dir')==='asc'?-1:1;th.setAttribute('data-dir',dir>0?'asc':'desc');
        rows.sort(function(a,b){var x=key(a.cells[col]),y=key(b.cells[col]);return x<y?-dir:x>y?dir:0;});
        rows.forEach(function(r){body.appendChild(r);});
      });
    });
  });
  document.body.setAttribute('data-ready','1');
})();
"""


def _s(ns: int) -> str:
    return f"{to_s(ns):.3f}"


def _td(ns: int) -> str:
    return f'<td data-v="{ns}">{_s(ns)}</td>'


def _summary(rep: TimingReport) -> str:
    cols = rep.columns
    head = "".join(f"<th>{escape(c.run.label)}</th>" for c in cols)
    rows = [
        "<tr><td class=l>total [s]</td>" + "".join(_td(c.total_ns) for c in cols) + "</tr>",
        "<tr><td class=l>trajectory [s]</td>" + "".join(_td(c.motion_ns) for c in cols) + "</tr>",
        "<tr><td class=l>events [s]</td>" + "".join(_td(c.event_ns) for c in cols) + "</tr>",
    ]
    for cat in CATEGORIES:
        if any(c.category_ns[cat] for c in cols):
            rows.append(f"<tr><td class=l>· {cat.replace('_', ' ')}</td>"
                        + "".join(_td(c.category_ns[cat]) for c in cols) + "</tr>")
    rows.append("<tr><td class=l>planner</td>" + "".join(f"<td>{escape(c.run.planner)}</td>" for c in cols) + "</tr>")
    rows.append("<tr><td class=l>machine</td>" + "".join(f"<td>{escape(c.run.machine.name)}</td>" for c in cols)
                + "</tr>")
    return f"<table><thead><tr><th class=l></th>{head}</tr></thead><tbody>{''.join(rows)}</tbody></table>"


def _lines(rep: TimingReport, rows: Sequence[LineRow], elapsed: bool) -> str:
    head = "<th>line</th><th class=l>N</th>" + ("<th>elapsed [s]</th>" if elapsed else "")
    head += "".join(f"<th>{escape(c.run.label)} [s]</th>" for c in rep.columns)
    head += "<th class=l>limited by</th><th class=l>block</th>"
    body = []
    for r in rows:
        cells = f'<td data-v="{r.index}">{r.line}</td><td class=l>{escape(r.n)}</td>'
        if elapsed:
            cells += _td(r.elapsed_ns)
        cells += "".join(_td(t) for t in r.times_ns)
        lim = r.limited_by.replace("_", " ") + (" *" if r.operator_dependent else "")
        cells += f"<td class=l>{escape(lim)}</td><td class=code>{escape(r.text)}</td>"
        body.append(f"<tr>{cells}</tr>")
    return f"<table class=sortable><thead><tr>{head}</tr></thead><tbody>{''.join(body)}</tbody></table>"


def render_html(rep: TimingReport, cmds: Sequence[Command]) -> str:
    p = rep.primary
    gap = ""
    if rep.nominal not in (None, 0):
        nom = rep.columns[rep.nominal or 0]
        if nom.total_ns:
            gap = (f"<p>Planned {p.run.label} takes <b>{_s(p.total_ns)} s</b>; the nominal length/feed estimate "
                   f"says {_s(nom.total_ns)} s ({(p.total_ns - nom.total_ns) / nom.total_ns * 100:+.1f}%).</p>")
    more = (f"<p class=note>{len(rep.lines) - MAX_LINES} more lines: see --report-format=json.</p>"
            if len(rep.lines) > MAX_LINES else "")
    op = (f"<p class=note>* operator-dependent (M00, M01, waits): {_s(p.operator_ns)} s assumed from the machine "
          f"model.</p>" if any(r.operator_dependent for r in rep.lines) else "")
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>cycle time of {escape(rep.file)}</title>
<style>{_CSS}</style></head><body data-ready="0">
<h1>Cycle time of {escape(rep.file)}
<span class=note>({escape(rep.dialect)}, machine {escape(p.run.machine.name)})</span></h1>
{gap}{_summary(rep)}
<h2>Path speed over time, by limiting constraint</h2>
<div class=plots>{feed_plot(rep, len(cmds))}</div>
<h2>Tool path and time per tool</h2>
<div class=plots>{path_plot(rep)}{tool_plot(rep, 620)}</div>
<h2>The {rep.top_n} slowest blocks</h2>{_lines(rep, rep.top(), False)}
<h2>Time per line</h2>{op}{_lines(rep, rep.lines[:MAX_LINES], True)}{more}
<script>{_JS}</script>
</body></html>
"""
