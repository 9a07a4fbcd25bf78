"""-O2 corner rounding on exact geometry: one blend arc per corner, lines and arcs alike.

Consumes a native :class:`PathRun` (``run.geo`` set: arcs are single pieces with their
:class:`~cncc.ir.trajectory.Geometry`); produces the run with every corner that may
blend replaced by one circular **blend arc** (itself a native arc piece, in the plane of
the corner), and the neighbouring pieces trimmed to its ends.

Per corner ``v`` between pieces ``v - 1`` (tangent ``t_in`` at its end) and ``v``
(``t_out`` at its start), deflection ``theta``:

1. the tangent distance ``d = tol tan(theta/2) / (sec(theta/2) - 1)`` (the blend of two
   lines that deviates ``tol`` from the corner), at most half of either piece and, next
   to an arc of radius ``r``, at most ``sqrt(2 ARC_SHARE tol r)`` (where the arc leaves its
   tangent by ``ARC_SHARE tol``) and a quarter of ``r``;
2. the pieces are trimmed by ``d`` of path length: ``E`` on the incoming piece, ``S`` on
   the outgoing one (exact points of the lines or arcs);
3. the blend is the circle from ``E``, tangent to the incoming piece there, through
   ``S``: chord ``c = S - E`` at angle ``alpha`` to the tangent, sweep ``2 alpha``, radius
   ``|c| / (2 sin alpha)``.  Between two lines it is the symmetric blend, tangent at both
   ends.  Next to an arc (and where a sliver joined, below) one circle cannot be tangent
   at both ends: the blend is the equal-leg **biarc** from ``(E, t_E)`` to ``(S, t_S)``,
   two such circles meeting tangentially, so the velocity is continuous (up to the
   non-planarity of a helix's corner).  A sliver of a piece left between two blends (a
   smooth polyline, where both blends want more than half of it) joins the incoming
   blend, so consecutive blends meet with nearly the same curvature.

The blend belongs to the incoming command (verify measures it against the command and
its neighbours).  ``origin`` maps both new points of a rounded corner to its vertex.
"""

from __future__ import annotations

import numpy as np

from cncc.ir.trajectory import FloatArray, Geometry
from cncc.passes.planning.geometry import PathRun

RADIUS_SHARE = 0.25
"""A corner next to an arc of radius ``r`` is trimmed by at most ``RADIUS_SHARE * r``."""

ARC_SHARE = 0.1
"""... and by at most the length over which the arc leaves its tangent by this share of the tolerance."""

SLIVER_SHARE = 0.1
"""A piece left shorter than this share of the incoming blend's tangent length joins that blend."""


def _piece_shapes(run: PathRun) -> tuple[Geometry, FloatArray, FloatArray]:
    """Every piece as a Geometry row (lines too), its length and its curvature radius (inf: line)."""
    pts = run.points
    d = np.diff(pts, axis=0)
    chord = np.linalg.norm(d, axis=1)
    u = d / np.maximum(chord, 1e-300)[:, None]
    lines = Geometry.lines(pts[:-1], u, chord)
    if run.geo is None or run.arcs is None or not (run.geo >= 0).any():
        return lines, chord, np.full(chord.size, np.inf)
    is_arc = run.geo >= 0
    arcs = run.arcs.take(np.maximum(run.geo, 0))
    col = is_arc[:, None]
    geo = Geometry(*(np.where(col if getattr(arcs, f).ndim == 2 else is_arc, getattr(arcs, f), getattr(lines, f))
                     for f in Geometry.__slots__))
    radius = np.where(is_arc, np.minimum(arcs.r0, arcs.r0 + arcs.dr * arcs.length), np.inf)
    return geo, geo.length, radius


def _trimmed(geo: Geometry, start: FloatArray, end: FloatArray) -> Geometry:
    """The rows of ``geo`` restricted to ``s`` in ``[start, length - end]``, re-based at ``s = 0``."""
    k = geo.kappa
    return Geometry(geo.c + geo.w * start[:, None], geo.e1, geo.e2, geo.w, geo.r0 + geo.dr * start, geo.dr,
                    geo.theta0 + k * start, k, geo.length - start - end)


def round_native(run: PathRun, sharp: np.ndarray | None = None) -> PathRun:
    """The run with its corners blended (see the module docstring); ``sharp`` (``(k+1,)``
    bool) marks vertices left as they are (the planner stops or steps there)."""
    k = run.cmd.size
    if k < 2:
        return run
    geo, length, radius = _piece_shapes(run)
    rows = np.arange(k)
    _, t_start, _, _ = geo.derivatives(rows, np.zeros(k))
    _, t_end, _, _ = geo.derivatives(rows, length)
    t_start /= np.maximum(np.linalg.norm(t_start, axis=1), 1e-300)[:, None]
    t_end /= np.maximum(np.linalg.norm(t_end, axis=1), 1e-300)[:, None]
    t_in, t_out = t_end[:-1], t_start[1:]
    cos_t = np.clip(np.einsum("ij,ij->i", t_in, t_out), -1.0, 1.0)
    theta = np.arccos(cos_t)
    tol = run.tol_mm[:-1]
    ok = (theta > 1e-7) & (theta < np.pi - 1e-3) & (tol > 0) & (length[:-1] > 1e-9) & (length[1:] > 1e-9)
    if sharp is not None:
        ok &= ~sharp[1:-1]
    if not ok.any():
        return run
    half = theta / 2
    with np.errstate(divide="ignore", invalid="ignore"):
        d_tol = np.nan_to_num(tol * np.tan(half) / (1.0 / np.cos(half) - 1.0), nan=0.0, posinf=np.inf)
    r_near = np.minimum(radius[:-1], radius[1:])
    d_t = np.minimum.reduce([d_tol, 0.5 * length[:-1], 0.5 * length[1:], RADIUS_SHARE * r_near,
                             np.sqrt(2 * ARC_SHARE * tol * r_near)])
    ok &= d_t > 1e-9
    d_t = np.where(ok, d_t, 0.0)
    v = np.flatnonzero(ok)  # corner index m: vertex m + 1, between pieces m and m + 1
    trim_end = np.zeros(k)
    trim_start = np.zeros(k)
    trim_end[v] = d_t[v]
    trim_start[v + 1] = d_t[v]
    # a sliver of line left between two blends would step the curvature to zero and back:
    # the incoming blend takes it (its end tangent then turns by about sliver / (4 d) more)
    rest = length - trim_start - trim_end
    sliver = (rest > 0) & (rest <= SLIVER_SHARE * trim_end) & (trim_start > 0)
    trim_end = np.where(sliver, trim_end + rest, trim_end)
    d_in = trim_end[v]  # tangent length on the incoming side of each corner
    p_e, tan_e, _, _ = geo.derivatives(v, length[v] - d_in)
    p_s, tan_s, _, _ = geo.derivatives(v + 1, d_t[v])
    tan_e /= np.maximum(np.linalg.norm(tan_e, axis=1), 1e-300)[:, None]
    tan_s /= np.maximum(np.linalg.norm(tan_s, axis=1), 1e-300)[:, None]
    # next to an arc (or after a sliver) one circle cannot be tangent at both ends: a biarc is
    two = np.isfinite(r_near[v]) | sliver[v]
    junction, tan_j = _biarc_junction(p_e[two], tan_e[two], p_s[two], tan_s[two])
    first = _blend_arcs(p_e, tan_e, np.where(two[:, None], _scatter(junction, two, p_s), p_s))
    second = _blend_arcs(junction, tan_j, p_s[two])
    keep = first.length > 1e-9
    keep[two] &= second.length > 1e-9
    if not keep.all():  # degenerate blends: leave those corners sharp
        bad = np.zeros(k + 1, bool)
        bad[v[~keep] + 1] = True
        return round_native(run, bad if sharp is None else (sharp | bad))
    pieces = _trimmed(geo, trim_start, trim_end)
    # blend rows in corner order: the first arc of every corner, the second of a biarc after it
    count = 1 + two.astype(np.int64)
    row_first = np.cumsum(count) - count
    order = np.empty(int(count.sum()), np.int64)
    order[row_first] = np.arange(v.size)
    order[row_first[two] + 1] = v.size + np.arange(int(two.sum()))
    m = run.points.shape[1]
    blend = Geometry.concat([first, second], m).take(order)
    return _assemble(run, pieces, blend, v, count)


def _scatter(rows: FloatArray, mask: np.ndarray, fill: FloatArray) -> FloatArray:
    out = fill.copy()
    out[mask] = rows
    return out


def _biarc_junction(p0: FloatArray, t0: FloatArray, p1: FloatArray, t1: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Junction point and tangent of the equal-leg biarc from ``(p0, t0)`` to ``(p1, t1)``:
    control points ``q0 = p0 + d t0``, ``q1 = p1 - d t1`` with ``|q1 - q0| = 2 d``; the two
    circles meet tangentially at ``(q0 + q1) / 2`` with tangent ``q1 - q0``."""
    vec = p1 - p0
    tt = t0 + t1
    vt = np.einsum("ij,ij->i", vec, tt)
    vv = np.einsum("ij,ij->i", vec, vec)
    c = np.maximum(1.0 - np.einsum("ij,ij->i", t0, t1), 0.0)
    # the positive root of 2 c d^2 + 2 vt d - vv = 0, in the form without cancellation
    d = vv / np.maximum(vt + np.sqrt(vt * vt + 2.0 * c * vv), 1e-300)
    q0 = p0 + d[:, None] * t0
    q1 = p1 - d[:, None] * t1
    tj = q1 - q0
    tj /= np.maximum(np.linalg.norm(tj, axis=1), 1e-300)[:, None]
    return (q0 + q1) / 2, tj


def _blend_arcs(p_e: FloatArray, tan_e: FloatArray, p_s: FloatArray) -> Geometry:
    """Circles from ``p_e`` (tangent ``tan_e``) through ``p_s``, as Geometry rows."""
    c = p_s - p_e
    chord = np.linalg.norm(c, axis=1)
    along = np.einsum("ij,ij->i", c, tan_e)
    side = c - along[:, None] * tan_e
    off = np.linalg.norm(side, axis=1)
    e2g = side / np.maximum(off, 1e-300)[:, None]  # towards the turn
    alpha = np.arctan2(off, along)
    sin_a = np.maximum(np.sin(alpha), 1e-300)
    radius = chord / (2 * sin_a)
    sweep = 2 * alpha
    arc_len = radius * sweep
    centre = p_e + radius[:, None] * e2g
    z = np.zeros(p_e.shape[0])
    return Geometry(centre, -e2g, tan_e.copy(), np.zeros_like(p_e), radius, z, z.copy(),
                    sweep / np.maximum(arc_len, 1e-300), np.where(off > 1e-12, arc_len, 0.0))


def _assemble(run: PathRun, pieces: Geometry, blend: Geometry, v: np.ndarray, count: np.ndarray) -> PathRun:
    """New run: each trimmed piece, then the ``count`` blend arcs of the corner at its end (if any)."""
    k = run.cmd.size
    nblend = np.zeros(k, np.int64)
    nblend[v] = count  # piece m is followed by its corner's blend arcs
    per = 1 + nblend
    first = np.cumsum(per) - per  # new index of each trimmed piece
    n = int(per.sum())
    owner = np.repeat(np.arange(v.size), count)  # corner of each blend row
    sub = np.arange(owner.size) - (np.cumsum(count) - count)[owner]
    slot = first[v][owner] + 1 + sub  # new index of each blend row
    is_blend = np.zeros(n, bool)
    is_blend[slot] = True
    src = np.repeat(np.arange(k), per)  # the original piece (a blend: the incoming one)
    m = run.points.shape[1]
    # Geometry of every new piece: trimmed pieces and blends interleaved
    order = np.empty(n, np.int64)
    order[first] = np.arange(k)
    order[slot] = k + np.arange(owner.size)
    allg = Geometry.concat([pieces, blend], m).take(order)
    starts, _, _, _ = allg.derivatives(np.arange(n), np.zeros(n))
    end, _, _, _ = allg.derivatives(np.array([n - 1]), allg.length[-1:])
    pts = np.vstack([starts, end])
    pts[0] = run.points[0]
    pts[-1] = run.points[-1]
    straight = run.straight[src] & ~is_blend
    geo = np.where(straight, -1, np.arange(n)).astype(np.int64)
    feed = run.feed_mm_s[src].copy()
    nxt = np.minimum(src + 1, k - 1)
    feed[is_blend] = np.minimum(run.feed_mm_s[src], run.feed_mm_s[nxt])[is_blend]
    rapid = run.rapid[src] & ~(is_blend & ~run.rapid[nxt])
    origin_piece = np.where(is_blend, src + 1, src)  # the vertex at each new piece's start
    base = run.origin if run.origin is not None else np.arange(k + 1)
    origin = np.concatenate([base[origin_piece], base[-1:]])
    return PathRun(pts, run.cmd[src], rapid, feed, run.tol_mm[src], np.zeros(n + 1, bool), run.stop_cmd, origin,
                   geo, allg)
