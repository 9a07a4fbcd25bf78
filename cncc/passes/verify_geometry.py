"""Distances from points to the programmed path, for ``verify`` (no planner code).

:func:`distance_to_commands` takes points ``(n, 6)`` and, per point, the index of the
responsible command; it returns the distance to the nearest of that command and its
previous and next motion commands (a blended corner lies between two commands).
Lines and rapids: distance to the segment.  Arcs and helices: for a point whose angle
about the centre lies within the swept angle (``turns`` per the IR: + counter-clockwise
in the plane's first/second axes, ``|turns| > 1`` whole extra turns, start = end a full
circle), the in-plane radial error (to the radius band between start and end radius)
combined with the distance of the other coordinates to the band between their start and
end values; outside the sweep, the distance to the nearer end point.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from cncc.ir.commands import Arc, Command, Linear, Rapid
from cncc.ir.trajectory import FloatArray


def _tables(cmds: Sequence[Command]) -> dict[str, np.ndarray]:
    n = len(cmds)
    start, end, center = np.zeros((n, 6)), np.zeros((n, 6)), np.zeros((n, 6))
    is_arc = np.zeros(n, bool)
    plane = np.zeros((n, 3), np.int64)
    turns = np.zeros(n, np.int64)
    for i, c in enumerate(cmds):
        if isinstance(c, Rapid | Linear | Arc):
            start[i], end[i] = c.start, c.end
            if isinstance(c, Arc):
                is_arc[i] = True
                center[i] = c.center
                plane[i] = c.plane.value
                turns[i] = c.turns
    return {"start": start, "end": end, "center": center, "arc": is_arc, "plane": plane, "turns": turns}


def _neighbours(motion: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    n = motion.size
    idx = np.where(motion, np.arange(n), -1)
    last = np.maximum.accumulate(idx)
    prev = np.concatenate([[-1], last[:-1]])
    idx_r = np.where(motion, np.arange(n), n)
    nxt_all = np.minimum.accumulate(idx_r[::-1])[::-1]
    nxt = np.concatenate([nxt_all[1:], [n]])
    return prev, np.where(nxt >= n, -1, nxt)


def _line_dist(p: FloatArray, a: FloatArray, b: FloatArray) -> FloatArray:
    ab = b - a
    den = np.einsum("ij,ij->i", ab, ab)
    t = np.where(den > 0, np.einsum("ij,ij->i", p - a, ab) / np.maximum(den, 1e-300), 0.0)
    t = np.clip(t, 0.0, 1.0)
    out: FloatArray = np.linalg.norm(p - (a + ab * t[:, None]), axis=1)
    return out


def _band(x: FloatArray, a: FloatArray, b: FloatArray) -> FloatArray:
    out: FloatArray = np.maximum(np.maximum(np.minimum(a, b) - x, x - np.maximum(a, b)), 0.0)
    return out


def _arc_dist(p: FloatArray, tab: dict[str, np.ndarray], c: np.ndarray) -> FloatArray:
    pl = tab["plane"][c]
    rows = np.arange(p.shape[0])
    f, s = pl[:, 0], pl[:, 1]
    st, en, ce = tab["start"][c], tab["end"][c], tab["center"][c]
    rho = np.hypot(p[rows, f] - ce[rows, f], p[rows, s] - ce[rows, s])
    r0 = np.hypot(st[rows, f] - ce[rows, f], st[rows, s] - ce[rows, s])
    r1 = np.hypot(en[rows, f] - ce[rows, f], en[rows, s] - ce[rows, s])
    radial = _band(rho, r0, r1)
    other = _band(p, st, en)
    other[rows, f] = 0.0
    other[rows, s] = 0.0
    on_arc = np.hypot(radial, np.linalg.norm(other, axis=1))
    inside = _within_sweep(p, st, en, ce, f, s, tab["turns"][c], np.maximum(np.maximum(r0, r1), 1e-12))
    ends = np.minimum(np.linalg.norm(p - st, axis=1), np.linalg.norm(p - en, axis=1))
    out: FloatArray = np.where(inside, on_arc, ends)
    return out


def _within_sweep(p: FloatArray, st: FloatArray, en: FloatArray, ce: FloatArray, f: np.ndarray, s: np.ndarray,
                  turns: np.ndarray, radius: FloatArray) -> np.ndarray:
    """Whether each point's angle about the centre lies in the arc's swept angle (with
    an angular slack of 1 um along the arc)."""
    rows = np.arange(p.shape[0])
    two_pi = 2 * np.pi

    def angle(q: FloatArray) -> FloatArray:
        out: FloatArray = np.arctan2(q[rows, s] - ce[rows, s], q[rows, f] - ce[rows, f])
        return out

    a_start, a_end, a_p = angle(st), angle(en), angle(p)
    ccw = turns >= 0
    span = np.where(ccw, (a_end - a_start) % two_pi, (a_start - a_end) % two_pi)
    span = np.where(span < 1e-9, two_pi, span) + two_pi * (np.maximum(np.abs(turns), 1) - 1)
    offset = np.where(ccw, (a_p - a_start) % two_pi, (a_start - a_p) % two_pi)
    slack = 1e-3 / radius
    inside: np.ndarray = (span >= two_pi - 1e-12) | (offset <= span + slack) | (offset >= two_pi - slack)
    return inside


def distance_to_commands(points: FloatArray, ci: np.ndarray, cmds: Sequence[Command], motion: np.ndarray
                         ) -> FloatArray:
    if not len(cmds):
        return np.zeros(points.shape[0])
    tab = _tables(cmds)
    prev, nxt = _neighbours(motion)
    best = np.full(points.shape[0], np.inf)
    for cand in (ci, prev[ci], nxt[ci]):
        ok = cand >= 0
        c = np.where(ok, cand, 0)
        arc = tab["arc"][c]
        d = _line_dist(points, tab["start"][c], tab["end"][c])
        if arc.any():
            d = np.where(arc, _arc_dist(points, tab, c), d)
        best = np.where(ok, np.minimum(best, d), best)
    return best
