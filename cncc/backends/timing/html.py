"""The HTML timing report (``--report-format=html``): one self-contained page.

Consumes a :class:`TimingReport` and the commands; produces a page with inline CSS,
its data as JSON (:mod:`.pagedata`: decimated, bounded in size whatever the program's
length) and an inline script (``page.js``) that draws on canvases: path speed over
time (zoom, pan, colours by the limiting constraint, events as bands, the nominal
speed dashed), the tool path in XY, XZ, YZ and a rotatable 3-D view (rapids dashed,
one colour per tool, drill holes circled), and links every plot point to its line.
It fetches nothing, so it opens offline and can be mailed as one file.  When its
script has run, ``<body>`` carries ``data-ready="1"`` (the browser tests wait for it).
"""

from __future__ import annotations

import base64
import json
from collections.abc import Sequence
from html import escape
from importlib import resources
from typing import Any

from cncc.backends.timing.events import CATEGORIES
from cncc.backends.timing.model import LineRow, TimingReport, hms, to_s
from cncc.backends.timing.pagedata import page_data, tool_table
from cncc.backends.timing.plots import tool_plot
from cncc.backends.timing.svg import CATEGORY_COLORS, HOLE_COLOR, LIMIT_COLORS, RAPID_COLOR, SELECTED_COLOR, TOOL_COLORS
from cncc.ir import Command

MAX_LINES = 2000

_CSS = """
body{font-family:sans-serif;margin:24px;color:#222;max-width:1160px}
h1{font-size:20px}h2{font-size:16px;margin-top:28px}
table{border-collapse:collapse;font-size:12px}
th,td{padding:2px 8px;border-bottom:1px solid #eee;text-align:right}
th{background:#f4f4f4;cursor:pointer;position:sticky;top:0}
td.l,th.l{text-align:left}td.code{font-family:monospace;text-align:left;white-space:pre}
tr[data-i]{cursor:pointer}tr[data-i]:hover{background:#f3f7ff}tr.sel{background:#ffe9c7}
.note{color:#555;font-size:12px}
#selected{position:sticky;top:0;z-index:2;background:#fffbe8;border:1px solid #e6d9a8;padding:4px 8px;
font-family:monospace;font-size:12px;white-space:pre;overflow:hidden;text-overflow:ellipsis}
#tip{position:absolute;display:none;z-index:3;background:#fff;border:1px solid #999;padding:3px 6px;
font-size:12px;white-space:pre;pointer-events:none;box-shadow:1px 1px 4px #0003}
canvas{display:block;border:1px solid #ddd;background:#fff}
#speed{width:100%;height:320px;cursor:crosshair}
.views{display:grid;grid-template-columns:1fr 1fr;gap:12px}.views canvas{width:100%;height:360px}
.views h3{font-size:13px;margin:0 0 4px 0;font-weight:normal}
.legend{display:flex;flex-wrap:wrap;gap:4px 16px;font-size:12px;margin:6px 0}
.legend span.sw{display:inline-block;width:18px;height:10px;margin-right:5px;vertical-align:middle}
.legend span.dash{display:inline-block;width:18px;margin-right:5px;vertical-align:middle;border-top:2px dashed}
.legend span.ring{display:inline-block;width:8px;height:8px;border:2px solid;border-radius:50%;margin-right:5px}
button{font-size:12px}
"""



def _s(ns: int) -> str:
    return f"{to_s(ns):.3f}"


def _td(ns: int) -> str:
    return f'<td data-v="{ns}">{_s(ns)}</td>'


def _tdh(ns: int) -> str:
    """Seconds with h:mm:ss beside them."""
    return f'<td data-v="{ns}">{_s(ns)} <span class=note>({hms(ns)})</span></td>'


def _summary(rep: TimingReport) -> str:
    cols = rep.columns
    head = "".join(f"<th>{escape(c.run.label)}</th>" for c in cols)
    rows = [
        "<tr><td class=l>total [s]</td>" + "".join(_tdh(c.total_ns) for c in cols) + "</tr>",
        "<tr><td class=l>trajectory [s]</td>" + "".join(_tdh(c.motion_ns) for c in cols) + "</tr>",
        "<tr><td class=l>events [s]</td>" + "".join(_tdh(c.event_ns) for c in cols) + "</tr>",
    ]
    for cat in CATEGORIES:
        if any(c.category_ns[cat] for c in cols):
            rows.append(f"<tr><td class=l>· {cat.replace('_', ' ')}</td>"
                        + "".join(_tdh(c.category_ns[cat]) for c in cols) + "</tr>")
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
        body.append(f'<tr data-i="{r.index}" data-t0="{to_s(r.elapsed_ns - r.times_ns[0]):.6f}" '
                    f'data-t1="{to_s(r.elapsed_ns):.6f}">{cells}</tr>')
    return f"<table class=sortable><thead><tr>{head}</tr></thead><tbody>{''.join(body)}</tbody></table>"


def _tools(rep: TimingReport, cmds: Sequence[Command]) -> str:
    cols = rep.columns
    head = "<th class=l>tool</th><th class=l>D in force</th><th class=l>H in force</th>"
    head += "".join(f"<th>{escape(c.run.label)} [s]</th>" for c in cols) + "<th>share</th>"
    body = []
    total = rep.primary.total_ns
    for t in tool_table(rep, cmds):
        name = "no tool" if t["tool"] < 0 else f"T{t['tool']}"
        cells = (f"<td class=l>{name}</td><td class=l>{' '.join(f'D{d}' for d in t['d']) or '–'}</td>"
                 f"<td class=l>{' '.join(f'H{h}' for h in t['h']) or '–'}</td>")
        cells += "".join(_tdh(ns) for ns in t["times_ns"])
        cells += f"<td>{t['times_ns'][0] / total * 100:.1f}%</td>" if total else "<td></td>"
        body.append(f"<tr>{cells}</tr>")
    return f"<table class=sortable><thead><tr>{head}</tr></thead><tbody>{''.join(body)}</tbody></table>"


def _legend(items: list[tuple[str, str, str]]) -> str:
    """(kind: sw | dash | ring, colour, label) as an HTML legend (text never overlaps a plot)."""
    return "<div class=legend>" + "".join(
        f'<span><span class={k} style="{"background" if k == "sw" else "border-color"}:{c}"></span>{escape(t)}</span>'
        for k, c, t in items) + "</div>"


def _extents(path: dict[str, Any]) -> str:
    if not path.get("n"):
        return ""
    lo, hi = path["lo"], path["hi"]
    rows = "".join(f"<tr><td class=l>{a}</td><td>{lo[k]:.3f}</td><td>{hi[k]:.3f}</td><td>{hi[k] - lo[k]:.3f}</td></tr>"
                   for k, a in enumerate("XYZ"))
    return ("<table><thead><tr><th class=l>extents</th><th>min [mm]</th><th>max [mm]</th><th>size [mm]</th></tr>"
            f"</thead><tbody>{rows}</tbody></table>"
            f"<p>Minimum Z <b>{lo[2]:.3f} mm</b>. Path length: feed <b>{path['feed_mm']:.1f} mm</b>, "
            f"rapid <b>{path['rapid_mm']:.1f} mm</b>. <span class=note>Drawn with {path['n']} of "
            f"{path['vertices_in']} vertices (within {path['tol_mm']:.3g} mm of the path; a retraced segment "
            f"is drawn once).</span></p>")


def _script_json(doc: object) -> str:
    return json.dumps(doc, separators=(",", ":")).replace("</", "<\\/")


def render_html(rep: TimingReport, cmds: Sequence[Command]) -> str:
    import numpy as np

    p = rep.primary
    gap = ""
    if rep.nominal not in (None, 0):
        nom = rep.columns[rep.nominal or 0]
        if nom.total_ns:
            gap = (f"<p>Planned {p.run.label} takes <b>{_s(p.total_ns)} s ({hms(p.total_ns)})</b>; the nominal "
                   f"length/feed estimate says {_s(nom.total_ns)} s ({hms(nom.total_ns)}, "
                   f"{(p.total_ns - nom.total_ns) / nom.total_ns * 100:+.1f}%).</p>")
    more = (f"<p class=note>{len(rep.lines) - MAX_LINES} more lines: see --report-format=json.</p>"
            if len(rep.lines) > MAX_LINES else "")
    op = (f"<p class=note>* operator-dependent (M00, M01, waits): {_s(p.operator_ns)} s assumed from the machine "
          f"model.</p>" if bool(rep.lines.operator_dependent.any()) else "")
    top = rep.top()
    shown = rep.lines[:MAX_LINES]
    data = page_data(rep, cmds, [r.index for r in top] + [r.index for r in shown])
    data["colors"] = {"limit": LIMIT_COLORS, "category": CATEGORY_COLORS, "tools": list(TOOL_COLORS),
                      "rapid": RAPID_COLOR, "hole": HOLE_COLOR, "selected": SELECTED_COLOR}
    sp = np.concatenate([np.frombuffer(base64.b64decode(data["speed"][k]), dtype=np.int8) for k in ("limit", "top")])
    used = [name for k, name in enumerate(data["limits"]) if (sp == k).any()]
    seen = {b[2] for b in data["bands"]}
    items = [("sw", LIMIT_COLORS[u], f"limited by {u.replace('_', ' ')}") for u in used]
    items += [("sw", CATEGORY_COLORS[c], c.replace("_", " ")) for c in CATEGORIES if c in seen]
    if data["nominal"] is not None:
        items.append(("dash", "#222", f"{data['nominal']['label']} (nominal, dashed)"))
    path = data["path"]
    tools = path.get("tools", [])
    drawn = set(np.frombuffer(base64.b64decode(path["tool"]), dtype=np.uint8).tolist()) if path.get(
        "n") else set()
    titems = [("sw", TOOL_COLORS[k % len(TOOL_COLORS)], "no tool" if t < 0 else f"T{t}") for k, t in enumerate(tools)
              if k in drawn]
    titems.append(("dash", RAPID_COLOR, "rapid"))
    if path.get("holes_total"):
        titems.append(("ring", HOLE_COLOR, f"drilled hole ({path['holes_total']})"))
    extents = _extents(path)
    views = "".join(f'<div><h3>{title}</h3><canvas id="view-{k}"></canvas></div>' for k, title in
                    (("iso", "3-D view"), ("xy", "XY (top)"), ("xz", "XZ (front)"), ("yz", "YZ (side)")))
    bands_note = (f"<p class=note>{data['bands_total'] - len(data['bands'])} shorter events are not drawn.</p>"
                  if data["bands_total"] > len(data["bands"]) else "")
    js = resources.files(__package__).joinpath("page.js").read_text(encoding="utf-8")
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>cycle time of {escape(rep.file)}</title>
<style>{_CSS}</style></head><body data-ready="0">
<h1>Cycle time of {escape(rep.file)}
<span class=note>({escape(rep.dialect)}, machine {escape(p.run.machine.name)})</span></h1>
{gap}{_summary(rep)}
<div id=selected></div><div id=tip></div>
<h2>Path speed over time, by limiting constraint</h2>
<p class=note>Wheel: zoom · drag: pan · double-click: whole program · click: select the line. Each pixel column
shows the lowest and highest speed in its time span, in the colour of the constraint that held longest there.</p>
<canvas id=speed></canvas>
<div><button id=speed-reset>whole program</button> <span id=speed-range class=note></span></div>
{_legend(items)}{bands_note}
<h2>Tool path</h2>
{_legend(titems)}
<div class=views>{views}</div>
{extents}
<h2>Tools</h2>{_tools(rep, cmds)}
<p class=note>D and H: the cutter-compensation and tool-length numbers selected while the tool was in the
spindle (both stay selected until changed).</p>
<div>{tool_plot(rep, 900)}</div>
<h2>The {rep.top_n} slowest blocks</h2>{_lines(rep, top, False)}
<h2>Time per line</h2>{op}{_lines(rep, shown, True)}{more}
<script type="application/json" id="cncc-data">{_script_json(data)}</script>
<script>{js}</script>
</body></html>
"""
