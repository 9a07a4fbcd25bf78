"""Decimation that keeps what a reader looks at.

* :func:`speed_columns`: samples of a speed over time reduced to pixel columns keeping
  each column's minimum and maximum (so no spike is lost and none is invented: every
  value shown is a sampled value of the trajectory), the limit that held for most of
  the column's time (a limit that really held there) with the highest value under it,
  the limit at the maximum, and the line at the maximum.
* :func:`douglas_peucker`: a polyline reduced to the vertices that keep it within a
  distance tolerance (so raster passes stay passes: a chord across two passes would
  leave the path by a whole step-over).  Level-synchronous: every interval is split
  at once per round, a few dozen numpy rounds instead of one Python call per vertex.

Consumes and produces numpy arrays; knows nothing about trajectories.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import numpy as np
    import numpy.typing as npt

    F64 = npt.NDArray[np.float64]
    I64 = npt.NDArray[np.int64]
    B = npt.NDArray[np.bool_]

MAX_ROUNDS = 200
"""Douglas–Peucker rounds before the remaining candidates are all kept (never in practice)."""


@dataclass(frozen=True, slots=True)
class Columns:
    """Per-column reduction of samples over ``edges`` (``c + 1`` ascending boundaries)."""

    edges: F64
    vmin: F64  # (c,) smallest sampled value in the column (NaN: no sample)
    vmax: F64  # (c,) largest sampled value
    limit: I64  # (c,) the limit value with the most time in the column (-1: no sample)
    line: I64  # (c,) the line of the sample at the maximum (-1: no sample)
    top_limit: I64  # (c,) the limit at the sample at the maximum (-1: no sample)
    vlimit: F64  # (c,) the largest sampled value under ``limit`` (NaN: no sample)


def speed_columns(t: F64, v: F64, limit: I64, line: I64, edges: F64, n_limits: int,
                  edge_v: F64 | None = None) -> Columns:
    """Reduce samples ``(t, v, limit, line)`` (``t`` ascending) to the columns between ``edges``.

    ``edge_v``: the values at the ``edges`` themselves (NaN: none), counted in the columns on both
    sides (so neighbouring columns share a value and a steep ramp draws without gaps).
    A sample's time weight is the time to the next sample; a column's limit is the one
    with the most weight among its samples.
    """
    import numpy as np

    c = len(edges) - 1
    vmin = np.full(c, np.nan)
    vmax = np.full(c, np.nan)
    lim = np.full(c, -1, dtype=np.int64)
    ln = np.full(c, -1, dtype=np.int64)
    top = np.full(c, -1, dtype=np.int64)
    vlim = np.full(c, np.nan)
    if len(t) == 0 or c <= 0:
        return Columns(edges, vmin, vmax, lim, ln, top, vlim)
    col = np.clip(np.searchsorted(edges, t, side="right") - 1, 0, c - 1)
    hi = np.full(c, -np.inf)
    lo = np.full(c, np.inf)
    np.maximum.at(hi, col, v)
    np.minimum.at(lo, col, v)
    sampled = np.isfinite(hi)
    at_max = np.flatnonzero(v == hi[col])  # the line and limit at the highest sample
    cols_at_max, first = np.unique(col[at_max], return_index=True)
    ln[cols_at_max] = line[at_max[first]]
    top[cols_at_max] = limit[at_max[first]]
    weight = np.append(np.diff(t), 0.0)
    weight = np.maximum(weight, 1e-12)  # a lone sample still counts
    w2 = np.zeros((c, n_limits))
    np.add.at(w2, (col, np.clip(limit, 0, n_limits - 1)), weight)
    lim[sampled] = w2.argmax(axis=1)[sampled]
    under = np.flatnonzero(np.clip(limit, 0, n_limits - 1) == lim[col])
    hi_lim = np.full(c, -np.inf)
    np.maximum.at(hi_lim, col[under], v[under])
    vlim[np.isfinite(hi_lim)] = hi_lim[np.isfinite(hi_lim)]
    if edge_v is not None and len(edge_v) == c + 1:
        hi = np.fmax(hi, np.fmax(edge_v[:-1], edge_v[1:]))  # fmax/fmin: a NaN edge (no value) is ignored
        lo = np.fmin(lo, np.fmin(edge_v[:-1], edge_v[1:]))
    has = np.isfinite(hi) & sampled
    vmax[has], vmin[has] = hi[has], lo[has]
    return Columns(edges, vmin, vmax, lim, ln, top, vlim)


def _segment_distance(p: F64, a: F64, b: F64) -> F64:
    """Distance of each point ``p[i]`` to the segment ``a[i]``-``b[i]`` (rows of equal shape)."""
    import numpy as np

    ab = b - a
    den = (ab * ab).sum(axis=1)
    u = np.where(den > 0, ((p - a) * ab).sum(axis=1) / np.where(den > 0, den, 1.0), 0.0)
    u = np.clip(u, 0.0, 1.0)
    d = p - (a + ab * u[:, None])
    dist: F64 = np.sqrt((d * d).sum(axis=1))
    return dist


def douglas_peucker(points: F64, tol: float, keep: B) -> B:
    """Mask of the vertices of ``points`` (``(n, d)``) to keep: within ``tol`` of the
    original polyline between kept vertices; ``keep`` (``(n,)``) are kept whatever
    (the first and last vertex always are)."""
    import numpy as np

    n = len(points)
    kept = np.array(keep, dtype=bool, copy=True)
    if n <= 2:
        kept[:] = True
        return kept
    kept[0] = kept[-1] = True
    cand = np.flatnonzero(~kept)
    for _ in range(MAX_ROUNDS):
        if len(cand) == 0:
            return kept
        ks = np.flatnonzero(kept)
        sid = np.searchsorted(ks, cand, side="right") - 1
        a, b = ks[sid], ks[sid + 1]
        dist = _segment_distance(points[cand], points[a], points[b])
        starts = np.concatenate(([0], np.flatnonzero(sid[1:] != sid[:-1]) + 1))
        gmax = np.maximum.reduceat(dist, starts)
        group = np.repeat(np.arange(len(starts)), np.diff(np.append(starts, len(cand))))
        split = gmax > tol
        is_max = (dist == gmax[group]) & split[group]
        g_of_max, first = np.unique(group[is_max], return_index=True)
        kept[cand[np.flatnonzero(is_max)[first]]] = True
        del g_of_max
        cand = cand[split[group] & ~kept[cand]]
    kept[cand] = True
    return kept
