"""The data of the interactive HTML page: decimated, bounded in size, JSON with base64 arrays.

Consumes a :class:`TimingReport` and the commands; produces one dict (see
:func:`page_data`) that ``page.js`` draws.  Sizes are bounded whatever the program's
length: at most :data:`MAX_VERTICES` tool-path vertices, :data:`MAX_COLUMNS` speed
columns, :data:`MAX_BANDS` event bands, and the texts of the lines those refer to
(cut to :data:`TEXT_CHARS`).

The trajectory is read only through :mod:`.sampling` and ``Trajectory.sample``.

Tool path: vertices at each command's start and at every phase boundary of arcs and
rapids (lines are straight between their ends); a segment is drawn once even if the
program retraces it (same quantised ends, same tool and kind); then Douglas–Peucker
with a tolerance of 1/3000 of the part's diagonal, keeping every vertex where the
source line changes if the budget allows (so a click on a segment finds its line),
else the tolerance doubled until the budget holds.
Speed: every phase boundary plus one sample per column, reduced per column by
:func:`~.decimate.speed_columns`.
"""

from __future__ import annotations

import base64
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from cncc.backends.timing import sampling
from cncc.backends.timing.decimate import Columns, douglas_peucker, speed_columns
from cncc.backends.timing.events import CATEGORIES
from cncc.backends.timing.model import MOTION_LIMITS, NS_PER_S, Column, TimingReport, to_s
from cncc.ir import Command, Linear, OriginKind

if TYPE_CHECKING:
    import numpy as np
    import numpy.typing as npt

    F64 = npt.NDArray[np.float64]
    I64 = npt.NDArray[np.int64]

MAX_VERTICES = 40_000
MAX_COLUMNS = 16_384
MIN_COLUMNS = 1_024
MAX_BANDS = 4_000
TEXT_CHARS = 80
DP_FRACTION = 1 / 3000
QUANT = 65535
_RAPID = CATEGORIES.index("rapid")
_FEED = CATEGORIES.index("feed")


def b64(arr: Any, dtype: str) -> str:
    """Little-endian bytes of ``arr`` as ``dtype``, base64 (the page decodes them into typed arrays)."""
    import numpy as np

    return base64.b64encode(np.ascontiguousarray(arr, dtype=np.dtype(dtype).newbyteorder("<")).tobytes()).decode()


def event_shift_s(col: Column, n_cmds: int) -> F64:
    """Seconds of events before each command: wall time = trajectory time + this."""
    import numpy as np

    ev = np.zeros(n_cmds + 1, dtype=np.int64)
    for i, ns, *_ in col.event_list:
        ev[i + 1] += ns
    out: F64 = np.cumsum(ev)[:-1] / NS_PER_S
    return out


def event_bands(col: Column) -> list[tuple[float, float, str]]:
    """(wall start s, wall end s, category) of the events with time."""
    import numpy as np

    end = np.cumsum(col.cmd_ns)
    return [(to_s(int(end[i]) - ns), to_s(int(end[i])), cat) for i, ns, cat, _op, _w in col.event_list if ns > 0]


def _wall_to_traj(w: F64, bands: list[tuple[float, float, str]]) -> F64:
    """Trajectory time at wall times ``w`` (inside an event: the trajectory time the event stands at)."""
    import numpy as np

    if not bands:
        return w
    s = np.array([b[0] for b in bands])
    d = np.array([b[1] - b[0] for b in bands])
    before = np.concatenate(([0.0], np.cumsum(d)))
    i = np.searchsorted(s, w, side="right") - 1
    shift = np.where(i >= 0, before[np.maximum(i, 0)] + np.clip(w - s[np.maximum(i, 0)], 0.0, d[np.maximum(i, 0)]), 0.0)
    out: F64 = w - shift
    return out


def speed_series(col: Column, rep: TimingReport, n_cmds: int, edges: F64) -> tuple[dict[str, Any], Columns]:
    """Per-column min/max path speed [mm/min], limit and line of one column over wall-time ``edges``."""
    import numpy as np

    traj = col.run.trajectory
    knots = sampling.knot_times(traj)
    total = to_s(col.total_ns)
    if traj.phase_count == 0 or n_cmds == 0:
        c = speed_columns(np.zeros(0), np.zeros(0), np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64),
                          edges, len(MOTION_LIMITS))
        return _series_doc(col, c, total), c
    shift = event_shift_s(col, n_cmds)
    kc, _ = sampling.at(traj, knots)
    knot_wall = knots + shift[np.clip(kc, 0, n_cmds - 1)]
    bands = event_bands(col)
    inside = edges[edges <= total]
    if bands:  # an edge within an event is no motion sample: the band is drawn there instead
        b0 = np.array([b[0] for b in bands])
        b1 = np.array([b[1] for b in bands])
        k = np.searchsorted(b0, inside, side="right") - 1
        inside = inside[(k < 0) | (inside >= b1[np.maximum(k, 0)])]
    edge_t = np.clip(_wall_to_traj(inside, bands), 0.0, traj.duration_total_s)
    t = np.concatenate((knots, edge_t))
    wall = np.concatenate((knot_wall, inside))
    order = np.argsort(wall, kind="stable")
    t, wall = t[order], wall[order]
    _, v, _, _ = traj.sample(t)
    speed = np.linalg.norm(v[:, :3], axis=1) * 60.0
    cmd, lim = sampling.at(traj, t)
    line = rep.index.cmd_line[np.clip(cmd, 0, n_cmds - 1)]
    edge_v = np.full(len(edges), np.nan)
    edge_v[np.searchsorted(edges, inside)] = np.linalg.norm(traj.sample(edge_t)[1][:, :3], axis=1) * 60.0
    c = speed_columns(wall, speed, lim, line, edges, len(MOTION_LIMITS), edge_v)
    return _series_doc(col, c, total), c


def _series_doc(col: Column, c: Columns, total: float) -> dict[str, Any]:
    import numpy as np

    vmax = float(np.nanmax(c.vmax)) if np.isfinite(c.vmax).any() else 0.0
    return {"label": col.run.label, "vmin": b64(np.nan_to_num(c.vmin, nan=-1.0), "f4"),
            "vmax": b64(np.nan_to_num(c.vmax, nan=-1.0), "f4"), "limit": b64(c.limit, "i1"),
            "top": b64(c.top_limit, "i1"), "vlimit": b64(np.nan_to_num(c.vlimit, nan=-1.0), "f4"),
            "line": b64(c.line, "i4"), "max": vmax, "end_s": total}


def _quantise(p: F64, lo: F64, span: F64) -> Any:
    import numpy as np

    return np.rint((p - lo) / span * QUANT).astype(np.uint16)


def tool_path(rep: TimingReport, cmds: Sequence[Command]) -> tuple[dict[str, Any], I64]:
    """The decimated tool path of the primary column, its extents and lengths; the line of each vertex."""
    import numpy as np

    traj = rep.primary.run.trajectory
    idx = rep.index
    n_cmds = len(cmds)
    if traj.phase_count == 0 or n_cmds == 0:
        return {"n": 0}, np.zeros(0, dtype=np.int64)
    starts, _ = sampling.command_starts(traj)
    knots = sampling.knot_times(traj)
    kc, _ = sampling.at(traj, knots)
    curved = knots[idx.cmd_cat[np.clip(kc, 0, n_cmds - 1)] != _FEED]
    t = np.unique(np.concatenate((starts, curved, sampling.curve_times(traj), knots[-1:])))
    pos = traj.sample(t)[0][:, :3]
    cmd, _ = sampling.at(traj, t)
    cmd = np.clip(cmd, 0, n_cmds - 1)
    rapid = idx.cmd_cat[cmd] == _RAPID
    tools_used = sorted({int(x) for x in np.unique(idx.cmd_tool)})
    tool = np.searchsorted(np.asarray(tools_used), idx.cmd_tool[cmd])
    line = idx.cmd_line[cmd]
    seg = np.linalg.norm(np.diff(pos, axis=0), axis=1)
    rapid_mm = float(seg[rapid[:-1]].sum())
    feed_mm = float(seg[~rapid[:-1]].sum())
    lo, hi = pos.min(axis=0), pos.max(axis=0)
    span = np.maximum(hi - lo, 1e-6)
    # a segment drawn once: same quantised ends (either way round), same kind and tool
    q = _quantise(pos, lo, span).astype(np.int64)
    key_a = (q[:-1, 0] << 32) | (q[:-1, 1] << 16) | q[:-1, 2]
    key_b = (q[1:, 0] << 32) | (q[1:, 1] << 16) | q[1:, 2]
    kind = (rapid[:-1].astype(np.int64) << 8) | tool[:-1]
    keys = np.stack((np.minimum(key_a, key_b), np.maximum(key_a, key_b), kind), axis=1)
    _, first = np.unique(keys, axis=0, return_index=True)
    draw = np.zeros(len(t), dtype=bool)
    draw[first] = True
    draw[:-1] &= key_a != key_b
    draw[-1] = False
    used = draw.copy()
    used[1:] |= draw[:-1]
    sel = np.flatnonzero(used)
    pos, rapid, tool, line, draw = pos[sel], rapid[sel], tool[sel], line[sel], draw[sel]
    draw[:-1] &= np.diff(sel) == 1  # a removed vertex in between: pen up
    if len(sel):
        draw[-1] = False
    keep = np.zeros(len(sel), dtype=bool)
    if len(sel):
        keep[1:] |= (rapid[1:] != rapid[:-1]) | (tool[1:] != tool[:-1]) | ~draw[:-1]
        keep |= ~draw
    diag = float(np.linalg.norm(span))
    tol = diag * DP_FRACTION
    lines_kept = keep.copy()  # a vertex where the line changes, so a click finds the right line ...
    lines_kept[1:] |= line[1:] != line[:-1]
    mask = douglas_peucker(pos, tol, lines_kept)
    if mask.sum() > MAX_VERTICES:  # ... while the budget allows it
        mask = douglas_peucker(pos, tol, keep)
    while mask.sum() > MAX_VERTICES and tol < diag:
        tol *= 2
        mask = douglas_peucker(pos, tol, keep)
    v = np.flatnonzero(mask)
    qv = _quantise(pos[v], lo, span)
    flags = draw[v].astype(np.uint8) | (rapid[v].astype(np.uint8) << 1)
    holes = drill_holes(cmds)
    return {"n": len(v), "lo": lo.tolist(), "hi": hi.tolist(), "q": b64(qv, "u2"), "flags": b64(flags, "u1"),
            "tool": b64(tool[v], "u1"), "line": b64(line[v], "i4"), "tools": tools_used,
            "feed_mm": feed_mm, "rapid_mm": rapid_mm, "tol_mm": tol, "vertices_in": len(t),
            "holes": holes[:5000], "holes_total": len(holes)}, line[v]


def drill_holes(cmds: Sequence[Command]) -> list[list[float]]:
    """[x, y, bottom z] of each hole a canned cycle feeds into (pecks of one hole counted once)."""
    out: list[list[float]] = []
    for c in cmds:
        if isinstance(c, Linear) and c.origin.kind is OriginKind.CYCLE:
            s, e = c.start, c.end
            if abs(s[0] - e[0]) < 1e-9 and abs(s[1] - e[1]) < 1e-9 and e[2] < s[2]:
                if out and abs(out[-1][0] - e[0]) < 1e-9 and abs(out[-1][1] - e[1]) < 1e-9:
                    out[-1][2] = min(out[-1][2], e[2])
                else:
                    out.append([e[0], e[1], e[2]])
    return out


def tool_table(rep: TimingReport, cmds: Sequence[Command]) -> list[dict[str, Any]]:
    """Per tool: the D and H numbers in force in its motions and its time in every column.

    Only motions count: a tool change leaves the previous tool's H in force until the
    program's next G43, and the blocks in between (spindle, modes) do not use it."""
    d_used: dict[int, set[int]] = {}
    h_used: dict[int, set[int]] = {}
    tools = rep.index.cmd_tool.tolist()
    last_frame = None
    for c, t in zip(cmds, tools, strict=True):
        frame = getattr(c, "frame", None)
        if frame is None or frame is last_frame or not (hasattr(c, "end") or hasattr(c, "holes")):
            continue
        last_frame = frame
        if frame.comp_index:  # the D in force (cutter-comp has applied the radius: the side is off by now)
            d_used.setdefault(t, set()).add(frame.comp_index)
        if frame.tool_length_index:
            h_used.setdefault(t, set()).add(frame.tool_length_index)
    out = []
    for t in sorted({k for c in rep.columns for k, v in c.tool_ns.items() if any(v.values())}):
        out.append({"tool": t, "d": sorted(d_used.get(t, ())), "h": sorted(h_used.get(t, ())),
                    "times_ns": [sum(c.tool_ns.get(t, {}).values()) for c in rep.columns],
                    "by_category_ns": {k: v for k, v in rep.primary.tool_ns.get(t, {}).items() if v}})
    return out


def page_data(rep: TimingReport, cmds: Sequence[Command], table_rows: Sequence[int]) -> dict[str, Any]:
    """Everything the page's script draws; ``table_rows``: the line indices the page's tables list."""
    import numpy as np

    n_cmds = len(cmds)
    p = rep.primary
    nominal = rep.columns[rep.nominal] if rep.nominal not in (None, 0) else None
    end = max(to_s(p.total_ns), to_s(nominal.total_ns) if nominal is not None else 0.0, 1e-6)
    n_cols = int(np.clip(4 * (p.run.trajectory.phase_count + 1), MIN_COLUMNS, MAX_COLUMNS))
    edges = np.linspace(0.0, end, n_cols + 1)
    speed, cols = speed_series(p, rep, n_cmds, edges)
    nom = speed_series(nominal, rep, n_cmds, edges)[0] if nominal is not None else None
    bands = event_bands(p)
    if len(bands) > MAX_BANDS:
        bands = sorted(sorted(bands, key=lambda b: b[0] - b[1])[:MAX_BANDS])
    path, path_lines = tool_path(rep, cmds)
    need = set(np.unique(cols.line[cols.line >= 0]).tolist()) | set(table_rows)
    if len(path_lines):
        need |= set(np.unique(path_lines).tolist())
    rows = [rep.lines[i] for i in sorted(need) if 0 <= i < len(rep.lines)]
    texts: dict[str, int] = {}
    files: dict[str, int] = {}
    text_of = [texts.setdefault(r.text[:TEXT_CHARS], len(texts)) for r in rows]
    file_of = [files.setdefault(r.file, len(files)) for r in rows]
    return {
        "file": rep.file, "total_s": to_s(p.total_ns), "end_s": end, "columns": n_cols,
        "limits": list(MOTION_LIMITS), "speed": speed, "nominal": nom,
        "bands": [[round(a, 6), round(b, 6), c] for a, b, c in bands], "bands_total": len(event_bands(p)),
        "path": path,
        "lines": {"i": [r.index for r in rows], "line": [r.line for r in rows], "n": [r.n for r in rows],
                  "t": text_of, "f": file_of, "texts": list(texts), "files": list(files)},
    }
