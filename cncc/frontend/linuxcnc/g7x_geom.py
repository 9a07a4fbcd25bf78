"""Plane geometry of the G70-G72 profile: line and arc pieces, their offset, crossings, fillets.

Written from LinuxCNC's G-code manual (G70, G71/G72) and black-box runs of rs274 2.9 only.
Points are ``(w, u)`` pairs in the cycle's own frame (:mod:`cncc.frontend.linuxcnc.g7x_frame`):
the cut travels towards -w, the start point (the stock) lies towards +u.  ``ccw`` is the
arc's sense in that frame (w the first axis).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

P = tuple[float, float]
EPS = 1e-9
# An outside corner whose moved ends lie less than this apart along w (program units) is not rounded:
# the moved pieces are extended to where they meet (rs274 2.9, black-box: the threshold is the same in
# G20 and G21 and for every corner angle tried, 10-150 degrees).
ROUND_MIN_W = 0.01


@dataclass(frozen=True, slots=True)
class Piece:
    a: P
    b: P
    c: P | None = None  # arc centre (None: a line)
    ccw: bool = False

    @property
    def radius(self) -> float:
        assert self.c is not None
        return math.dist(self.a, self.c)


def _sub(p: P, q: P) -> P:
    return (p[0] - q[0], p[1] - q[1])


def _unit(v: P) -> P:
    n = math.hypot(v[0], v[1])
    return (0.0, 0.0) if n < EPS else (v[0] / n, v[1] / n)


def cross(a: P, b: P) -> float:
    return a[0] * b[1] - a[1] * b[0]


_cross = cross


def tangent(p: Piece, at_end: bool) -> P:
    """Unit direction of travel at the start (or end) of the piece."""
    if p.c is None:
        return _unit(_sub(p.b, p.a))
    r = _sub(p.b if at_end else p.a, p.c)
    return _unit((-r[1], r[0]) if p.ccw else (r[1], -r[0]))


def _angle(p: Piece, q: P) -> float:
    assert p.c is not None
    return math.atan2(q[1] - p.c[1], q[0] - p.c[0])


def sweep(p: Piece) -> float:
    """The arc's signed sweep in radians (ccw positive), in (0, 2 pi]."""
    d = _angle(p, p.b) - _angle(p, p.a)
    if p.ccw:
        while d <= EPS:
            d += 2 * math.pi
    else:
        while d >= -EPS:
            d -= 2 * math.pi
    return d


def on_arc(p: Piece, q: P) -> bool:
    d = _angle(p, q) - _angle(p, p.a)
    s = sweep(p)
    if p.ccw:
        d %= 2 * math.pi
        return d <= s + 1e-12
    d = -((-d) % (2 * math.pi))
    return d >= s - 1e-12


def split_extrema(p: Piece) -> list[Piece]:
    """An arc cut where u turns (its top or bottom inside the arc); a line as it is."""
    if p.c is None:
        return [p]
    r = p.radius
    cuts = [q for q in ((p.c[0], p.c[1] + r), (p.c[0], p.c[1] - r))
            if math.dist(q, p.a) > 1e-7 and math.dist(q, p.b) > 1e-7 and on_arc(p, q)]
    cuts.sort(key=lambda q: abs(_angle_from(p, q)))
    out, start = [], p.a
    for q in cuts:
        out.append(Piece(start, q, p.c, p.ccw))
        start = q
    out.append(Piece(start, p.b, p.c, p.ccw))
    return out


def _angle_from(p: Piece, q: P) -> float:
    d = _angle(p, q) - _angle(p, p.a)
    return d % (2 * math.pi) if p.ccw else (-d) % (2 * math.pi)


def at_u(p: Piece, level: float) -> P | None:
    """The point of a u-monotonic piece at height ``level`` (None if it does not reach it)."""
    lo, hi = sorted((p.a[1], p.b[1]))
    if level < lo - EPS or level > hi + EPS:
        return None
    if p.c is None:
        du = p.b[1] - p.a[1]
        t = 0.0 if abs(du) < EPS else (level - p.a[1]) / du
        return (p.a[0] + t * (p.b[0] - p.a[0]), level)
    r = p.radius
    dw = math.sqrt(max(r * r - (level - p.c[1]) ** 2, 0.0))
    cands = [(p.c[0] + dw, level), (p.c[0] - dw, level)]
    mid = ((p.a[0] + p.b[0]) / 2, 0.0)
    good = [q for q in cands if on_arc(p, q) or min(math.dist(q, p.a), math.dist(q, p.b)) < 1e-7]
    return min(good or cands, key=lambda q: abs(q[0] - mid[0]))


def cut_piece(p: Piece, start: P | None = None, end: P | None = None) -> Piece:
    return Piece(start or p.a, end or p.b, p.c, p.ccw)


# ---- offset ---------------------------------------------------------------------------------------
def _shift(p: Piece, d: float) -> Piece:
    """The piece moved ``d`` to the right of its travel."""
    if p.c is None:
        t = tangent(p, False)
        n = (t[1], -t[0])
        return Piece((p.a[0] + d * n[0], p.a[1] + d * n[1]), (p.b[0] + d * n[0], p.b[1] + d * n[1]))
    r = p.radius
    r2 = r + d if p.ccw else r - d
    if r2 <= EPS:
        raise ValueError("the offset is larger than an arc's radius")
    f = r2 / r
    c = p.c
    return Piece((c[0] + (p.a[0] - c[0]) * f, c[1] + (p.a[1] - c[1]) * f),
                 (c[0] + (p.b[0] - c[0]) * f, c[1] + (p.b[1] - c[1]) * f), c, p.ccw)


def _circle_line(c: P, r: float, a: P, b: P) -> list[P]:
    d = _sub(b, a)
    f = _sub(a, c)
    aa = d[0] ** 2 + d[1] ** 2
    bb = 2 * (f[0] * d[0] + f[1] * d[1])
    cc = f[0] ** 2 + f[1] ** 2 - r * r
    disc = bb * bb - 4 * aa * cc
    if aa < EPS or disc < -1e-12:
        return []
    s = math.sqrt(max(disc, 0.0))
    return [(a[0] + t * d[0], a[1] + t * d[1]) for t in ((-bb - s) / (2 * aa), (-bb + s) / (2 * aa))]


def _circles(c1: P, r1: float, c2: P, r2: float) -> list[P]:
    dd = math.dist(c1, c2)
    if dd < EPS or dd > r1 + r2 + 1e-12 or dd < abs(r1 - r2) - 1e-12:
        return []
    a = (r1 * r1 - r2 * r2 + dd * dd) / (2 * dd)
    h = math.sqrt(max(r1 * r1 - a * a, 0.0))
    m = (c1[0] + a * (c2[0] - c1[0]) / dd, c1[1] + a * (c2[1] - c1[1]) / dd)
    return [(m[0] + h * (c2[1] - c1[1]) / dd, m[1] - h * (c2[0] - c1[0]) / dd),
            (m[0] - h * (c2[1] - c1[1]) / dd, m[1] + h * (c2[0] - c1[0]) / dd)]


def meet(p: Piece, q: Piece, near: P, *, rs274_arcs: bool = False) -> P | None:
    """Where the (extended) pieces p and q cross, the crossing nearest ``near`` (``rs274_arcs``: of two
    circles, the crossing rs274 2.9 takes at an offset corner)."""
    if p.c is None and q.c is None:
        d1, d2 = _sub(p.b, p.a), _sub(q.b, q.a)
        den = _cross(d1, d2)
        if abs(den) < EPS:
            return None
        t = _cross(_sub(q.a, p.a), d2) / den
        return (p.a[0] + t * d1[0], p.a[1] + t * d1[1])
    if p.c is None or q.c is None:
        line, arc = (p, q) if p.c is None else (q, p)
        assert arc.c is not None
        cands = _circle_line(arc.c, arc.radius, line.a, line.b)
    else:  # rs274 2.9 takes the crossing to the right of the line from p's centre to q's (black-box),
        # which is not always the one at the corner
        assert p.c is not None and q.c is not None
        cands = _circles(p.c, p.radius, q.c, q.radius)[: 1 if rs274_arcs else 2]
    return min(cands, key=lambda x: math.dist(x, near)) if cands else None


def offset(pieces: list[Piece], d: float) -> list[Piece]:
    """The profile ``d`` to the right of its travel: outside corners rounded (an arc about the corner;
    see :data:`ROUND_MIN_W`), inside corners trimmed to where the moved pieces cross."""
    if abs(d) < EPS or not pieces:
        return list(pieces)
    moved = _moved(pieces, d)
    out: list[Piece] = [moved[0][0]]
    raw: list[Piece] = [moved[0][0]]  # each piece of out before it was trimmed
    for k in range(1, len(moved)):
        cur, orig, joined = moved[k]
        prev = out[-1]
        vertex = orig.a
        turn = _cross(tangent(moved[k - 1][1], True), tangent(orig, False))
        if joined or math.dist(prev.b, cur.a) < 1e-9:
            out.append(cur)
            raw.append(cur)
        elif turn * d > 0 and abs(prev.b[0] - cur.a[0]) >= ROUND_MIN_W:  # the moved pieces part: round it
            out.append(Piece(prev.b, cur.a, vertex, d > 0))
            out.append(cur)
            raw += out[-2:]
        else:
            _trim(out, raw, cur, vertex)
    return out


def _smooth(p: Piece, q: Piece) -> bool:
    """q continues p without a corner."""
    t1, t2 = tangent(p, True), tangent(q, False)
    return abs(_cross(t1, t2)) < 1e-6 and t1[0] * t2[0] + t1[1] * t2[1] > 0


def _moved(pieces: list[Piece], d: float) -> list[tuple[Piece, Piece, bool]]:
    """Each piece moved by d, with the piece it came from and whether it joins the one before as it is.
    An arc whose moved radius would vanish (a concave arc smaller than d) becomes two arcs of radius |d|
    about its end points, meeting where those circles cross; one without corners at its ends (a fillet)
    vanishes (as rs274 2.9 does, black-box)."""
    out: list[tuple[Piece, Piece, bool]] = []
    for k, p in enumerate(pieces):
        try:
            out.append((_shift(p, d), p, False))
            continue
        except ValueError:
            if k == 0 or k == len(pieces) - 1:
                raise
        if _smooth(pieces[k - 1], p) and _smooth(p, pieces[k + 1]):  # a fillet: it vanishes, its neighbours meet
            continue
        a_end = _shift(pieces[k - 1], d).b
        b_start = _shift(pieces[k + 1], d).a
        t = _unit(_sub(p.b, p.a))
        side = (t[1], -t[0]) if d > 0 else (-t[1], t[0])
        cands = _circles(p.a, abs(d), p.b, abs(d))
        if not cands:
            raise ValueError("the offset is larger than an arc's radius")
        mid = ((p.a[0] + p.b[0]) / 2 + side[0], (p.a[1] + p.b[1]) / 2 + side[1])
        x = min(cands, key=lambda q: math.dist(q, mid))
        out.append((Piece(a_end, x, p.a, d > 0), Piece(p.a, p.a), True))
        out.append((Piece(x, b_start, p.b, d > 0), Piece(p.b, p.b), True))
    return out


def _reversed(p: Piece, q: Piece) -> bool:
    """A trimmed line ``q`` that now runs against its untrimmed self ``p`` (it has vanished)."""
    return p.c is None and q.c is None and ((q.b[0] - q.a[0]) * (p.b[0] - p.a[0])
                                              + (q.b[1] - q.a[1]) * (p.b[1] - p.a[1])) <= 0


def _trim(out: list[Piece], raw: list[Piece], cur: Piece, vertex: P) -> None:
    """Join ``cur`` to the end of ``out`` at an inside corner: both trimmed to where they cross.  A line
    trimmed away (a short piece, e.g. a chamfer, between two inside corners, or one whose start was
    trimmed past its end) is dropped and its neighbours meet instead.  ``raw``: out's pieces untrimmed."""
    while True:
        prev = out[-1]
        x = meet(prev, cur, vertex, rs274_arcs=True)
        if x is None:
            out.append(Piece(prev.b, cur.a))
            out.append(cur)
            raw += out[-2:]
            return
        trimmed = cut_piece(prev, end=x)
        if len(out) > 1 and _reversed(raw[-1], trimmed):
            out.pop()
            raw.pop()
            vertex = out[-1].b
            continue
        out[-1] = trimmed
        out.append(cut_piece(cur, start=x))
        raw.append(cur)
        return


def corner(p: Piece, q: Piece, size: float, chamfer: bool) -> tuple[Piece, Piece, Piece] | None:
    """A fillet (radius ``size``) or chamfer (the fillet's end points) between p and q."""
    turn = _cross(tangent(p, True), tangent(q, False))
    if abs(turn) < 1e-9 or size <= 0:
        return None
    side = -size if turn > 0 else size  # the centre lies inside the turn
    try:
        c = meet(_shift(p, side), _shift(q, side), p.b, rs274_arcs=True)
    except ValueError:
        return None
    if c is None:
        return None
    t1, t2 = _foot(p, c), _foot(q, c)
    join = Piece(t1, t2) if chamfer else Piece(t1, t2, c, turn > 0)
    return cut_piece(p, end=t1), join, cut_piece(q, start=t2)


def _foot(p: Piece, c: P) -> P:
    if p.c is None:
        d = _unit(_sub(p.b, p.a))
        t = (c[0] - p.a[0]) * d[0] + (c[1] - p.a[1]) * d[1]
        return (p.a[0] + t * d[0], p.a[1] + t * d[1])
    v = _unit(_sub(c, p.c))
    r = p.radius
    return (p.c[0] + v[0] * r, p.c[1] + v[1] * r)


def runs_down_w(pieces: list[Piece]) -> bool:
    """Every piece runs towards -w (or across): no turning back along the cut's axis."""
    for p in pieces:
        if p.b[0] > p.a[0] + 1e-9:
            return False
        if p.c is not None:
            swapped = Piece((p.a[1], p.a[0]), (p.b[1], p.b[0]), (p.c[1], p.c[0]), not p.ccw)
            if len(split_extrema(swapped)) > 1:
                return False
    return True
