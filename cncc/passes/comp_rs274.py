"""``cutter-comp-rs274``: G41/G42 cutter radius compensation as LinuxCNC 2.9's interpreter makes it.

Consumes commands whose frames carry ``comp_side``/``comp_radius_mm``; produces the tool
path with compensation off in the frames.  Chosen for a dialect by ``comp_algorithm =
"rs274"`` (the LinuxCNC dialect); the generic pass is :mod:`cncc.passes.cutter_comp`.

rs274 works move by move with a queue: the last move in the plane (and the moves off the
plane after it) wait until the next move in the plane settles their corner.

* **Entry** (first move after G41/G42): a line ends r from its programmed end, square to
  itself (it must be longer than r); an arc keeps its start,
  its end moves by r square to the arc, and its centre moves so the start stays on it.
* **Corners** are judged by ``beta``, the turn from the tool's offset at the corner to the
  next element, with 0.05 rad of tolerance: outside (``beta`` above it) an arc of radius r
  about the programmed corner; nearly tangent, nothing; inside, the queued moves' ends go
  back to where the offset curves meet (an "h" shape, a line tangent after an arc curving
  the other way, is inside too).
* **Moves off the plane** (Z only, a rotary axis) keep the tool's plane point; a later
  inside corner moves their plane point with the queued element's end, and an outside
  corner's arc is cut at the new height (Z first, then the corner).
* **Errors** with rs274's texts: an entry no longer than r, a queued line that would run
  backwards (gouging), an inside corner the tool cannot reach, an inside arc not larger
  than r, an arc just after G40.
* **Exit** (first move after G40): the queue is flushed where it stands; the move goes
  from the tool to its programmed end (a move off the plane takes the plane point along).
"""

from __future__ import annotations

import contextlib
import math
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field, replace
from typing import ClassVar

from cncc import diagnostics as dg
from cncc.ir import (
    Arc,
    Command,
    Comment,
    CompSide,
    Coolant,
    Dwell,
    FeedRate,
    Frame,
    InterpreterReport,
    Linear,
    OriginKind,
    Rapid,
    SetCutterComp,
    SetFeedMode,
    SetSpindleMode,
    SetUnits,
    Spindle,
    SpindleSpeed,
    Stop,
    Vec6,
)
from cncc.ir.frame import add_offsets, sub_offsets
from cncc.passes import Pass, PassContext, register
from cncc.passes.comp_geometry import Pt

Motion = Rapid | Linear | Arc
# The calls rs274 queues with the moves (its enqueue_* canon calls): while moves wait in the queue
# these wait after them, so the trace keeps rs274's order (a feed rate after the move it follows).
HELD = (FeedRate, Dwell, Coolant, Spindle, SpindleSpeed, SetSpindleMode, SetFeedMode, Comment, InterpreterReport)
SMALL = 0.05  # rs274's TOLERANCE_CONCAVE_CORNER (radians)
HALF_PI = math.pi / 2


@dataclass(slots=True)
class _Queued:
    cmd: Motion  # the programmed command it comes from (span, feed, motion)
    start: Vec6  # world (program + offsets)
    end: Vec6
    center: Pt | None = None  # arcs
    turn: int = 0  # arcs: signed like Arc.turns
    direction: Pt = (0.0, 0.0)  # lines: the programmed direction (reversal check)
    sweep: float = 0.0  # arcs: the sweep when queued
    checked: bool = True  # lines: checked for reversal (rs274 never reverses an entry move)


def _turn_angle(p0: Pt, c: Pt, turn: int, p1: Pt) -> float:
    """rs274's find_turn: the signed angle an arc of ``turn`` travels from p0 to p1."""
    a0, a1 = math.atan2(p0[1] - c[1], p0[0] - c[0]), math.atan2(p1[1] - c[1], p1[0] - c[0])
    if turn > 0:
        d = a1 - a0
        if d <= 0:
            d += 2 * math.pi
        return d + 2 * math.pi * (turn - 1)
    d = a1 - a0
    if d >= 0:
        d -= 2 * math.pi
    return d - 2 * math.pi * (-turn - 1)


def _line_circle(p: Pt, d: Pt, c: Pt, r: float) -> list[Pt]:
    n = math.hypot(*d)
    if n == 0:
        return []
    u = (d[0] / n, d[1] / n)
    f = (p[0] - c[0], p[1] - c[1])
    b = f[0] * u[0] + f[1] * u[1]
    disc = b * b - (f[0] * f[0] + f[1] * f[1] - r * r)
    if disc < 0:
        return []
    s = math.sqrt(disc)
    return [(p[0] + u[0] * t, p[1] + u[1] * t) for t in (-b - s, -b + s)]


def _circle_circle(c1: Pt, r1: float, c2: Pt, r2: float) -> list[Pt]:
    dx, dy = c2[0] - c1[0], c2[1] - c1[1]
    d = math.hypot(dx, dy)
    if d < 1e-12 or d > r1 + r2 or d < abs(r1 - r2):
        return []
    a = (r1 * r1 - r2 * r2 + d * d) / (2 * d)
    h = math.sqrt(max(r1 * r1 - a * a, 0.0))
    mx, my = c1[0] + dx * a / d, c1[1] + dy * a / d
    return [(mx - dy * h / d, my + dx * h / d), (mx + dy * h / d, my - dx * h / d)]


def _behind(points: list[Pt], q: _Queued, plane: tuple[int, int]) -> Pt | None:
    """The meeting point the queued element reaches first when it backs up from its end
    (an inside corner shortens the element before it; it never runs past its end)."""
    if not points:
        return None
    i, j = plane
    end = (q.end[i], q.end[j])
    if q.center is None:
        d = q.direction
        n = math.hypot(*d) or 1.0

        def back(p: Pt) -> float:
            t = ((end[0] - p[0]) * d[0] + (end[1] - p[1]) * d[1]) / n
            return t if t >= -1e-9 else math.inf

        best = min(points, key=back)
        return best if back(best) < math.inf else None
    c, sign = q.center, (1.0 if q.turn > 0 else -1.0)
    a_end = math.atan2(end[1] - c[1], end[0] - c[0])
    return min(points, key=lambda p: (sign * (a_end - math.atan2(p[1] - c[1], p[0] - c[0]))) % (2 * math.pi))


def _plane(c: Motion) -> tuple[int, int]:
    return c.frame.plane.first, c.frame.plane.second


@register
@dataclass(frozen=True, kw_only=True)
class CutterCompRs274(Pass):
    """G41/G42 as rs274 2.9 (queue, beta corners, tangent entry)."""

    name: ClassVar[str] = "cutter-comp-rs274"

    def run(self, cmds: Iterable[Command], ctx: PassContext) -> Iterator[Command]:
        st = _State(ctx)
        for c in cmds:
            yield from st.feed(c)
        yield from st.flush()


class _Stop(Exception):
    """A compensation error: reported, the queue flushed, the move made uncompensated."""


@dataclass(slots=True)
class _State:
    ctx: PassContext
    cur: Vec6 | None = None  # world position of the tool (end of the last output or queued move)
    prog: Pt = (0.0, 0.0)  # programmed plane point of the last compensated move (rs274's program_x/y)
    first: bool = True
    on: bool = False
    arc_not_allowed: bool = False
    queue: list[_Queued] = field(default_factory=list)
    endpoint: Pt | None = None  # start of the queued element (the reversal check)
    frames: dict[int, tuple[Frame, Frame]] = field(default_factory=dict)
    held: list[tuple[int, Command]] = field(default_factory=list)  # (after queue[i], a HELD call)

    # ---- entry
    def feed(self, c: Command) -> Iterator[Command]:
        if not isinstance(c, Rapid | Linear | Arc):
            if isinstance(c, SetCutterComp | Stop):
                if self.queue and self.cur is not None:  # G40: rs274 checks the queue where the tool is
                    last = self.queue[-1].cmd
                    with contextlib.suppress(_Stop):
                        yield from self._move_endpoint_and_flush(last, self._xy(last, self.cur))
                yield from self.flush()
                if isinstance(c, SetCutterComp) and c.frame.comp_side is not CompSide.OFF and not self.on:
                    self.first = True
            elif self.queue and isinstance(c, HELD):
                self.held.append((len(self.queue) - 1, c))
                return
            elif self.queue and isinstance(c, SetUnits):  # rs274 prints the queued moves in the new units
                self._reunit(c.frame)
            yield c if self._frame(c.frame) is c.frame else replace(c, frame=self._frame(c.frame))
            return
        f = c.frame
        comp = f.comp_side is not CompSide.OFF and f.comp_radius_mm > 0.0
        special = c.origin.kind in (OriginKind.MACHINE, OriginKind.HOME, OriginKind.REFERENCE)  # G53, G28/G30
        if not comp or special:
            if self.on:
                yield from self.flush()
                self.on = False
                self.arc_not_allowed = True
            if isinstance(c, Arc) and self.arc_not_allowed:
                self._error(c, "The move just after exiting cutter compensation mode must be straight, not an arc",
                            dg.COMP_ON_ARC)
            if not isinstance(c, Arc):
                self.arc_not_allowed = False
            yield from self._plain(c)
            return
        if not self.on:
            self.on, self.first = True, True
        try:
            if self.first:
                yield from self._first(c)
            elif isinstance(c, Arc):
                yield from self._arc2(c)
            else:
                yield from self._straight2(c)
        except _Stop:
            yield from self.flush()
            yield from self._plain(c)

    def flush(self) -> Iterator[Command]:
        q, self.queue = self.queue, []
        held, self.held = self.held, []
        for k, item in enumerate(q):
            yield self._out(item)
            for _, c in (h for h in held if h[0] == k):
                yield c if self._frame(c.frame) is c.frame else replace(c, frame=self._frame(c.frame))

    def _reunit(self, f: Frame) -> None:
        for q in self.queue:
            if q.cmd.frame.units is not f.units:
                q.cmd = replace(q.cmd, frame=replace(q.cmd.frame, units=f.units))

    # ---- helpers
    def _frame(self, f: Frame) -> Frame:
        got = self.frames.get(id(f))
        if got is None or got[0] is not f:  # (the key frame is kept: an id is unique only while it lives)
            got = (f, f if f.comp_side is CompSide.OFF and f.comp_radius_mm == 0.0 else replace(
                f, comp_side=CompSide.OFF, comp_radius_mm=0.0))
            self.frames[id(f)] = got
        return got[1]

    def _error(self, c: Motion, text: str, code: str = dg.CONTROLLER_REJECTS) -> None:
        self.ctx.sink.emit(code, c.span, text)

    def _fail(self, c: Motion, text: str, code: str = dg.CONTROLLER_REJECTS) -> None:
        self._error(c, text, code)
        raise _Stop

    def _here(self, c: Motion) -> Vec6:
        return self.cur if self.cur is not None else add_offsets(c.start, c.frame)

    def _plain(self, c: Motion) -> Iterator[Command]:
        nf = self._frame(c.frame)
        start = sub_offsets(self.cur, nf) if self.cur is not None else c.start
        self.cur = add_offsets(c.end, c.frame)
        end = sub_offsets(self.cur, nf)
        if start == c.start and end == c.end and nf is c.frame:
            yield c
        else:
            yield replace(c, frame=nf, start=start, end=end)

    def _out(self, q: _Queued) -> Motion:
        c = q.cmd
        nf = self._frame(c.frame)
        start, end = sub_offsets(q.start, nf), sub_offsets(q.end, nf)
        if q.center is None:
            if isinstance(c, Rapid):
                return Rapid(c.span, nf, start, end, c.motion, c.origin)
            return Linear(c.span, nf, start, end, c.feed_mm_min, c.motion, c.origin)
        i, j = c.frame.plane.first, c.frame.plane.second
        cen = list(q.end)
        cen[i], cen[j] = q.center
        center = sub_offsets((cen[0], cen[1], cen[2], cen[3], cen[4], cen[5]), nf)
        feed = c.feed_mm_min if isinstance(c, Linear | Arc) else 0.0
        return Arc(c.span, nf, start, end, center, q.turn, c.frame.plane, feed, c.motion, c.origin)

    def _at(self, c: Motion, base: Vec6, xy: Pt) -> Vec6:
        i, j = c.frame.plane.first, c.frame.plane.second
        out = list(base)
        out[i], out[j] = xy
        return (out[0], out[1], out[2], out[3], out[4], out[5])

    def _xy(self, c: Motion, p: Vec6) -> Pt:
        return p[c.frame.plane.first], p[c.frame.plane.second]

    def _enqueue(self, q: _Queued) -> None:
        self.queue.append(q)
        self.cur = q.end

    def _move_endpoint_and_flush(self, c: Motion, xy: Pt) -> Iterator[Command]:
        """rs274's move_endpoint_and_flush: the queued moves end at ``xy``, then run."""
        for q in self.queue:
            if q.center is not None:
                sweep = _turn_angle(self._xy(c, q.start), q.center, q.turn, xy)
                if abs(sweep) > abs(q.sweep) + 0.01:
                    self._fail(c, "Arc move in concave corner cannot be reached by the tool without gouging")
            elif q.checked and self.endpoint is not None and (q.direction[0] * (xy[0] - self.endpoint[0])
                                                + q.direction[1] * (xy[1] - self.endpoint[1])) < 0:
                kind = "traverse" if isinstance(q.cmd, Rapid) else "feed"
                self._fail(c, f"Straight {kind} in concave corner cannot be reached by the tool without gouging",
                           dg.COMP_GOUGE)
            q.end = self._at(c, q.end, xy)
            if q.center is None and q is not self.queue[0]:
                q.start = self._at(c, q.start, xy)
        for k in range(1, len(self.queue)):
            self.queue[k].start = self.queue[k - 1].end
        if self.queue:
            self.cur = self.queue[-1].end
        yield from self.flush()

    # ---- the first move: entry
    def _corner_arc(self, c: Motion, here: Vec6, mid: Pt, end: Pt, corner: Pt, left: bool) -> Iterator[Command]:
        """An outside corner: the queued move ends at ``end``, then an arc about the programmed ``corner``
        to ``mid`` (where the next move starts)."""
        yield from self._move_endpoint_and_flush(c, end)
        turn = -1 if left else 1
        self._enqueue(_Queued(c, here, self._at(c, here, mid), corner, turn, sweep=_turn_angle(end, corner, turn, mid)))
        yield from self.flush()

    def _first(self, c: Motion) -> Iterator[Command]:
        r, left = c.frame.comp_radius_mm, c.frame.comp_side is CompSide.LEFT
        here = self._here(c)
        cx, cy = self._xy(c, here)
        w_end = add_offsets(c.end, c.frame)
        px, py = self._xy(c, w_end)
        if isinstance(c, Arc):
            yield from self._arc1(c, here, w_end, r, left)
            return
        if (px, py) == (cx, cy):  # no move in the plane yet: compensation starts with the next one
            yield from self.flush()
            self.cur = w_end
            self._enqueue(_Queued(c, here, w_end))
            yield from self.flush()
            return
        distance = math.hypot(px - cx, py - cy)
        if distance <= r:
            self._fail(c, "Length of cutter compensation entry move is not greater than the tool radius")
        alpha = math.atan2(py - cy, px - cx) + (HALF_PI if left else -HALF_PI)
        end = (px + r * math.cos(alpha), py + r * math.sin(alpha))  # square to the entry move
        yield from self.flush()
        self.endpoint = None  # rs274 checks queued lines against the start set at an outside corner only
        self._enqueue(_Queued(c, here, self._at(c, w_end, end), direction=(px - cx, py - cy),
                             checked=False))
        self.first = False
        self.prog = (px, py)

    def _arc1(self, c: Arc, here: Vec6, w_end: Vec6, r: float, left: bool) -> Iterator[Command]:
        cx, cy = self._xy(c, here)
        ex, ey = self._xy(c, w_end)
        center = self._xy(c, add_offsets(c.center, c.frame))
        ccw = c.turns > 0
        if math.hypot(ex - cx, ey - cy) <= r:
            self._fail(c, "Radius of cutter compensation entry arc is not greater than the tool radius")
        inside = left == ccw
        if inside and math.hypot(center[0] - ex, center[1] - ey) <= r:
            self._fail(c, "Tool radius not less than arc radius with comp", dg.COMP_ARC_TOO_SMALL)
        if inside:
            gamma = math.atan2(center[1] - ey, center[0] - ex)
        else:
            gamma = math.atan2(ey - center[1], ex - center[0])
        self.prog = (ex, ey)
        ex, ey = ex + r * math.cos(gamma), ey + r * math.sin(gamma)
        b_len = math.hypot(cy - ey, cx - ex) / 2.0
        ab = math.atan2(center[1] - ey, center[0] - ex)
        a_ang = math.atan2(cy - ey, cx - ex) - ab
        if abs(math.cos(a_ang)) < 1e-4:
            self._fail(c, "Tool radius not less than arc radius with comp", dg.COMP_ARC_TOO_SMALL)
        c_len = b_len / math.cos(a_ang)
        new_center = (ex + c_len * math.cos(ab), ey + c_len * math.sin(ab))
        yield from self.flush()
        self.endpoint = None
        turn = c.turns
        self._enqueue(_Queued(c, here, self._at(c, w_end, (ex, ey)), new_center, turn,
                              sweep=_turn_angle((cx, cy), new_center, turn, (ex, ey))))
        self.first = False

    # ---- later moves
    def _straight2(self, c: Rapid | Linear) -> Iterator[Command]:
        r, left = c.frame.comp_radius_mm, c.frame.comp_side is CompSide.LEFT
        here = self._here(c)
        cx, cy = self._xy(c, here)
        opx, opy = self.prog
        w_end = add_offsets(c.end, c.frame)
        px, py = self._xy(c, w_end)
        if (px, py) == (opx, opy):  # no motion in the plane: the tool keeps its plane point
            self._enqueue(_Queued(c, here, self._at(c, w_end, (cx, cy))))
            return
        theta = math.atan2(cy - opy, cx - opx)
        alpha = math.atan2(py - opy, px - opx)
        if left:
            if theta < alpha:
                theta += 2 * math.pi
            beta, gamma = theta - alpha - HALF_PI, HALF_PI
        else:
            if alpha < theta:
                alpha += 2 * math.pi
            beta, gamma = alpha - theta - HALF_PI, -HALF_PI
        end = (px + r * math.cos(alpha + gamma), py + r * math.sin(alpha + gamma))
        mid = (opx + r * math.cos(alpha + gamma), opy + r * math.sin(alpha + gamma))
        front = self.queue[0] if self.queue else None
        concave = beta < -SMALL or beta > math.pi + SMALL or (
            beta > math.pi - SMALL and front is not None and front.center is not None
            and ((not left and front.turn > 0) or (left and front.turn < 0)))
        start: Pt = (cx, cy)
        if concave:
            if front is None or front.center is None:
                half = (beta + math.pi) / 2.0
                if half == 0.0:
                    self._fail(c, "Zero degree inside corner is invalid for cutter compensation")
                back = r / math.tan(half)
                start = (cx + back * math.cos(theta + gamma), cy + back * math.sin(theta + gamma))
            else:
                rad = math.hypot(front.end[c.frame.plane.first] - front.center[0],
                                 front.end[c.frame.plane.second] - front.center[1])
                x = _behind(_line_circle(mid, (px - opx, py - opy), front.center, rad), front, _plane(c))
                if x is None:
                    self._fail(c, "Arc to straight motion makes a corner the compensated tool can't fit in "
                                  "without gouging", dg.COMP_NO_INTERSECTION)
                    return
                start = x
            yield from self._move_endpoint_and_flush(c, start)
            self.endpoint = start  # rs274's dequeue: the end of the last move it flushed
        elif beta > SMALL:  # outside corner: an arc about the programmed corner
            yield from self._corner_arc(c, here, mid, (cx, cy), (opx, opy), left)
            start = self.endpoint = mid
        else:
            yield from self.flush()
            self.endpoint = (cx, cy)  # rs274: the tool's point before an inside or tangent corner
        s = self._at(c, self._here(c), start)
        self._enqueue(_Queued(c, s, self._at(c, w_end, end), direction=(px - opx, py - opy)))
        self.prog = (px, py)

    def _arc2(self, c: Arc) -> Iterator[Command]:
        r, left = c.frame.comp_radius_mm, c.frame.comp_side is CompSide.LEFT
        here = self._here(c)
        cx, cy = self._xy(c, here)
        opx, opy = self.prog
        w_end = add_offsets(c.end, c.frame)
        ex, ey = self._xy(c, w_end)
        center = self._xy(c, add_offsets(c.center, c.frame))
        ccw = c.turns > 0
        arc_radius = math.hypot(center[0] - ex, center[1] - ey)
        theta = math.atan2(cy - opy, cx - opx)
        theta = theta - HALF_PI if left else theta + HALF_PI
        delta = math.atan2(center[1] - opy, center[0] - opx)
        alpha = delta - HALF_PI if ccw else delta + HALF_PI
        beta = theta - alpha if left else alpha - theta
        if beta > 1.5 * math.pi:
            beta -= 2 * math.pi
        elif beta < -HALF_PI:
            beta += 2 * math.pi
        inside = left == ccw
        if inside:
            gamma = math.atan2(center[1] - ey, center[0] - ex)
            if arc_radius <= r:
                self._fail(c, "Tool radius not less than arc radius with comp", dg.COMP_ARC_TOO_SMALL)
        else:
            gamma = math.atan2(ey - center[1], ex - center[0])
            delta += math.pi
        new_end = (ex + r * math.cos(gamma), ey + r * math.sin(gamma))
        start_radius = math.hypot(center[0] - opx, center[1] - opy)
        offset_radius = start_radius - r if inside else start_radius + r  # inside corners meet it from the start
        front = self.queue[0] if self.queue else None
        start: Pt = (cx, cy)
        if beta < -SMALL or beta > math.pi + SMALL or (abs(beta - math.pi) < SMALL and not inside):
            if front is None or front.center is None:
                d = (math.cos(theta), math.sin(theta)) if front is None else front.direction
                pts = _line_circle((cx, cy), d, center, offset_radius)
                what = "Straight to arc"
            else:
                i, j = c.frame.plane.first, c.frame.plane.second
                rad = math.hypot(front.end[i] - front.center[0], front.end[j] - front.center[1])
                # arc to arc: rs274 meets the new arc's offset circle by its end radius (a line: by its start)
                pts = _circle_circle(front.center, rad, center, arc_radius - r if inside else arc_radius + r)
                what = "Arc to arc"
            x = _behind(pts, front, _plane(c)) if front is not None else None
            if x is None:
                self._fail(c, f"{what} motion makes a corner the compensated tool can't fit in without gouging")
                return
            start = x
            yield from self._move_endpoint_and_flush(c, start)
            self.endpoint = (cx, cy)
        elif beta > SMALL:  # outside corner: an arc about the programmed corner
            mid = (opx + r * math.cos(delta), opy + r * math.sin(delta))
            yield from self._corner_arc(c, here, mid, (cx, cy), (opx, opy), left)
            start = self.endpoint = mid
        else:
            yield from self.flush()
            self.endpoint = (cx, cy)  # rs274: the tool's point before an inside or tangent corner
        s = self._at(c, self._here(c), start)
        self._enqueue(_Queued(c, s, self._at(c, w_end, new_end), center, c.turns,
                              sweep=_turn_angle(start, center, c.turns, new_end)))
        self.prog = (ex, ey)
