"""Static SVG plots of the timing report (the HTML page's chart of time per tool, the docs' figures).

* :func:`feed_plot`: path speed over wall-clock time, one min/max bar per pixel column
  coloured by the constraint that held longest in it (:mod:`.decimate`), events as
  shaded bands, the nominal speed dashed;
* :func:`path_plot`: the tool path in XY, one colour per tool, rapids dashed, drilled
  holes circled (the page's decimated path, :func:`.pagedata.tool_path`);
* :func:`tool_plot`: time per tool, stacked by category, one bar per column.

Consumes a :class:`TimingReport`; reads trajectories only through :mod:`.pagedata`.
The interactive page draws the first two itself (``page.js``); these are for documents.
"""

from __future__ import annotations

import base64
from collections.abc import Sequence
from html import escape
from typing import Any

from cncc.backends.timing.events import CATEGORIES
from cncc.backends.timing.model import MOTION_LIMITS, TimingReport, to_s
from cncc.backends.timing.pagedata import event_bands, speed_series, tool_path
from cncc.backends.timing.svg import (
    CATEGORY_COLORS,
    HOLE_COLOR,
    LIMIT_COLORS,
    RAPID_COLOR,
    TOOL_COLORS,
    Frame,
    legend,
    svg,
)
from cncc.ir import Command


def _decode(s: str, dtype: str) -> Any:
    import numpy as np

    return np.frombuffer(base64.b64decode(s), dtype=np.dtype(dtype).newbyteorder("<"))


def feed_plot(rep: TimingReport, n_cmds: int, width: int = 900, height: int = 300) -> str:
    import numpy as np

    col = rep.primary
    nominal = rep.columns[rep.nominal] if rep.nominal not in (None, 0) else None
    end = max(to_s(col.total_ns), 1e-6)
    f = Frame(width - 150, height, 0.0, end, 0.0, 1.0)
    px = int(f.width - f.left - f.right)
    edges = np.linspace(0.0, end, px + 1)
    _, c = speed_series(col, rep, n_cmds, edges)
    nc = speed_series(nominal, rep, n_cmds, edges)[1] if nominal is not None else None
    top = max(float(np.nanmax(c.vmax)) if np.isfinite(c.vmax).any() else 0.0,
              float(np.nanmax(nc.vmax)) if nc is not None and np.isfinite(nc.vmax).any() else 0.0)
    f.y1 = top * 1.05 or 1.0
    body = [f.axes("time [s]", "path speed [mm/min]")]
    bands = event_bands(col)
    for t0, t1, cat in bands:
        body.append(f'<rect x="{f.px(t0):.1f}" y="{f.top}" width="{max(f.px(t1) - f.px(t0), 0.5):.1f}" '
                    f'height="{f.height - f.top - f.bottom}" fill="{CATEGORY_COLORS[cat]}" opacity="0.22">'
                    f'<title>{cat.replace("_", " ")} {t1 - t0:.3f} s</title></rect>')
    if nc is not None:
        pts = " ".join(f"{f.px(edges[k]):.1f},{f.py(v):.1f} {f.px(edges[k + 1]):.1f},{f.py(v):.1f}"
                       for k, v in enumerate(nc.vmax) if np.isfinite(v))
        body.append(f'<polyline points="{pts}" fill="none" stroke="#222" stroke-dasharray="5 4" '
                    f'stroke-width="1.2"><title>{escape(nominal.run.label if nominal else "")}</title></polyline>')
    bars: dict[int, list[str]] = {}
    for k in np.flatnonzero(np.isfinite(c.vmax)).tolist():
        y0, y1 = f.py(float(c.vmax[k])), f.py(float(c.vmin[k]))
        if y1 - y0 < 2:
            y0, y1 = y0 - 1, y0 + 1
        x, w = f.px(edges[k]), max(f.px(edges[k + 1]) - f.px(edges[k]), 1.0)
        bars.setdefault(int(c.limit[k]), []).append(f"M{x:.1f} {y0:.1f}h{w:.1f}V{y1:.1f}h{-w:.1f}z")
        if c.top_limit[k] >= 0 and c.top_limit[k] != c.limit[k] and c.vmax[k] > c.vlimit[k]:
            ym = f.py(float(c.vlimit[k]))  # above the speeds under the column's main limit: the peak's limit
            bars.setdefault(int(c.top_limit[k]), []).append(
                f"M{x:.1f} {y0:.1f}h{w:.1f}V{max(ym, y0 + 1):.1f}h{-w:.1f}z")
    for lim, segs in sorted(bars.items()):
        name = MOTION_LIMITS[lim] if 0 <= lim < len(MOTION_LIMITS) else "none"
        body.append(f'<path d="{"".join(segs)}" fill="{LIMIT_COLORS[name]}"/>')
    used = [MOTION_LIMITS[k] for k in sorted(bars) if 0 <= k < len(MOTION_LIMITS)]
    items = [(f"limited by {u.replace('_', ' ')}", LIMIT_COLORS[u]) for u in used]
    seen = {b[2] for b in bands}
    items += [(cat.replace("_", " "), CATEGORY_COLORS[cat]) for cat in CATEGORIES if cat in seen]
    if nominal is not None:
        items.append((f"{nominal.run.label} (dashed)", "#222"))
    body.append(legend(items, width - 140, 24))
    return svg(width, height, "".join(body), "path speed over time, coloured by the limiting constraint")


def path_plot(rep: TimingReport, cmds: Sequence[Command], width: int = 480, height: int = 420) -> str:
    import numpy as np

    path, _ = tool_path(rep, cmds)
    n = path.get("n", 0)
    lo = np.array(path.get("lo", [0.0, 0.0, 0.0]))
    hi = np.array(path.get("hi", [1.0, 1.0, 1.0]))
    span = max(float(hi[0] - lo[0]), float(hi[1] - lo[1]), 1e-3) * 1.08
    cx, cy = (hi[0] + lo[0]) / 2, (hi[1] + lo[1]) / 2
    f = Frame(height, height, cx - span / 2, cx + span / 2, cy - span / 2, cy + span / 2, left=56, right=16,
              top=16, bottom=40)
    body = [f.axes("X [mm]", "Y [mm]")]
    items: list[tuple[str, str]] = []
    if n:
        pos = lo + _decode(path["q"], "u2").reshape(-1, 3) / 65535 * np.maximum(hi - lo, 1e-6)
        flags = _decode(path["flags"], "u1")
        tool = _decode(path["tool"], "u1")
        runs: dict[int, list[str]] = {}
        last_end: dict[int, int] = {}  # per style: the vertex its path ends at
        for i in range(n - 1):
            if not flags[i] & 1:
                continue
            style = -1 if flags[i] & 2 else int(tool[i])
            seg = runs.setdefault(style, [])
            if last_end.get(style) != i:
                seg.append(f"M{f.px(pos[i, 0]):.1f} {f.py(pos[i, 1]):.1f}")
            seg.append(f"L{f.px(pos[i + 1, 0]):.1f} {f.py(pos[i + 1, 1]):.1f}")
            last_end[style] = i + 1
        for style, segs in sorted(runs.items(), reverse=True):
            if style < 0:
                continue
            body.append(f'<path d="{"".join(segs)}" stroke="{TOOL_COLORS[style % len(TOOL_COLORS)]}" '
                        f'stroke-width="1.5" fill="none" stroke-linejoin="round"/>')
            t = path["tools"][style]
            items.append(("no tool" if t < 0 else f"T{t}", TOOL_COLORS[style % len(TOOL_COLORS)]))
        if -1 in runs:
            body.append(f'<path d="{"".join(runs[-1])}" stroke="{RAPID_COLOR}" stroke-dasharray="6 4" '
                        f'stroke-width="1.2" fill="none"/>')
            items.append(("rapid (dashed)", RAPID_COLOR))
        for x, y, _z in path["holes"]:
            body.append(f'<circle cx="{f.px(x):.1f}" cy="{f.py(y):.1f}" r="3" fill="none" stroke="{HOLE_COLOR}"/>')
        if path["holes"]:
            items.append(("drilled hole", HOLE_COLOR))
    body.append(legend(items, height + 8, 24))
    return svg(height + 130, height, "".join(body), "tool path in XY, one colour per tool, rapids dashed")


def tool_plot(rep: TimingReport, width: int = 900) -> str:
    tools = sorted({t for c in rep.columns for t, v in c.tool_ns.items() if any(v.values())})
    rows = [(t, c) for t in tools for c in rep.columns]
    bar_h, gap = 16, 6
    height = max(40 + len(rows) * (bar_h + 2) + len(tools) * gap + 20, 130)
    longest = max((sum(c.tool_ns[t].values()) for t, c in rows), default=1) or 1
    f = Frame(width - 150, height, 0.0, to_s(longest) * 1.05, 0.0, 1.0, left=150, top=10, bottom=36)
    body = [f.axes("time [s]", "", yticks=False)]
    y = f.top + 6.0
    for k, (t, c) in enumerate(rows):
        if k and rows[k - 1][0] != t:
            y += gap
        x = 0.0
        for cat in CATEGORIES:
            dt = to_s(c.tool_ns[t].get(cat, 0))
            if dt > 0:
                body.append(f'<rect x="{f.px(x):.1f}" y="{y:.1f}" width="{f.px(x + dt) - f.px(x):.1f}" '
                            f'height="{bar_h}" fill="{CATEGORY_COLORS[cat]}"><title>{cat.replace("_", " ")} '
                            f'{dt:.3f} s</title></rect>')
                x += dt
        name = ("no tool" if t < 0 else f"T{t}") + f" · {c.run.label}"
        body.append(f'<text x="{f.left - 6}" y="{y + 12:.1f}" text-anchor="end">{escape(name)}</text>'
                    f'<text x="{f.px(x) + 4:.1f}" y="{y + 12:.1f}">{x:.2f} s</text>')
        y += bar_h + 2
    used = [c for c in CATEGORIES if any(col.category_ns[c] for col in rep.columns)]
    body.append(legend([(c.replace("_", " "), CATEGORY_COLORS[c]) for c in used], width - 140, 20))
    return svg(width, height, "".join(body), "time per tool by category")
