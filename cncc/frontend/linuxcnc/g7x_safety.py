"""The safety check of a G70-G72 tool path: no move goes below the profile (into the part).

In the cycle's frame the profile is a function u(w) (it is monotonic along w) and the stock lies
above it.  Every move of the path, rapids included, is sampled along its length; a sample below
the profile (more than :data:`TOLERANCE`) means the path would cut into the finished part, and the
cycle is refused (E0463) rather than run.  rs274 2.9 has no such check.
"""

from __future__ import annotations

import math

from cncc.frontend.linuxcnc.g7x_cut import Move
from cncc.frontend.linuxcnc.g7x_geom import P, Piece, on_arc, sweep

TOLERANCE = 1e-6
SAMPLES = 24


def _profile_u(pieces: list[Piece], w: float) -> float | None:
    """u of the profile at ``w`` (None outside its extent along w)."""
    for p in pieces:
        lo, hi = sorted((p.a[0], p.b[0]))
        if not lo - 1e-12 <= w <= hi + 1e-12:
            continue
        if p.c is None:
            dw = p.b[0] - p.a[0]
            t = 0.5 if abs(dw) < 1e-12 else (w - p.a[0]) / dw
            return p.a[1] + t * (p.b[1] - p.a[1])
        r = p.radius
        h = math.sqrt(max(r * r - (w - p.c[0]) ** 2, 0.0))
        on = [u for u in (p.c[1] + h, p.c[1] - h) if on_arc(p, (w, u))]
        return max(on) if on else min(p.a[1], p.b[1])
    return None


def _arc_point(p: Piece, t: float) -> P:
    assert p.c is not None
    a0 = math.atan2(p.a[1] - p.c[1], p.a[0] - p.c[0]) + t * sweep(p)
    r = p.radius
    return (p.c[0] + r * math.cos(a0), p.c[1] + r * math.sin(a0))


def _samples(at: P, m: Move) -> list[P]:
    if m.kind == "arc" and m.piece is not None and m.piece.c is not None:
        return [_arc_point(m.piece, k / SAMPLES) for k in range(SAMPLES + 1)]
    return [(at[0] + (m.end[0] - at[0]) * k / SAMPLES, at[1] + (m.end[1] - at[1]) * k / SAMPLES)
            for k in range(SAMPLES + 1)]


def first_gouge(profile: list[Piece], start: P, moves: list[Move]) -> tuple[P, str] | None:
    """The first point of the path that lies below the profile, with its move's kind; or None."""
    at = start
    for m in moves:
        for q in _samples(at, m):
            u = _profile_u(profile, q[0])
            if u is not None and q[1] < u - TOLERANCE * max(1.0, abs(u)):
                return q, m.kind
        at = m.end
    return None
