"""The three plots of the HTML report, as SVG text.

* :func:`feed_plot`: path speed over wall-clock time, coloured by the limiting
  constraint of each phase, events (dwells, tool changes ...) as shaded bands, the
  nominal speed as a dashed line;
* :func:`path_plot`: the tool path in the XY plane coloured by speed, rapids dashed;
* :func:`tool_plot`: time per tool, stacked by category, one bar per column.

Consumes a :class:`TimingReport` (its columns' Trajectories).  Large trajectories
are sampled down to a few thousand points so the page stays small.
"""

from __future__ import annotations

from html import escape
from typing import Any

from cncc.backends.timing.events import CATEGORIES
from cncc.backends.timing.model import MOTION_LIMITS, NS_PER_S, Column, TimingReport, to_s
from cncc.backends.timing.svg import CATEGORY_COLORS, LIMIT_COLORS, SPEED_COLORS, Frame, legend, svg

MAX_PHASES_DRAWN = 3000
SAMPLES = 6000


def _event_shift_s(col: Column, n_cmds: int) -> Any:
    """Seconds of events before each command: wall time = trajectory time + this."""
    import numpy as np

    ev = np.zeros(n_cmds + 1, dtype=np.int64)
    for i, ns, *_ in col.event_list:
        ev[i + 1] += ns
    return np.cumsum(ev)[:-1] / NS_PER_S


def speed_samples(col: Column, n_cmds: int) -> tuple[Any, Any, Any]:
    """(wall time s, path speed mm/min, limit index) samples of a column's trajectory."""
    import numpy as np

    traj = col.run.trajectory
    n = traj.phase_count
    if n == 0:
        return np.zeros(0), np.zeros(0), np.zeros(0, dtype=np.int64)
    if n <= MAX_PHASES_DRAWN:
        frac = np.array([0.0, 0.5, 1.0 - 1e-9])
        t = (traj.t0_s[:, None] + traj.duration_s[:, None] * frac).ravel()
    else:
        t = np.linspace(0.0, traj.duration_total_s * (1 - 1e-12), SAMPLES)
    k = np.clip(np.searchsorted(traj.t0_s, t, side="right") - 1, 0, n - 1)
    _, v, _, _ = traj.sample(t)
    speed = np.linalg.norm(v[:, :3], axis=1) * 60.0
    wall = t + _event_shift_s(col, n_cmds)[traj.cmd_index[k]]
    return wall, speed, traj.limit[k].astype(np.int64)


def _events(rep: TimingReport, col: Column) -> list[tuple[float, float, str]]:
    import numpy as np

    end = np.cumsum(col.cmd_ns)
    return [(to_s(int(end[i]) - ns), to_s(int(end[i])), cat) for i, ns, cat, _op, _w in col.event_list if ns > 0]


def feed_plot(rep: TimingReport, n_cmds: int, width: int = 900, height: int = 300) -> str:
    col = rep.primary
    wall, speed, lim = speed_samples(col, n_cmds)
    nominal = rep.columns[rep.nominal] if rep.nominal not in (None, 0) else None
    top = float(speed.max()) if len(speed) else 1.0
    if nominal is not None:
        _nw, nsp, _ = speed_samples(nominal, n_cmds)
        top = max(top, float(nsp.max()) if len(nsp) else 0.0)
    f = Frame(width - 150, height, 0.0, max(to_s(col.total_ns), 1e-6), 0.0, top * 1.05 or 1.0)
    body = [f.axes("time [s]", "path speed [mm/min]")]
    for t0, t1, cat in _events(rep, col):
        body.append(f'<rect x="{f.px(t0):.1f}" y="{f.top}" width="{max(f.px(t1) - f.px(t0), 0.5):.1f}" '
                    f'height="{f.height - f.top - f.bottom}" fill="{CATEGORY_COLORS[cat]}" opacity="0.18">'
                    f'<title>{cat.replace("_", " ")} {t1 - t0:.3f} s</title></rect>')
    if nominal is not None:
        nw, nsp, _ = speed_samples(nominal, n_cmds)
        pts = " ".join(f"{f.px(x):.1f},{f.py(y):.1f}" for x, y in zip(nw, nsp, strict=True))
        body.append(f'<polyline points="{pts}" fill="none" stroke="#444" stroke-dasharray="4 3" '
                    f'stroke-width="1"><title>{escape(nominal.run.label)}</title></polyline>')
    used: list[str] = []
    start = 0
    for k in range(1, len(wall) + 1):
        if k == len(wall) or lim[k] != lim[start]:
            name = MOTION_LIMITS[int(lim[start])] if 0 <= lim[start] < len(MOTION_LIMITS) else "none"
            seg = range(max(start - 1, 0), k)
            pts = " ".join(f"{f.px(wall[j]):.1f},{f.py(speed[j]):.1f}" for j in seg)
            body.append(f'<polyline points="{pts}" fill="none" stroke="{LIMIT_COLORS[name]}" stroke-width="2"/>')
            if name not in used:
                used.append(name)
            start = k
    items = [(f"limited by {u.replace('_', ' ')}", LIMIT_COLORS[u]) for u in used]
    seen = {e[2] for e in _events(rep, col)}
    items += [(c.replace("_", " "), CATEGORY_COLORS[c]) for c in CATEGORIES if c in seen]
    if nominal is not None:
        items.append((f"{nominal.run.label} (dashed)", "#444"))
    body.append(legend(items, width - 140, 24))
    return svg(width, height, "".join(body), "path speed over time, coloured by the limiting constraint")


def _path_segments(col: Column, rep: TimingReport) -> tuple[Any, Any, Any, Any]:
    """(start xy, end xy, speed mm/min, is-rapid) per drawn segment."""
    import numpy as np

    traj = col.run.trajectory
    n = traj.phase_count
    step = max(1, -(-n // MAX_PHASES_DRAWN))
    idx = np.arange(0, n, step)
    p0 = traj.p0_mm[idx, :2]
    last = np.minimum(idx + step - 1, n - 1)
    ends = np.array([traj.end_state(int(k))[0][:2] for k in last]) if len(idx) else np.zeros((0, 2))
    t_mid = traj.t0_s[idx] + (traj.t0_s[last] + traj.duration_s[last] - traj.t0_s[idx]) / 2
    _, v, _, _ = traj.sample(t_mid) if len(idx) else (None, np.zeros((0, 3)), None, None)
    speed = np.linalg.norm(v[:, :3], axis=1) * 60.0
    rapid = rep.index.cmd_cat[traj.cmd_index[idx]] == CATEGORIES.index("rapid")
    return p0, ends, speed, rapid


def path_plot(rep: TimingReport, width: int = 480, height: int = 420) -> str:
    p0, p1, speed, rapid = _path_segments(rep.primary, rep)
    if len(p0):
        xs = [float(p0[:, 0].min()), float(p1[:, 0].min()), float(p0[:, 0].max()), float(p1[:, 0].max())]
        ys = [float(p0[:, 1].min()), float(p1[:, 1].min()), float(p0[:, 1].max()), float(p1[:, 1].max())]
    else:
        xs, ys = [0.0, 1.0], [0.0, 1.0]
    span = max(max(xs) - min(xs), max(ys) - min(ys), 1e-3) * 1.08
    cx, cy = (max(xs) + min(xs)) / 2, (max(ys) + min(ys)) / 2
    f = Frame(height, height, cx - span / 2, cx + span / 2, cy - span / 2, cy + span / 2, left=56, right=16,
              top=16, bottom=40)
    body = [f.axes("X [mm]", "Y [mm]")]
    top = float(speed[~rapid].max()) if (~rapid).any() else 1.0
    paths: dict[int, list[str]] = {}
    dashed: list[str] = []
    for a, b, s, r in zip(p0, p1, speed, rapid, strict=True):
        seg = f"M{f.px(a[0]):.1f} {f.py(a[1]):.1f}L{f.px(b[0]):.1f} {f.py(b[1]):.1f}"
        if r:
            dashed.append(seg)
        else:
            paths.setdefault(min(int(s / top * len(SPEED_COLORS)), len(SPEED_COLORS) - 1), []).append(seg)
    if dashed:
        body.append(f'<path d="{"".join(dashed)}" stroke="#999" stroke-dasharray="3 3" fill="none"/>')
    for b, segs in sorted(paths.items()):
        body.append(f'<path d="{"".join(segs)}" stroke="{SPEED_COLORS[b]}" stroke-width="2" fill="none" '
                    f'stroke-linecap="round"/>')
    n = len(SPEED_COLORS)
    items = [(f"≤ {top * (k + 1) / n:.0f} mm/min", SPEED_COLORS[k]) for k in range(n)] + [("rapid", "#999")]
    body.append(legend(items, height + 8, 24))
    return svg(height + 130, height, "".join(body), "tool path in XY coloured by speed")


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
