"""-O2 multi-segment smoothing: runs of short moves snapped onto straight lines within tolerance.

Consumes a :class:`PathRun`; produces the same run (same pieces, commands and feeds) whose
interior points of short moves are moved onto the straight line between two anchor
points when every moved point stays within :data:`SHARE` of the blend tolerance.  A CAM
point cloud of 0.01 mm moves zig-zagging by a few micrometres becomes collinear: no
velocity steps at its vertices, one S-curve block instead of a crawl from vertex to
vertex.  The pieces keep their commands, so every point of the trajectory stays within
the moved distance of its own command; the corners left at the anchors are rounded
with the rest of the tolerance (the pieces' ``tol_mm`` is reduced by the share used), so
the total deviation stays within the tolerance.

Anchors: greedy from the start of each stretch of short pieces (shorter than
:data:`SHORT_TOL` blend tolerances, same command kind and feed, not inside an arc), the
farthest end whose intermediate points all lie within the band (doubling, then
bisection; at most :data:`MAX_POINTS` points per line): cost linear in the points.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from cncc.ir.trajectory import FloatArray
from cncc.passes.planning.geometry import PathRun

SHARE = 0.5
"""Share of the blend tolerance the snapping may use (the rest rounds the anchors' corners)."""

SHORT_TOL = 20.0
"""Pieces shorter than this many blend tolerances may be snapped."""

MAX_POINTS = 256


def _fits(pts: FloatArray, a: int, b: int, band: float) -> bool:
    """All points strictly between ``a`` and ``b`` within ``band`` of the segment a-b."""
    if b - a < 2:
        return True
    p, q = pts[a], pts[b]
    d = q - p
    length2 = float(d @ d)
    if length2 <= 1e-24:
        return False
    mid = pts[a + 1:b] - p
    t = np.clip(mid @ d / length2, 0.0, 1.0)
    off = mid - t[:, None] * d
    if not bool(np.all(np.diff(np.concatenate([[0.0], t, [1.0]])) >= 0.0)):
        return False  # the points must keep their order along the line
    return bool(np.einsum("ij,ij->i", off, off).max() <= band * band)


def snap_short_moves(run: PathRun) -> PathRun:
    """The run with its short-move stretches snapped onto lines (see the module docstring)."""
    pts = run.points
    k = run.cmd.size
    if k < 2:
        return run
    length = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    tol = run.tol_mm
    short = (length < SHORT_TOL * tol) & (tol > 0) & ~run.rapid & run.straight
    # point i (1..k-1) may move when both its pieces are short, alike and not inside an arc
    movable = np.zeros(k + 1, bool)
    movable[1:-1] = (short[:-1] & short[1:] & (run.feed_mm_s[:-1] == run.feed_mm_s[1:])
                     & (tol[:-1] == tol[1:]) & ~run.arc_vertex[1:-1])
    if not movable.any():
        return run
    new = pts.copy()
    used = np.zeros(k, bool)  # pieces whose points moved
    band_of = SHARE * tol
    i = 0
    mov = movable.tolist()
    while i < k:
        if not mov[i + 1]:
            i += 1
            continue
        band = float(band_of[i])
        # farthest b > i with points i+1..b-1 movable and within the band
        limit = i + 1
        while limit < k and mov[limit] and limit - i < MAX_POINTS:
            limit += 1
        good, step = i + 1, 1
        while good + step <= limit and _fits(pts, i, good + step, band):
            good += step
            step *= 2
        lo, hi = good, min(good + step, limit + 1)
        while hi - lo > 1:
            mid = (lo + hi) // 2
            if _fits(pts, i, mid, band):
                lo = mid
            else:
                hi = mid
        b = lo
        if b - i >= 2:
            p, q = pts[i], pts[b]
            d = q - p
            t = (pts[i + 1:b] - p) @ d / float(d @ d)
            new[i + 1:b] = p + t[:, None] * d
            used[i:b] = True
        i = b
    if not used.any():
        return run
    return replace(run, points=new, tol_mm=np.where(used, tol * (1 - SHARE), tol))
