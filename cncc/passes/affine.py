"""Shared machinery of the transform passes (``scaling``, ``mirror``, ``rotation``).

Consumes commands whose frames may carry the pass's transform record; produces the
same commands with the transform applied to their positions (program coordinates
of the same frame) and the record removed from the frame.

A transform maps a programmed point ``p`` to ``c + L (p - c)`` (``L`` a 3x3 matrix on
X Y Z; rotary axes are left alone).  Three rules keep the path what the controller
would cut:

* **continuity**: a move starts where the previous move actually ended, so the first
  move after G51 starts at the unscaled point and the first one after G50 at the
  scaled one (SYNTEC E000-33);
* **increments**: in G91 (``frame.incremental``) the increment is mapped,
  ``end' = start' + L (end - start)``, so a rotation turns it about the actual start
  (SZGH E002-19); in G90 the programmed point itself is mapped;
* **held axes**: after a cancel, axes in ``frame.held_axes`` (not named absolutely since)
  move by their programmed increment from where the tool actually is, so a block
  that does not name them leaves them where the transform put them;
* **bypass**: G53 moves and the second leg of G28/G30 (origin kind ``REFERENCE``) are in
  machine terms and are not transformed.

An arc's direction flips when ``L`` reverses orientation in the arc's plane; so does
the cutter-compensation side in the frame's plane.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field, replace
from typing import Any, ClassVar

from cncc import diagnostics as dg
from cncc.ir import ZERO6, Arc, Command, CompSide, Cycle, Frame, Linear, Plane, Rapid, Vec6
from cncc.ir.batch import Item, MoveBatch, expand
from cncc.ir.frame import add_offsets, sub_offsets
from cncc.passes import Pass, PassContext

Mat3 = tuple[tuple[float, float, float], tuple[float, float, float], tuple[float, float, float]]
IDENTITY3: Mat3 = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))


@dataclass(frozen=True, slots=True)
class Affine:
    """``p -> center + linear (p - center)`` on X Y Z."""

    center: tuple[float, float, float]
    linear: Mat3

    def vector(self, d: tuple[float, float, float]) -> tuple[float, float, float]:
        m = self.linear
        return (m[0][0] * d[0] + m[0][1] * d[1] + m[0][2] * d[2],
                m[1][0] * d[0] + m[1][1] * d[1] + m[1][2] * d[2],
                m[2][0] * d[0] + m[2][1] * d[1] + m[2][2] * d[2])

    def point(self, p: Vec6) -> Vec6:
        c = self.center
        x, y, z = self.vector((p[0] - c[0], p[1] - c[1], p[2] - c[2]))
        return (c[0] + x, c[1] + y, c[2] + z, p[3], p[4], p[5])

    def moved(self, start_out: Vec6, start_in: Vec6, p: Vec6) -> Vec6:
        """``start_out + L (p - start_in)``: an increment mapped from the actual start."""
        x, y, z = self.vector((p[0] - start_in[0], p[1] - start_in[1], p[2] - start_in[2]))
        return (start_out[0] + x, start_out[1] + y, start_out[2] + z,
                start_out[3] + p[3] - start_in[3], start_out[4] + p[4] - start_in[4],
                start_out[5] + p[5] - start_in[5])

    def det2(self, plane: Plane) -> float:
        """Determinant of ``L`` restricted to ``plane`` (negative: orientation reversed)."""
        i, j = plane.first, plane.second
        m = self.linear
        return m[i][i] * m[j][j] - m[i][j] * m[j][i]

    def keeps_plane(self, plane: Plane) -> bool:
        """True when ``L`` maps the plane to itself as a similarity (circles stay circles)."""
        i, j, n = plane.first, plane.second, plane.normal
        m = self.linear
        if abs(m[i][n]) > 1e-12 or abs(m[j][n]) > 1e-12 or abs(m[n][i]) > 1e-12 or abs(m[n][j]) > 1e-12:
            return False
        a, b, c, d = m[i][i], m[i][j], m[j][i], m[j][j]
        return abs(a * a + c * c - b * b - d * d) < 1e-9 and abs(a * b + c * d) < 1e-9


def _carried(held: tuple[bool, ...], start: Vec6, prog_start: Vec6, end: Vec6, center: Vec6) -> tuple[Vec6, Vec6]:
    """Held axes (``Frame.held_axes``) move by the programmed increment from where the tool is."""
    d = [start[k] - prog_start[k] if held[k] else 0.0 for k in range(6)]
    return ((end[0] + d[0], end[1] + d[1], end[2] + d[2], end[3] + d[3], end[4] + d[4], end[5] + d[5]),
            (center[0] + d[0], center[1] + d[1], center[2] + d[2], center[3] + d[3], center[4] + d[4],
             center[5] + d[5]))


def flip_side(side: CompSide) -> CompSide:
    if side is CompSide.LEFT:
        return CompSide.RIGHT
    if side is CompSide.RIGHT:
        return CompSide.LEFT
    return side


_MOTIONS = (Rapid, Linear, Arc)


@dataclass(slots=True)
class _Through:
    """The transform passes' run state: the actual end of the previous motion (program + offsets),
    and the frame and end of the last motion passed through unchanged (``last`` not yet made)."""

    last: Vec6 | None = None
    frame: Frame | None = None
    end: Vec6 = ZERO6
    cache: dict[int, tuple[Frame, Affine | None, Frame]] = field(default_factory=dict)

    def leave(self) -> None:
        """End the pass-through: make ``last``."""
        if self.frame is not None:
            self.last = add_offsets(self.end, self.frame)
            self.frame = None


@dataclass(frozen=True, kw_only=True)
class AffinePass(Pass):
    """Base of the transform passes; subclasses say which record they apply."""

    name: ClassVar[str] = ""

    def affine(self, frame: Frame) -> Affine | None:
        """The transform the frame asks this pass to apply (None: none)."""
        raise NotImplementedError

    def strip(self, frame: Frame, affine: Affine | None) -> Frame:
        """The frame once this pass has applied its transform."""
        raise NotImplementedError

    def bypasses(self, frame: Frame) -> bool:
        """G53 moves and home legs of this frame are in machine terms (not transformed)."""
        return True

    def run(self, cmds: Iterable[Command], ctx: PassContext) -> Iterator[Command]:
        return expand(self.run_items(cmds, ctx))

    def _entry(self, frame: Frame, cache: dict[int, tuple[Frame, Affine | None, Frame]]
               ) -> tuple[Frame, Affine | None, Frame]:
        entry = cache.get(id(frame))
        if entry is None or entry[0] is not frame:
            aff = self.affine(frame)
            entry = cache[id(frame)] = (frame, aff, self.strip(frame, aff))
        return entry

    def _batch(self, x: MoveBatch, st: _Through) -> MoveBatch | None:
        """``x`` passed through whole or mapped with array operations (``st`` updated); None: command
        by command."""
        frame = x.frame
        if x.passes_whole:  # else its commands one by one (the per-command fast path still applies)
            if st.frame is not None:
                if frame is st.frame and x.start0 == st.end:
                    st.end = x.last_end
                    return x
                st.leave()
            _, aff, nf = self._entry(frame, st.cache)
            if aff is None and nf is frame and (st.last is None or sub_offsets(st.last, frame) == x.start0):
                st.frame, st.end = frame, x.last_end  # as the first move would, the rest follow
                return x
        _, aff, nf = self._entry(frame, st.cache)
        if aff is None:
            return None
        st.leave()
        mapped = _mapped(x, aff, nf, st.last)
        if mapped is not None:
            st.last = add_offsets(mapped.last_end, nf)
        return mapped

    def run_items(self, items: Iterable[Item], ctx: PassContext) -> Iterator[Item]:
        # Fast path: once a motion went through unchanged (no transform in its frame), the
        # next motion (or batch of moves) in the same frame object that starts where it ended
        # goes through unchanged too, without per-command work; ``last`` is materialised on leaving.
        st = _Through()
        for x in items:
            if isinstance(x, MoveBatch):
                done = self._batch(x, st)
                if done is not None:
                    yield done
                    continue
                cmds: Iterable[Command] = x.commands()
            else:
                cmds = (x,)
            for c in cmds:
                frame = c.frame
                if st.frame is not None:
                    if frame is st.frame and isinstance(c, _MOTIONS) and c.start == st.end:
                        st.end = c.end
                        yield c
                        continue
                    st.leave()
                _, aff, nf = self._entry(frame, st.cache)
                if isinstance(c, Rapid | Linear | Arc):
                    out = self._motion(c, aff, nf, st.last, ctx)
                    st.last = add_offsets(out.end, nf)
                    if out is c and aff is None and nf is frame:
                        st.frame, st.end = frame, c.end
                    yield out
                elif isinstance(c, Cycle):  # kept whole for the G-code backend (untransformed frames only)
                    st.last = add_offsets(c.holes[-1], nf)
                    yield c if nf is frame else replace(c, frame=nf)
                else:
                    yield c if nf is frame else replace(c, frame=nf)

    def _motion(self, c: Rapid | Linear | Arc, aff: Affine | None, nf: Frame, last: Vec6 | None,
                ctx: PassContext) -> Rapid | Linear | Arc:
        start = c.start if last is None else sub_offsets(last, nf)
        bypass = aff is None or (c.origin.in_machine_terms and self.bypasses(c.frame))
        if bypass or aff is None:
            if start == c.start and nf is c.frame:
                return c
            end, center, turns = c.end, (c.center if isinstance(c, Arc) else c.end), 0
            if c.frame.after_cancel and start != c.start:
                end, center = _carried(c.frame.held_axes, start, c.start, end, center)
        elif c.frame.incremental:
            end = aff.moved(start, c.start, c.end)
            center = aff.moved(start, c.start, c.center) if isinstance(c, Arc) else end
            turns = 0
        else:
            end = aff.point(c.end)
            center = aff.point(c.center) if isinstance(c, Arc) else end
            turns = 0
        if isinstance(c, Rapid):
            return Rapid(c.span, nf, start, end, c.motion, c.origin)
        if isinstance(c, Linear):
            return Linear(c.span, nf, start, end, c.feed_mm_min, c.motion, c.origin)
        turns = c.turns
        if not bypass and aff is not None:
            if not aff.keeps_plane(c.plane):
                ctx.sink.emit(dg.SCALED_ARC_ELLIPSE, c.span,
                              f"{self.name}: this arc would not stay a circle in its plane; it is kept as a circle "
                              "through the mapped end points")
            if aff.det2(c.plane) < 0:
                turns = -turns
        return Arc(c.span, nf, start, end, center, turns, c.plane, c.feed_mm_min, c.motion, c.origin)


def _mapped(b: MoveBatch, aff: Affine, nf: Frame, last: Vec6 | None) -> MoveBatch | None:
    """The batch with ``aff`` applied to every end point and centre, as :meth:`AffinePass._motion`
    maps each move in G90; None where the command path must decide: G91, offsets in the new frame
    (a start re-derived from the offset end may differ in its last bits), a mapped ``-0.0`` (the
    re-derived start would be ``0.0``), an arc that would not stay a circle (a warning each)."""
    import numpy as np

    f = b.frame
    if f.incremental or nf.total_offset_mm != ZERO6 or (nf.rotation is not None and nf.rotation.work):
        return None
    arcs = bool((b.kind == 2).any())
    if arcs and not aff.keeps_plane(b.plane):
        return None
    c = aff.center
    m = aff.linear

    def point(p: np.ndarray[Any, Any]) -> np.ndarray[Any, Any]:
        d0, d1, d2 = p[:, 0] - c[0], p[:, 1] - c[1], p[:, 2] - c[2]
        out = p.copy()
        out[:, 0] = c[0] + (m[0][0] * d0 + m[0][1] * d1 + m[0][2] * d2)
        out[:, 1] = c[1] + (m[1][0] * d0 + m[1][1] * d1 + m[1][2] * d2)
        out[:, 2] = c[2] + (m[2][0] * d0 + m[2][1] * d1 + m[2][2] * d2)
        return out

    end = point(b.end)
    if bool(((end == 0.0) & np.signbit(end)).any()):
        return None
    center = point(b.center) if arcs else b.center
    start = b.start0 if last is None else sub_offsets(last, nf)
    turns = -b.turns if arcs and aff.det2(b.plane) < 0 else b.turns
    return b.with_(frame=nf, start0=start, end=end, center=center, turns=turns)


__all__ = ["IDENTITY3", "Affine", "AffinePass", "Mat3", "flip_side"]
