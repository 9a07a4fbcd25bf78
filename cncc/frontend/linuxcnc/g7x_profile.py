"""The profile of a G70-G72 cycle: the Q subroutine's moves read (not run) and put in the cycle's frame.

From LinuxCNC's G-code manual (11.5.39): the subroutine may hold G0, G1, G2 and G3 moves (G0 is
read as G1), each with an optional A (a fillet of that radius at its end point) or C (a chamfer
with the fillet's end points); all other words are ignored.  Positions follow the distance mode
in force (G91: increments from the cycle's start point) and the diameter mode (X already halved
by the executor).  The cycle's frame ``(w, u)``: w along the axis the cut travels (Z for G71, X for
G72), signed so that the profile runs towards -w; u across, signed so that the profile's end lies
above its start (rs274 2.9 takes the stock to lie on that side: a start point below the profile's
start cuts nothing, black-box finding).  Written from the manual and black-box runs of rs274 2.9 only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

from cncc.frontend.linuxcnc.g7x_geom import P, Piece, corner, cross, split_extrema, tangent
from cncc.frontend.syntax import Word

if TYPE_CHECKING:
    from cncc.frontend.linuxcnc.executor import Frame, LinuxcncExecutor
    from cncc.source import Span

ZX = tuple[float, float]  # (z, x) in program units


class ProfileError(Exception):
    """The profile cannot be cut (rs274's text); ``code``: the diagnostic."""

    def __init__(self, message: str, code: str = "E0480") -> None:
        super().__init__(message)
        self.code = code


def capture(ex: LinuxcncExecutor, fr: Frame, label: str, span: Span) -> list[tuple[Word, ...]] | None:
    """The words of the blocks of subroutine ``label`` (its control flow runs, its moves do not)."""
    from cncc.frontend.linuxcnc.frames import Frame as CallFrame

    found = fr.index.subs.get(label)
    if found is None:
        return None
    depth = len(ex.stack)
    ex.push_scope([])
    ex.stack.append(CallFrame(fr.index, found[0] + 1, label, fr.pc, fr, span))
    ex.capture = []
    try:
        while len(ex.stack) > depth and not ex.stopped:
            top = ex.stack[-1]
            if top.pc >= len(top.index.blocks):
                ex.stack.pop()
                break
            ex._step(top)
        got = ex.capture
    finally:
        ex.capture = None
    return [w for _, w in got]


@dataclass(frozen=True, slots=True)
class Frame7x:
    """(z, x) -> (w, u): w = a * (z or x), u = b * (x or z)."""

    facing: bool  # G72: the cut travels along X
    a: float
    b: float

    def to(self, p: ZX) -> P:
        z, x = p
        return (self.a * x, self.b * z) if self.facing else (self.a * z, self.b * x)

    def back(self, q: P) -> ZX:
        w, u = q
        return (u / self.b, w / self.a) if self.facing else (w / self.a, u / self.b)

    @property
    def flips(self) -> bool:
        """True when the map reverses the sense of arcs."""
        det = -self.a * self.b if self.facing else self.a * self.b
        return det < 0


def _arc_centre(a: ZX, b: ZX, r: float, ccw: bool) -> ZX:
    """The centre of an R arc in the (z, x) plane (z first, G3 counter-clockwise)."""
    mz, mx = (a[0] + b[0]) / 2, (a[1] + b[1]) / 2
    dz, dx = b[0] - a[0], b[1] - a[1]
    h = math.hypot(dz, dx) / 2
    if h < 1e-12 or abs(r) < h - 1e-9:
        raise ProfileError("Radius to end of arc differs from radius to start")
    s = math.sqrt(max(r * r - h * h, 0.0)) / (2 * h)
    side = 1.0 if (r > 0) == ccw else -1.0  # short arc: the centre on the turning side
    return (mz - side * s * dx, mx + side * s * dz)


@dataclass(slots=True)
class _Reader:
    at: ZX
    incremental: bool
    arc_absolute: bool
    motion: int = 1

    def move(self, words: tuple[Word, ...]) -> tuple[Piece, float, bool] | None:
        """One block as a (z, x) piece, with its fillet/chamfer size; None for a block with no move."""
        w = {x.letter: x.value for x in words}
        for g in (x for x in words if x.letter == "G"):
            t = round(g.value * 10)
            if t in (0, 10, 20, 30):
                self.motion = t // 10
        z, x = self.at
        if self.incremental:
            z, x = z + w.get("Z", 0.0), x + w.get("X", 0.0)
        else:
            z, x = w.get("Z", z), w.get("X", x)
        z, x = z + w.get("W", 0.0), x + w.get("U", 0.0)
        if not any(k in w for k in "XZUW"):
            return None
        end = (z, x)
        start, self.at = self.at, end
        if self.motion in (2, 3):
            ccw = self.motion == 3
            if "R" in w:
                c = _arc_centre(start, end, w["R"], ccw)
            elif self.arc_absolute:
                c = (w.get("K", 0.0), w.get("I", 0.0))
            else:
                c = (start[0] + w.get("K", 0.0), start[1] + w.get("I", 0.0))
            piece = Piece(start, end, c, ccw)
        else:
            piece = Piece(start, end)
        size = w.get("A", w.get("C", 0.0))
        return piece, size, "C" in w and "A" not in w


def read(blocks: list[tuple[Word, ...]], start: ZX, incremental: bool,
         arc_absolute: bool) -> list[tuple[Piece, float, bool]]:
    """The profile's moves in (z, x) with their fillet/chamfer sizes."""
    r = _Reader(start, incremental, arc_absolute)
    out = []
    for words in blocks:
        m = r.move(words)
        if m is not None and m[0].a != m[0].b:
            out.append(m)
    if not out:
        raise ProfileError("G7x: the profile subroutine has no move")
    return out


def frame_for(moves: list[tuple[Piece, float, bool]], start: ZX, facing: bool) -> Frame7x:
    first, last = moves[0][0].b, moves[-1][0].b
    axis = 1 if facing else 0
    a = -1.0 if last[axis] > first[axis] else 1.0
    across = last[1 - axis] - first[1 - axis]  # rs274 takes the stock to lie where the profile climbs to
    b = (1.0 if start[1 - axis] >= first[1 - axis] else -1.0) if abs(across) < 1e-12 else math.copysign(1.0, across)
    return Frame7x(facing, a, b)


def monotonic(moves: list[tuple[Piece, float, bool]], facing: bool) -> bool:
    """Every move (but the first, the approach) goes the same way along the cut's axis."""
    f = Frame7x(facing, 1.0, 1.0)
    sign = 0.0
    for piece, _, _ in moves[1:]:
        for q in split_extrema(_to_frame(piece, f, swap_u=True)):
            d = q.b[1] - q.a[1]
            if abs(d) < 1e-9:
                continue
            if sign and d * sign < 0:
                return False
            sign = sign or math.copysign(1.0, d)
    return True


def _to_frame(p: Piece, f: Frame7x, *, swap_u: bool = False) -> Piece:
    """p in frame f; ``swap_u``: the cut's axis as u (to test it for turning points)."""
    if swap_u:
        f = Frame7x(not f.facing, f.b, f.a)
    c = None if p.c is None else f.to(p.c)
    return Piece(f.to(p.a), f.to(p.b), c, p.ccw != f.flips)


# rs274 2.9 and small fillets/chamfers (black-box, the same in G20 and G21, in program units): one whose
# end points lie less than SMALL_CHORD apart is not put in (the corner stays); one that spans less than
# SMALL_SPAN_OUTSIDE along the cut's axis at an outside corner (less than SMALL_SPAN_INSIDE at an inside
# one) makes it report "Not monotonic".
SMALL_CHORD = 0.001
SMALL_SPAN_OUTSIDE = 0.01
SMALL_SPAN_INSIDE = 0.001


def _small(join: Piece, outside: bool) -> bool:
    """True when rs274 2.9 refuses the profile for this fillet or chamfer (see SMALL_CHORD)."""
    return abs(join.a[0] - join.b[0]) < (SMALL_SPAN_OUTSIDE if outside else SMALL_SPAN_INSIDE)


def pieces(moves: list[tuple[Piece, float, bool]], f: Frame7x) -> list[Piece]:
    """The profile (from the end of its first move) in the cycle's frame, fillets and chamfers put in."""
    out: list[Piece] = []
    todo = [(_to_frame(p, f), size, chamfer) for p, size, chamfer in moves[1:]]
    pending = 0.0, False
    for p, size, chamfer in todo:
        if out and pending[0] > 0:
            got = corner(out[-1], p, pending[0], pending[1])
            if got is None:
                raise ProfileError("G7X error: Not monotonic")
            join = got[1]
            if math.dist(join.a, join.b) >= SMALL_CHORD:
                outside = cross(tangent(out[-1], True), tangent(p, False)) > 0
                if _small(join, outside):
                    raise ProfileError("G7X error: Not monotonic")
                out[-1] = got[0]
                out.append(join)
                p = got[2]
        out.append(p)
        pending = size, chamfer
    return [p for p in out if p.a != p.b or p.c is not None]


def start_tangent(ps: list[Piece]) -> P:
    return tangent(ps[0], False)
