"""``cutter-comp``: G41/G42 cutter radius compensation (type C, Fanuc family).

Consumes commands whose frames carry ``comp_side``/``comp_radius_mm`` (already
scaled, mirrored and rotated: the mirror pass has swapped the side where it must);
produces the tool-centre path, with frames whose compensation is off.

* **Start-up** (first G00/G01 move in the plane after G41/G42): from the
  uncompensated start to the programmed end moved by r square to the *next* element
  (type A).  Start-up on an arc is an error.
* **Offset mode**: each element is offset by r to the tool side (arcs keep their
  centre; radius R - r on the centre side, R + r outside).  At a corner the offset
  elements are cut at their intersection when the corner is inside; outside, the
  intersection is used up to a 90 degree turn and the acute corner gets two
  extensions of length r joined by a line (``outer_corner="intersection"``), or an
  arc of radius r about the corner (``outer_corner="arc"``); with ``outer_arc_below_deg``
  set, an arc only where the included angle is below it and the intersection at every
  other outside corner (SERIES 8's 70 degree rule, spec A-16).  Outside corners whose
  offset curves do not meet (two arcs) get the arc, with a warning.
* **Look-ahead**: blocks without motion in the plane (a Z move, G43, M codes) are
  held back until the next element settles the corner, up to ``lookahead`` moves;
  past that the vector is taken square to the last element (a warning: over- or
  undercut, as the controllers do).
* **Cancel** (first move in the plane after G40): from the offset point of the last
  element, square to it, to the programmed end point.
* **Interference**: an inside arc smaller than r, an inside corner whose offset
  elements do not meet, and an offset element that runs against its programmed
  direction (a notch narrower than the tool, a step lower than r) are errors at the
  offending block with the neighbouring block as related location.  The path is
  still produced so that it can be looked at.

Geometry lives in :mod:`cncc.passes.comp_geometry`; the corner rules and the
reasons for them in ``docs/cutter-comp.md``.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field, replace
from typing import ClassVar

from cncc import diagnostics as dg
from cncc.diagnostics import Related
from cncc.ir import ZERO6, Arc, Command, CompSide, Cycle, Frame, Linear, OriginKind, Plane, Rapid, Vec6, with_ends
from cncc.ir.batch import Item, MoveBatch, expand, rebatch
from cncc.ir.frame import add_offsets, sub_offsets
from cncc.passes import Pass, PassContext, register
from cncc.passes.comp_geometry import (
    EPS,
    Element,
    Pt,
    add,
    arc_sweep,
    cross,
    dot,
    nearest,
    norm,
    offset_intersections,
    sub,
)

Motion = Rapid | Linear | Arc
_MOTIONS = (Rapid, Linear, Arc)


def _off(f: Frame) -> bool:
    return f.comp_side is CompSide.OFF and f.comp_radius_mm == 0.0


@register
@dataclass(frozen=True, kw_only=True)
class CutterComp(Pass):
    """G41/G42 path offset with interference check."""

    name: ClassVar[str] = "cutter-comp"
    outer_corner: str = "intersection"  # or "arc": an arc about every outside corner
    outer_arc_below_deg: float = 0.0  # > 0: an arc where the included angle is below it, else the intersection
    lookahead: int = 2  # moves without plane motion looked through for the next corner
    gouge_check: bool = True
    startup: str = "type_a"  # or "perpendicular": square off the start point, then the first element (SERIES 8)
    # or "end_normal" (LinuxCNC): the entry move ends square to itself; the next corner is joined as usual

    def run(self, cmds: Iterable[Command], ctx: PassContext) -> Iterator[Command]:
        return expand(self.run_items(cmds, ctx))

    def run_items(self, items: Iterable[Item], ctx: PassContext) -> Iterator[Item]:
        # the moves made one by one are handed on as batches again (the stages after keep their fast paths)
        if not ctx.batches:
            return self._items(items, ctx)
        return rebatch(self._items(items, ctx), ctx.sink)

    def _items(self, items: Iterable[Item], ctx: PassContext) -> Iterator[Item]:
        comp = _Comp(self, ctx)
        # Fast path while compensation is off and nothing is pending: a motion (or a batch of
        # moves) in an uncompensated frame that starts where the previous one (passed through
        # unchanged, same frame object) ended is passed through as is; ``comp.last`` is
        # materialised when the fast path ends.
        t_frame: Frame | None = None  # frame and end of the last motion passed through
        t_end: Vec6 = ZERO6
        for x in items:
            if isinstance(x, MoveBatch):
                if x.passes_whole and t_frame is not None and x.frame is t_frame and x.start0 == t_end:
                    t_end = x.last_end
                    yield x
                    continue
                if (x.passes_whole and t_frame is None and comp.pending is None and comp.last is None
                        and not comp.was_on and _off(x.frame)):
                    t_frame, t_end = x.frame, x.last_end
                    yield x
                    continue
                cmds: Iterable[Command] = x.commands()
            else:
                cmds = (x,)
            for c in cmds:
                if t_frame is not None:
                    if c.frame is t_frame and isinstance(c, _MOTIONS) and c.start == t_end:
                        t_end = c.end
                        yield c
                        continue
                    comp.last = add_offsets(t_end, t_frame)
                    t_frame = None
                if (comp.pending is None and comp.last is None and not comp.was_on and isinstance(c, _MOTIONS)
                        and _off(c.frame)):
                    t_frame, t_end = c.frame, c.end
                    yield c
                    continue
                yield from comp.feed(c)
                if (comp.pending is None and not comp.was_on and isinstance(c, _MOTIONS) and _off(c.frame)
                        and comp.last is not None and comp.last == add_offsets(c.end, c.frame)):
                    t_frame, t_end = c.frame, c.end
        yield from comp.finish()


@dataclass(slots=True)
class _Pending:
    el: Element
    cmd: Motion
    plane: Plane
    startup: bool
    neighbours: list[Related] = field(default_factory=list)  # the blocks whose corners trimmed it


def _with_plane(p: Vec6, plane: Plane, q: Pt) -> Vec6:
    if plane is Plane.XY:
        return (q[0], q[1], p[2], p[3], p[4], p[5])
    out = list(p)
    out[plane.first], out[plane.second] = q
    return (out[0], out[1], out[2], out[3], out[4], out[5])


def _suspends(c: Command) -> bool:
    """Moves in machine terms (G53, reference returns) and unexpanded cycles run uncompensated."""
    if isinstance(c, Rapid | Linear | Arc):
        return c.origin.kind in (OriginKind.MACHINE, OriginKind.HOME, OriginKind.REFERENCE)
    return hasattr(c, "holes")


@dataclass(slots=True)
class _Comp:
    opts: CutterComp
    ctx: PassContext
    last: Vec6 | None = None  # actual end of the last output motion (program + offsets)
    pending: _Pending | None = None
    held: list[Command] = field(default_factory=list)
    held_moves: int = 0
    was_on: bool = False  # the last move in the plane was compensated
    frames: dict[int, tuple[Frame, Frame]] = field(default_factory=dict)

    # ---- entry points
    def feed(self, c: Command) -> Iterator[Command]:
        if not isinstance(c, Rapid | Linear | Arc) or _suspends(c):
            if _suspends(c):
                yield from self._flush_square()
                self.was_on = False
            if self.pending is not None:
                self.held.append(c)
            else:
                yield from self._plain(c)
            return
        f = c.frame
        on = f.comp_side is not CompSide.OFF
        if on and self.pending is not None and f.plane is not self.pending.plane:
            self.ctx.sink.emit(dg.COMP_PLANE_CHANGE, c.span, "the plane changed while cutter compensation is on",
                               (Related(self.pending.cmd.span, "compensation was active here"),))
            on = False
        if not self._moves_in_plane(c):
            if self.pending is not None:
                self.held.append(c)
                self.held_moves += 1
                if self.held_moves > self.opts.lookahead:
                    self.ctx.sink.emit(dg.COMP_LOOKAHEAD, c.span,
                                       f"more than {self.opts.lookahead} moves without motion in the plane during "
                                       "compensation: the offset vector is set square to the last element",
                                       (Related(self.pending.cmd.span, "last element in the plane"),))
                    yield from self._flush_square()
            else:
                yield from self._plain(c)
            return
        if on:
            yield from self._element(c)
        else:
            yield from self._flush_square()
            if self.was_on and isinstance(c, Arc):
                self.ctx.sink.emit(dg.COMP_ON_ARC, c.span, "cutter compensation cannot be cancelled on an arc")
            self.was_on = False
            yield from self._plain(c)

    def finish(self) -> Iterator[Command]:
        yield from self._flush_square()

    # ---- helpers
    def _frame(self, f: Frame) -> Frame:
        entry = self.frames.get(id(f))
        if entry is None or entry[0] is not f:
            nf = f if f.comp_side is CompSide.OFF and f.comp_radius_mm == 0.0 else replace(
                f, comp_side=CompSide.OFF, comp_radius_mm=0.0)
            entry = self.frames[id(f)] = (f, nf)
        return entry[1]

    def _moves_in_plane(self, c: Motion) -> bool:
        if isinstance(c, Arc):
            return True
        i, j = c.frame.plane.first, c.frame.plane.second
        return abs(c.end[i] - c.start[i]) > EPS or abs(c.end[j] - c.start[j]) > EPS

    def _start(self, c: Motion, nf: Frame) -> Vec6:
        return c.start if self.last is None else sub_offsets(self.last, nf)

    def _plain(self, c: Command, plane_end: Pt | None = None, plane: Plane | None = None) -> Iterator[Command]:
        """Emit ``c`` uncompensated, starting where the tool is (optionally ending at ``plane_end``)."""
        nf = self._frame(c.frame)
        if not isinstance(c, Rapid | Linear | Arc):
            if isinstance(c, Cycle):  # kept whole for the G-code backend: the tool ends at the last hole
                self.last = add_offsets(c.holes[-1], nf)
            yield c if nf is c.frame else replace(c, frame=nf)
            return
        start = self._start(c, nf)
        end = c.end
        if plane_end is not None and plane is not None:
            end = sub_offsets(_with_plane(add_offsets(c.end, c.frame), plane, plane_end), c.frame)
        self.last = add_offsets(end, nf)
        yield c if start == c.start and end == c.end and nf is c.frame else with_ends(c, nf, start, end)

    def _make(self, c: Motion) -> Element:
        f = c.frame
        plane = f.plane
        i, j = plane.first, plane.second
        b0, b1 = add_offsets(c.start, f), add_offsets(c.end, f)
        side = 1.0 if f.comp_side is CompSide.LEFT else -1.0
        el = Element((b0[i], b0[j]), (b1[i], b1[j]), side, f.comp_radius_mm)
        if isinstance(c, Arc):
            bc = add_offsets(c.center, f)
            el.center = (bc[i], bc[j])
            el.ccw = c.turns > 0
            el.sweep = arc_sweep(el.p0, el.p1, el.center, el.ccw, c.turns)
            if el.offset_radius < -1e-7:
                self.ctx.sink.emit(dg.COMP_ARC_TOO_SMALL, c.span,
                                   f"arc radius {el.radius:.4f} mm is smaller than the tool radius "
                                   f"{el.r:.4f} mm on the inside: the tool cannot follow it")
        el.q0, el.q1 = el.normal_point(False), el.normal_point(True)
        return el

    # ---- elements and corners
    def _element(self, c: Motion) -> Iterator[Command]:
        el = self._make(c)
        p = self.pending
        if p is None:
            if self.was_on:  # continuing after the look-ahead ran out: jump to the new vector
                yield from self._connect(c, el.q0)
            elif self.opts.startup == "perpendicular" and not isinstance(c, Arc):
                if self.last is None:
                    self.last = add_offsets(c.start, c.frame)
                yield from self._connect(c, el.q0)  # square off the start point; the element is cut whole
                self.pending = _Pending(el, c, c.frame.plane, startup=False)
                self.was_on = True
                return
            else:
                if isinstance(c, Arc):
                    self.ctx.sink.emit(dg.COMP_ON_ARC, c.span, "cutter compensation cannot start on an arc; "
                                                               "program a G00/G01 start-up move")
                cur = self.last if self.last is not None else add_offsets(c.start, c.frame)
                el.q0 = (cur[c.frame.plane.first], cur[c.frame.plane.second])
            self.pending = _Pending(el, c, c.frame.plane, startup=not self.was_on)
            self.was_on = True
            return
        connectors = self._corner(p, el, c)
        p.neighbours.append(Related(c.span, "the next block"))
        yield from self._emit_pending(connectors)
        self.pending = _Pending(el, c, c.frame.plane, False, [Related(p.cmd.span, "the previous block")])

    def _corner(self, p: _Pending, b: Element, bc: Motion) -> list[Pt]:
        """Settle the corner between the pending element and ``b``; return connector points."""
        a = p.el
        if p.startup and self.opts.startup != "end_normal":  # type A start-up: square to the next element
            a.q1 = b.q0
            return []
        if norm(sub(a.p1, b.p0)) > 1e-6 or a.side != b.side or abs(a.r - b.r) > 1e-12:
            a.q1 = a.normal_point(True)  # a jump, a side or radius change: square vectors, joined
            return [b.q0]
        ta, tb = a.tangent(True), b.tangent(False)
        theta = math.atan2(cross(ta, tb), dot(ta, tb))
        a_end, b_start = a.q1, b.q0
        if abs(theta) < 1e-9 or norm(sub(a_end, b_start)) < 1e-9:
            b.q0 = a.q1 = a_end
            return []
        related = (Related(p.cmd.span, "the corner with this block"),)
        if a.side * theta > 0 and abs(theta) < math.pi - 1e-9:  # inside corner
            x = nearest(offset_intersections(a, b), a.p1)
            if x is None:
                self.ctx.sink.emit(dg.COMP_NO_INTERSECTION, bc.span,
                                   "the offset paths of this block and the previous one do not meet: the tool "
                                   "does not fit into this corner", related)
                return [b_start]
            a.q1 = b.q0 = x
            return []
        return self._outer(a, b, bc, theta, related)

    def _outer(self, a: Element, b: Element, bc: Motion, theta: float, related: tuple[Related, ...]) -> list[Pt]:
        corner = a.p1
        arc = self.opts.outer_corner == "arc"
        meet = not arc and abs(theta) <= math.pi / 2 + 1e-9
        if self.opts.outer_arc_below_deg > 0:  # SERIES 8 A-16: an arc only at corners sharper than the limit
            arc = 180.0 - math.degrees(abs(theta)) < self.opts.outer_arc_below_deg
            meet = not arc
        if meet:
            limit = 2.0 * a.r / max(math.cos(abs(theta) / 2), 1e-6)
            x = nearest(offset_intersections(a, b), corner)
            if x is not None and norm(sub(x, corner)) <= limit:
                a.q1 = b.q0 = x
                return []
            self.ctx.sink.emit(dg.COMP_CORNER_ARC, bc.span,
                               "the offset paths of this block and the previous one do not meet at this outside "
                               "corner; the tool goes round the corner on an arc", related)
        elif not arc:
            e1 = add(a.q1, a.tangent(True), a.r)
            e2 = add(b.q0, b.tangent(False), -b.r)
            return [e1, e2, b.q0]
        return [_ARC_MARK, b.q0]

    # ---- output
    def _emit_pending(self, connectors: list[Pt]) -> Iterator[Command]:
        p = self.pending
        assert p is not None
        self.pending = None
        a, c = p.el, p.cmd
        if not p.startup and self.opts.gouge_check and a.reversed_offset():
            self.ctx.sink.emit(dg.COMP_GOUGE, c.span,
                               f"interference: with a tool radius of {a.r:.4f} mm the offset path of this block runs "
                               "backwards (a notch narrower than the tool or a step lower than its radius)",
                               tuple(p.neighbours))
        yield from self._offset_command(p)
        arc_next = False
        for q in connectors:
            if q is _ARC_MARK:
                arc_next = True
                continue
            yield from self._connector(c, q, p.plane, a.p1 if arc_next else None, a.side)
            arc_next = False
        held, self.held, self.held_moves = self.held, [], 0
        for h in held:
            if isinstance(h, Rapid | Linear | Arc) and not _suspends(h):
                cur = self.last
                assert cur is not None
                yield from self._plain(h, (cur[p.plane.first], cur[p.plane.second]), p.plane)
            else:
                yield from self._plain(h)

    def _offset_command(self, p: _Pending) -> Iterator[Command]:
        a, c = p.el, p.cmd
        nf = self._frame(c.frame)
        base = self.last if self.last is not None else add_offsets(c.start, c.frame)
        start = sub_offsets(_with_plane(base, p.plane, a.q0), nf)
        end = sub_offsets(_with_plane(add_offsets(c.end, c.frame), p.plane, a.q1), nf)
        self.last = add_offsets(end, nf)
        if isinstance(c, Rapid):
            yield Rapid(c.span, nf, start, end, c.motion, c.origin)
        elif isinstance(c, Linear) or a.center is None:
            feed = c.feed_mm_min
            yield Linear(c.span, nf, start, end, feed, c.motion, c.origin)
        elif a.offset_radius <= 1e-7:  # the tool sits on the centre: only the normal axis moves
            if start != end:
                yield Linear(c.span, nf, start, end, c.feed_mm_min, c.motion, c.origin)
        else:
            turns = c.turns
            sweep = a.offset_sweep()
            full = int(abs(sweep) // (2 * math.pi + 1e-9))
            if full and norm(sub(a.q0, a.q1)) > 1e-9:
                turns = (full + 1) * (1 if turns > 0 else -1)
            center = sub_offsets(_with_plane(add_offsets(c.center, c.frame), p.plane, a.center), nf)
            yield Arc(c.span, nf, start, end, center, turns, c.plane, c.feed_mm_min, c.motion, c.origin)

    def _connector(self, c: Motion, q: Pt, plane: Plane, arc_center: Pt | None, side: float) -> Iterator[Command]:
        nf = self._frame(c.frame)
        assert self.last is not None
        start = sub_offsets(self.last, nf)
        end = sub_offsets(_with_plane(self.last, plane, q), nf)
        self.last = add_offsets(end, nf)
        if norm(sub((start[plane.first], start[plane.second]), q)) < 1e-9:
            return
        if arc_center is not None and not isinstance(c, Rapid):
            center = sub_offsets(_with_plane(self.last, plane, arc_center), nf)
            turns = -1 if side > 0 else 1  # around an outside corner the tool turns against its side
            yield Arc(c.span, nf, start, end, center, turns, plane, c.feed_mm_min, c.motion, c.origin)
        elif isinstance(c, Rapid):
            yield Rapid(c.span, nf, start, end, c.motion, c.origin)
        else:
            yield Linear(c.span, nf, start, end, c.feed_mm_min, c.motion, c.origin)

    def _connect(self, c: Motion, q: Pt) -> Iterator[Command]:
        yield from self._connector(c, q, c.frame.plane, None, 0.0)

    def _flush_square(self) -> Iterator[Command]:
        """End the pending element square to itself (cancel, end of program, look-ahead exhausted)."""
        p = self.pending
        if p is None:
            return
        p.el.q1 = p.el.normal_point(True)
        yield from self._emit_pending([])


_ARC_MARK: Pt = (math.nan, math.nan)
