"""The passes of G70-G72 in the cycle's own frame (w along the cut, towards -w; u across, stock at +u).

Written from LinuxCNC's G-code manual and black-box runs of rs274 2.9 (no LinuxCNC source):

- roughing levels are ``u = start_u - n * I`` (n = 0, 1, ...).  The main stage cuts each level
  above the profile's start from the entry line (the start point, moved along w to the profile's
  start when it lies past it, joined to the profile's start) to where the profile first reaches
  the level, retracts ``R`` at 45 degrees (less, half the pass, on a short pass), rapids back at
  that height and to the entry point;
- the pocket stage (G7x and G7x.2) follows the profile; where it turns down from a peak it cuts
  each level between the peak (included) and the next valley (excluded) from the falling wall
  to where the profile reaches the level again, feeding back to the wall after each pass;
- G7x.1 cuts only the pocket the profile may start with and ends with a pass along the profile
  with its other pockets bridged (each piece's part above the highest point before it, as rs274
  prints it: a feed to the part's start, then its end); G7x.2 leaves that first pocket alone;
- a roughing cycle ends with a feed from the profile's end across to the start height (none when
  the end lies above it);
- a start point below the profile's start cuts nothing: a feed along the entry line and the profile.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from cncc.frontend.linuxcnc.g7x_geom import EPS, P, Piece, at_u, cut_piece, split_extrema

LEVEL_EPS = 1e-7  # a level this close to a peak still cuts it
GRAZE = 1e-6


@dataclass(frozen=True, slots=True)
class Move:
    kind: str  # "rapid", "feed" (straight) or "arc"
    end: P
    piece: Piece | None = None


@dataclass(slots=True)
class Rough:
    pieces: list[Piece]
    start: P
    step: float
    retract: float
    own_grid: bool = False
    first_plain: P = (0.0, 0.0)
    out: list[Move] = field(default_factory=list)

    def __post_init__(self) -> None:
        self.pieces = [q for p in self.pieces for q in split_extrema(p)]

    @property
    def first(self) -> P:
        return self.pieces[0].a

    @property
    def last(self) -> P:
        return self.pieces[-1].b

    # ---- emitting
    def rapid(self, p: P) -> None:
        self.out.append(Move("rapid", p))

    def feed(self, p: P) -> None:
        self.out.append(Move("feed", p))

    def along(self, p: Piece) -> None:
        """A feed along the piece (an arc of no length is no move; a line of no length is, as in rs274)."""
        if p.c is not None and math.dist(p.a, p.b) < 1e-9:
            return
        self.out.append(Move("feed", p.b) if p.c is None else Move("arc", p.b, p))

    def levels(self, top: float, bottom: float, *, include_top: bool) -> list[float]:
        """The grid levels base - n I in (bottom, top] (or (bottom, top)); the base is the start point's u,
        or in G7x.2 (no main stage) the top of the pocket."""
        out: list[float] = []
        n = 0
        base = top if self.own_grid else self.start[1]
        while True:
            lv = base - n * self.step
            n += 1
            if lv <= bottom + EPS:
                return out
            if lv < top + LEVEL_EPS if include_top else lv < top - LEVEL_EPS:
                out.append(lv)
            if n > 100_000:
                return out

    def reach(self, level: float, after: int) -> float:
        """w where the profile, from piece ``after`` on, first reaches ``level`` (else its end)."""
        for p in self.pieces[after:]:
            if max(p.a[1], p.b[1]) >= level - EPS:
                if p.a[1] >= level - EPS:
                    return p.a[0]
                q = at_u(p, level)
                if q is not None:
                    return q[0]
        return self.last[0]

    def one_pass(self, level: float, w_in: float, w_out: float, *, feed_back: bool) -> None:
        self.feed((w_out, level))
        r = min(self.retract, max(w_in - w_out, 0.0) / 2)
        self.rapid((w_out + r, level + r))
        self.rapid((w_in - r, level + r))
        (self.feed if feed_back else self.rapid)((w_in, level))

    # ---- stages
    def main_stage(self) -> None:
        s = self.entry_rapids()
        for level in self.levels(self.start[1], self.first[1], include_top=True):
            w_in = _line_at(s, self.first, level)
            self.rapid((w_in, level))
            self.one_pass(level, w_in, self.reach(level, 0), feed_back=False)

    def entry_rapids(self) -> P:
        """The start point moved along w to the (not offset) profile's start when it lies past it."""
        s = (max(self.start[0], self.first_plain[0]), self.start[1])
        self.rapid(s)
        return s

    def pocket_walk(self) -> None:
        self.rapid(self.first)
        k, n = 0, len(self.pieces)
        while k < n:
            p = self.pieces[k]
            if p.b[1] >= p.a[1] - EPS:
                self.along(p)
                k += 1
                continue
            j = k
            while j + 1 < n and self.pieces[j + 1].b[1] < self.pieces[j + 1].a[1] - EPS:
                j += 1
            if k == 0 and self.own_grid:  # G7x.2: the pocket at the start is G7x.1's (manual), followed only
                for q in self.pieces[: j + 1]:
                    self.along(q)
            else:
                self._pocket(k, j)
            k = j + 1
        self.close()

    def _pocket(self, k: int, j: int) -> None:
        """The falling run of pieces k..j: the levels between its top and its valley."""
        top, valley = self.pieces[k].a[1], self.pieces[j].b[1]
        at = k
        cur: Piece | None = None
        for level in self.levels(top, valley, include_top=True):
            while at <= j:
                p = cur or self.pieces[at]
                q = at_u(p, level)
                if q is not None and p.b[1] < level - EPS:
                    self.along(cut_piece(p, end=q))
                    cur = cut_piece(p, start=q)
                    break
                self.along(p)
                cur = None
                at += 1
            if at > j:
                break
            w_wall = cur.a[0] if cur is not None else self.pieces[at].a[0]
            self.one_pass(level, w_wall, self.reach(level, j + 1), feed_back=True)
        while at <= j:
            self.along(cur or self.pieces[at])
            cur = None
            at += 1

    def bridged(self) -> None:
        """G7x.1's last pass: the profile with its pockets bridged."""
        self.rapid(self.first)
        k = 0
        while k < len(self.pieces) and self.pieces[k].b[1] < self.pieces[k].a[1] - EPS:
            k += 1
        if k:  # a profile that starts going down: that first pocket is cut, down to its valley
            self._pocket(0, k - 1)
        env = self.pieces[k - 1].b[1] if k else self.first[1]
        for n, p in enumerate(self.pieces[k:]):
            if p.b[1] < env - EPS or (p.b[1] <= env + EPS and p.a[1] < env - EPS):
                continue
            start = p.a if p.a[1] >= env - EPS else at_u(p, env) or p.a
            if not (n == 0 and k and p.c is not None and p.c == self.pieces[k - 1].c):
                self.feed(start)  # (an arc that climbs out of the first pocket goes on as one move)
            if not _grazes(p, env):
                self.along(cut_piece(p, start=start))
            env = max(env, p.b[1])
        self.feed((self.last[0], max(env, self.last[1])))  # a pocket at the end: bridged too
        self.close()

    def below(self, bridged: bool) -> None:
        """The start point lies below the profile's start: no pass; a feed along the entry line and the
        profile (G7x.1: as its bridged pass prints it), and no feed back to the start height."""
        s = self.entry_rapids()
        if not bridged:
            self.feed(self.first)
            for p in self.pieces:
                self.along(p)
            return
        env = s[1]
        for p in [Piece(s, self.first), *self.pieces]:
            if p.b[1] < env - EPS or (p.b[1] <= env + EPS and p.a[1] < env - EPS):
                continue
            start = p.a if p.a[1] >= env - EPS else at_u(p, env) or p.a
            self.feed(start)
            self.along(cut_piece(p, start=start))
            env = max(env, p.b[1])

    def close(self) -> None:
        """The feed from the profile's end across to the start height (none when the end lies above it)."""
        if self.last[1] <= self.start[1] + EPS:
            self.feed((self.last[0], self.start[1]))


def _grazes(p: Piece, env: float) -> bool:
    """An arc that rises less than GRAZE above the bridged height (the top of a corner arc the level line
    touches): rs274 2.9 prints the feed to its start, not the arc, in the bridged pass."""
    return p.c is not None and abs(p.a[1] - env) < GRAZE and p.b[1] - env < GRAZE


def _line_at(a: P, b: P, level: float) -> float:
    du = b[1] - a[1]
    if abs(du) < EPS:
        return a[0]
    return a[0] + (level - a[1]) * (b[0] - a[0]) / du


def roughing(pieces: list[Piece], start: P, step: float, retract: float, variant: int,
             plain_start: P) -> list[Move]:
    """G71/G72 (variant 0), .1 (no pockets) or .2 (pockets only); ``plain_start``: the profile's start
    before the D offset."""
    r = Rough(pieces, start, step, retract, variant == 2, plain_start)
    r.rapid(start)
    if start[1] < plain_start[1] or r.last[1] < r.first[1]:  # rs274: a feed along the profile, no pass
        r.below(variant == 1)
        return merge_valleys(r.out)
    if variant == 2:
        r.entry_rapids()
        r.pocket_walk()
    else:
        r.main_stage()
        if variant == 1:
            r.bridged()
        else:
            r.pocket_walk()
    return merge_valleys(r.out)


def merge_valleys(out: list[Move]) -> list[Move]:
    """Two arc moves of one arc that meet at its lowest point are one move (rs274 splits an arc at its top
    only)."""
    merged: list[Move] = []
    for m in out:
        prev = merged[-1] if merged else None
        if (m.kind == "arc" and prev is not None and prev.kind == "arc" and m.piece is not None
                and prev.piece is not None and m.piece.c == prev.piece.c and m.piece.ccw == prev.piece.ccw
                and m.piece.c is not None and abs(prev.end[1] - (m.piece.c[1] - m.piece.radius)) < 1e-9):
            merged[-1] = Move("arc", m.end, Piece(prev.piece.a, m.piece.b, m.piece.c, m.piece.ccw))
            continue
        merged.append(m)
    return merged


def finishing(passes: list[list[Piece]], start: P, plain_start: P) -> list[Move]:
    """G70: each pass along its profile, a rapid between them to the start point (moved along w to the
    profile's start when it lies past it, as in the roughing cycles)."""
    s = (max(start[0], plain_start[0]), start[1])
    out = [Move("rapid", start), Move("rapid", s)]
    for n, pieces in enumerate(passes):
        if n:
            out.append(Move("rapid", s))
        out.append(Move("rapid", pieces[0].a))
        out.extend(Move("feed", p.b) if p.c is None else Move("arc", p.b, p) for p in pieces)
    return out

