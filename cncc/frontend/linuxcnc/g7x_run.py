"""Runs one G70-G72 block: the start point, the profile, the passes, lowered to plain IR moves.

The moves are ordinary ``Rapid``/``Linear``/``Arc`` commands (origin ``CYCLE``), so every
pass and back end sees a lathe cycle as the moves it makes; only X and Z move (Y and the
rotary axes stay where they are).  Written from LinuxCNC's G-code manual (G70, G71/G72) and
black-box runs of rs274 2.9 (docs/dialects-notes.md lists what was learnt that way).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from cncc import diagnostics as dg
from cncc.frontend.interp import BlockContext
from cncc.frontend.linuxcnc.g7x_cut import Move, finishing, roughing
from cncc.frontend.linuxcnc.g7x_geom import Piece, offset, runs_down_w
from cncc.frontend.linuxcnc.g7x_profile import ZX, Frame7x, ProfileError, capture, frame_for, monotonic, pieces, read
from cncc.frontend.linuxcnc.g7x_safety import first_gouge
from cncc.frontend.ops import block_motion, feed_mm_min
from cncc.frontend.syntax import Block, Word
from cncc.ir import Arc, Command, Linear, Origin, OriginKind, Plane, Rapid, Vec6
from cncc.source import Span

if TYPE_CHECKING:
    from cncc.frontend.linuxcnc.executor import Frame, LinuxcncExecutor


def _start(ex: LinuxcncExecutor, words: tuple[Word, ...]) -> ZX:
    """The cycle's start point (z, x) in program units: the block's X/Z, else where the tool is."""
    it = ex.it
    k = it.frame.units.mm_per_unit
    z, x = it.pos[2] / k, it.pos[0] / k
    w = {v.letter: v.value for v in words}
    if it.modal.incremental:
        return z + w.get("Z", 0.0), x + w.get("X", 0.0)
    return w.get("Z", z), w.get("X", x)


def _arc_absolute(ex: LinuxcncExecutor) -> bool:
    st = ex.it.rs274
    return bool(st is not None and st.arc_absolute)


def _side(ps: list[Piece], s: tuple[float, float], *, finishing: bool) -> float:
    """+1: the D/E distances go towards +u (the stock).  With the start point on the far side of the profile
    (no roughing pass), and always in G70, rs274 2.9 offsets towards the side of the first piece's line
    the start point lies on (black-box finding; the manual, G70: "a positive distance towards this
    point")."""
    first, last = ps[0].a, ps[-1].b
    if not finishing and ((s[1] >= first[1] and last[1] >= first[1]) or len(ps) == 1):
        return 1.0  # (one piece: towards +u all the same)
    t = (ps[0].b[0] - first[0], ps[0].b[1] - first[1])  # the first piece's chord
    cross = t[0] * (s[1] - first[1]) - t[1] * (s[0] - first[0])
    return 1.0 if cross <= 0 else -1.0


def _plan(ex: LinuxcncExecutor, blocks: list[tuple[Word, ...]], start: ZX, words: tuple[Word, ...],
          cycle: int, sub: int) -> tuple[list[Move], Frame7x]:
    w = {v.letter: v.value for v in words}
    moves = read(blocks, start, ex.it.modal.incremental, _arc_absolute(ex))
    facing = cycle == 72 or (cycle == 70 and not monotonic(moves, False))
    if not monotonic(moves, facing):
        raise ProfileError("G7X error: Not monotonic")
    f = frame_for(moves, start, facing)
    ps = pieces(moves, f)
    if not ps:
        raise ProfileError("G7x: the profile subroutine has no move")
    s = f.to(start)
    side = _side(ps, s, finishing=cycle == 70)
    if cycle == 70:
        d, e, n = w.get("D", 0.0), w.get("E", 0.0), max(int(w.get("P", 1.0)), 1)
        passes = [offset(ps, side * ((p - 1) * (d - e) / n + e)) for p in range(n, 0, -1)]
        if not all(runs_down_w(q) for q in passes):
            raise ProfileError("G7X error: Not monotonic")
        out = finishing(passes, s, ps[0].a)
    else:
        rough: list[Piece] = offset(ps, side * w.get("D", 0.0))
        if not runs_down_w(rough):  # rs274 checks the offset profile too
            raise ProfileError("G7X error: Not monotonic")
        out = roughing(rough, s, w.get("I", 1.0), w.get("R", 0.5), sub, ps[0].a)
    above = s[1] >= ps[0].a[1] and ps[-1].b[1] >= ps[0].a[1] and side > 0
    if above and (bad := first_gouge(ps, s, out[1:])) is not None:  # (the first rapid is the block's own)
        z, x = f.back(bad[0])
        raise ProfileError(f"G{cycle}: a {bad[1]} move of the cycle would cut into the profile at X{x:.4f} "
                           f"Z{z:.4f}; nothing is run", dg.LATHE_GOUGE)
    return out, f


def _block_modes(ex: LinuxcncExecutor, words: tuple[Word, ...]) -> None:
    """G90/G91 and F of the cycle's own block apply before the cycle (rs274's order of execution)."""
    it = ex.it
    tenths = {round(w.value * 10) for w in words if w.letter == "G"}
    if 900 in tenths or 910 in tenths:
        it.modal = it.modal.with_(incremental=910 in tenths)
    f = next((w.value for w in words if w.letter == "F"), None)
    if f is not None:
        it.modal = it.modal.with_(feed=f)


def cut(ex: LinuxcncExecutor, fr: Frame, span: Span, words: tuple[Word, ...], cycle: int, sub: int) -> None:
    it = ex.it
    _block_modes(ex, words)
    label = str(round(next(v.value for v in words if v.letter == "Q")))
    scratch: list[Command] = []
    ctx = BlockContext(Block(0, span.start, span.end, ()), span, {}, [], scratch)
    feed = feed_mm_min(it, ctx)
    if feed is None:
        ex.stopped = True
        return
    start = _start(ex, words)
    blocks = capture(ex, fr, label, span)
    if blocks is None:
        ex.fail(dg.OWORD_NO_SUB, span, f"G{cycle}: the profile subroutine o{label} is not defined", label)
        return
    try:
        moves, f = _plan(ex, blocks, start, words, cycle, sub)
    except ProfileError as exc:
        ex.fail(exc.code, span, str(exc))
        return
    except ValueError as exc:
        ex.fail(dg.LATHE_PROFILE, span, str(exc))
        return
    _Emit(ex, span, f, feed, ctx).run(moves, cycle)


class _Emit:
    def __init__(self, ex: LinuxcncExecutor, span: Span, f: Frame7x, feed: float, ctx: BlockContext) -> None:
        self.ex, self.it, self.span, self.f, self.feed = ex, ex.it, span, f, feed
        self.k = self.it.frame.units.mm_per_unit
        self.at: Vec6 = self.it.pos
        self.motion = block_motion(self.it, ctx)

    def _vec(self, zx: ZX) -> Vec6:
        a = self.at
        return (zx[1] * self.k, a[1], zx[0] * self.k, a[3], a[4], a[5])

    def run(self, moves: list[Move], cycle: int) -> None:
        origin = Origin(OriginKind.CYCLE, f"G{cycle}")
        fr = self.it.frame
        for m in moves:
            end = self._vec(self.f.back(m.end))
            cmd: Command
            if m.kind == "rapid":
                cmd = Rapid(self.span, fr, self.at, end, self.motion, origin)
            elif m.kind == "feed" or m.piece is None or m.piece.c is None:
                cmd = Linear(self.span, fr, self.at, end, self.feed, self.motion, origin)
            else:
                c = self._vec(self.f.back(m.piece.c))
                ccw = m.piece.ccw != self.f.flips
                cmd = Arc(self.span, fr, self.at, end, c, 1 if ccw else -1, Plane.ZX, self.feed, self.motion, origin)
            self.ex.out.append(cmd)
            self.at = end
        self.it.pos = self.at
