"""The profile segments of LinuxCNC's lathe cycles (a port of LinuxCNC 2.9's ``interp_g7x.cc``).

Points are complex numbers ``z + x*1j`` in program units.  A :class:`Segment` is a
:class:`Straight` or a :class:`Round` (an arc; :class:`Fillet` and :class:`Chamfer` are the
A/C corners, fitted between their neighbours by ``do_finish``); each knows where a level
``x`` meets it, how to offset itself, how to meet the next segment, and the dive/climb
steps of the roughing loop (:mod:`cncc.frontend.linuxcnc.g7x_path`).  The arithmetic keeps
LinuxCNC's order of operations: a profile's offset side can hang on the last bit.
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass
from typing import Protocol

TOLERANCE = 1e-6
_NAN = complex(math.nan, math.nan)


class ProfileError(Exception):
    """The profile cannot be cut (LinuxCNC's ``G7X error: ...`` texts)."""


class Motion(Protocol):
    def straight_move(self, end: complex) -> None: ...
    def straight_rapid(self, end: complex) -> None: ...
    def circular_move(self, ccw: bool, center: complex, end: complex) -> None: ...


def div(a: complex, b: complex) -> complex:
    return a / b if b != 0 else _NAN


def _unit(v: complex) -> complex:
    return div(v, abs(v))


@dataclass(slots=True)
class Cursor:
    """The tool position the dive/climb steps move (LinuxCNC passes it by reference)."""

    at: complex


@dataclass(slots=True)
class Segment:
    start: complex
    end: complex
    finish: float = 0.0

    # --- shared
    def monotonic(self) -> bool:
        return (self.end - self.start).real <= 1e-3

    def do_finish(self, prev: Segment, nxt: Segment) -> None:
        return None

    def flip_imag(self) -> None:
        self.start, self.end = self.start.conjugate(), self.end.conjugate()

    def flip_real(self) -> None:
        self.start, self.end = -self.start.conjugate(), -self.end.conjugate()

    def rotate(self) -> None:
        self.start, self.end = -self.start * 1j, -self.end * 1j

    def move(self, d: complex) -> None:
        self.start += d
        self.end += d

    def dup(self) -> Segment:
        return copy.copy(self)

    def corner_finish(self, prev: Segment, nxt: Segment) -> complex:
        p, n = prev.dup(), nxt.dup()
        p.offset(self.finish)
        n.offset(self.finish)
        if (p.end - n.start).real > 1e-2:
            self.finish = -self.finish
            p, n = prev.dup(), nxt.dup()
            p.offset(self.finish)
            n.offset(self.finish)
        if (p.end - n.start).real > 1e-2:
            raise ProfileError(f"Corner finish failed at {_fmt(prev.end)}")
        p.intersect(n)
        center = (p.end + n.start) / 2.0
        p.offset(-self.finish)
        n.offset(-self.finish)
        self.start = prev.end = p.end
        self.end = nxt.start = n.start
        return center

    # --- per kind
    def intersection_z(self, x: float) -> list[float]:
        raise NotImplementedError

    def climb(self, loc: Cursor, out: Motion) -> bool:
        raise NotImplementedError

    def dive(self, loc: Cursor, x: float, out: Motion, fast: bool) -> bool:
        raise NotImplementedError

    def climb_only(self, loc: Cursor, out: Motion) -> None:
        raise NotImplementedError

    def draw(self, out: Motion) -> None:
        raise NotImplementedError

    def offset(self, distance: float) -> None:
        raise NotImplementedError

    def intersect(self, nxt: Segment) -> None:
        """Move the end of ``self`` and the start of ``nxt`` to where the two meet."""
        raise NotImplementedError

    def radius(self) -> float:
        raise NotImplementedError


def _fmt(p: complex) -> str:
    return f"({p.real:g},{p.imag:g})"


@dataclass(slots=True)
class Straight(Segment):
    def intersection_z(self, x: float) -> list[float]:
        s, e = self.start, self.end
        if min(s.imag, e.imag) > x + TOLERANCE or max(s.imag, e.imag) < x - TOLERANCE:
            return []
        if abs((s - e).imag) < TOLERANCE:
            return [s.real, e.real]
        return [(x - s.imag) / (e.imag - s.imag) * (e.real - s.real) + s.real]

    def climb(self, loc: Cursor, out: Motion) -> bool:
        if self.end.imag + TOLERANCE < self.start.imag:
            return True  # not climbing
        if abs(loc.at - self.start) > TOLERANCE:
            raise ProfileError("How did we get here?")
        out.straight_move(self.end)
        loc.at = self.end
        return False

    def climb_only(self, loc: Cursor, out: Motion) -> None:
        if self.end.imag < self.start.imag:
            return
        hits = self.intersection_z(loc.at.imag)
        if not hits:
            return
        loc.at = complex(hits[0], loc.at.imag)
        out.straight_move(loc.at)
        out.straight_move(self.end)
        loc.at = self.end

    def dive(self, loc: Cursor, x: float, out: Motion, fast: bool) -> bool:
        if self.start.imag <= self.end.imag + TOLERANCE:
            return True  # not a diving segment
        move = out.straight_rapid if fast else out.straight_move
        if x < self.end.imag:
            move(self.end)
            loc.at = self.end
            return False
        hits = self.intersection_z(x)
        if not hits:
            raise ProfileError("x too large in straight dive")
        ep = complex(hits[0], x)
        move(ep)
        loc.at = ep
        return False

    def draw(self, out: Motion) -> None:
        out.straight_move(self.end)

    def offset(self, distance: float) -> None:
        v = self.start - self.end
        d = div(1j * distance * v, abs(v))  # LinuxCNC's order of rounding
        self.start += d
        self.end += d

    def intersect(self, nxt: Segment) -> None:
        if isinstance(nxt, Round):
            _line_then_arc(self, nxt)
        else:
            _line_then_line(self, nxt)

    def radius(self) -> float:
        return abs(self.start - self.end)


@dataclass(slots=True)
class Round(Segment):
    ccw: bool = False
    center: complex = 0j

    def flip_imag(self) -> None:
        self.ccw = not self.ccw
        self.start, self.end, self.center = self.start.conjugate(), self.end.conjugate(), self.center.conjugate()

    def flip_real(self) -> None:
        self.ccw = not self.ccw
        self.start, self.end = -self.start.conjugate(), -self.end.conjugate()
        self.center = -self.center.conjugate()

    def rotate(self) -> None:
        self.start, self.end, self.center = -self.start * 1j, -self.end * 1j, -self.center * 1j

    def move(self, d: complex) -> None:
        self.start += d
        self.end += d
        self.center += d

    def monotonic(self) -> bool:
        if self.finish != 0:
            return True
        entry = (self.start - self.center).imag
        leave = (self.end - self.center).imag
        dz = (self.end - self.start).real
        if self.ccw:
            return entry >= -1e-3 and leave >= -1e-3 and dz <= -1e-3
        return entry <= 1e-3 and leave <= 1e-3 and dz <= -1e-3

    def _on_segment(self, p: complex) -> bool:
        a = ((self.start - self.center).conjugate() * (p - self.center)).imag
        b = ((self.end - self.center).conjugate() * (p - self.center)).imag
        if self.ccw:
            return a >= -TOLERANCE and b <= TOLERANCE
        return a <= TOLERANCE and b >= -TOLERANCE

    def intersection_z(self, x: float) -> list[float]:
        r = abs(self.start - self.center)
        c = self.center
        s = -(x - r - c.imag) * (x + r - c.imag)
        if s < -TOLERANCE:
            return []
        s = math.sqrt(max(s, 0.0))
        hits = []
        for z in (c.real + s, c.real - s):
            if self._on_segment(complex(z, x)):
                hits.append(z)
        return hits

    def _top(self) -> complex:
        """The end of a G3 climb: the end, or the arc's top when the end lies past the centre."""
        if self.end.real < self.center.real:
            return complex(self.center.real, self.center.imag + abs(self.start - self.center))
        return self.end

    def climb(self, loc: Cursor, out: Motion) -> bool:
        if not self.ccw:  # G2
            if loc.at.real > self.center.real:
                return True
            if abs(loc.at - self.end) > 1e-3:
                out.circular_move(self.ccw, self.center, self.end)
            loc.at = self.end
            return False
        if loc.at.real < self.center.real:
            return True
        ep = self._top()
        if abs(loc.at - ep) > 1e-3:
            out.circular_move(self.ccw, self.center, ep)
        loc.at = ep
        return True

    def dive(self, loc: Cursor, x: float, out: Motion, fast: bool) -> bool:
        if abs(loc.at - self.end) < TOLERANCE or (loc.at - self.end).real <= TOLERANCE:
            loc.at = self.end
            return False
        hits = self.intersection_z(x) or self.intersection_z(x - TOLERANCE)
        if self.ccw:  # G3
            if loc.at.real - TOLERANCE > self.center.real:
                return True
            if not hits or hits[-1] > self.center.real:
                out.circular_move(self.ccw, self.center, self.end)
                loc.at = self.end
                return False
            ep = complex(hits[-1], x)
            out.circular_move(self.ccw, self.center, ep)
            loc.at = ep
            return False
        if loc.at.real <= self.center.real:
            return True  # already climbing
        if not hits:
            out.circular_move(self.ccw, self.center, self.end)
            loc.at = self.end
            return False
        if hits[0] < self.center.real:
            return False  # the back side only: the pocket lowers x
        ep = complex(hits[0], x)
        out.circular_move(self.ccw, self.center, ep)
        loc.at = ep
        return False

    def climb_only(self, loc: Cursor, out: Motion) -> None:
        hits = self.intersection_z(loc.at.imag)
        if not hits:
            return
        if not self.ccw:
            if hits[-1] > self.center.real:
                return
            loc.at = complex(hits[-1], loc.at.imag)
            out.straight_move(loc.at)
            if abs(loc.at - self.end) > 1e-3:
                out.circular_move(self.ccw, self.center, self.end)
            loc.at = self.end
            return
        if hits[0] < self.center.real:
            return
        loc.at = complex(hits[0], loc.at.imag)
        out.straight_move(loc.at)
        ep = self._top()
        if abs(loc.at - ep) > 1e-3:
            out.circular_move(self.ccw, self.center, ep)
        loc.at = ep

    def draw(self, out: Motion) -> None:
        out.circular_move(self.ccw, self.center, self.end)

    def offset(self, distance: float) -> None:
        r = abs(self.start - self.center)
        factor = (r + (1 if self.ccw else -1) * distance) / r if r else math.nan
        self.start = factor * (self.start - self.center) + self.center
        self.end = factor * (self.end - self.center) + self.center

    def intersect(self, nxt: Segment) -> None:
        if isinstance(nxt, Round):
            _arc_then_arc(self, nxt)
        elif isinstance(nxt, Straight):
            _arc_then_line(self, nxt)

    def radius(self) -> float:
        return min(abs(self.start - self.end), abs(self.start - self.center))


@dataclass(slots=True)
class Fillet(Round):
    """An ``A`` corner: an arc of radius ``finish`` put in at the end point of a move."""

    def do_finish(self, prev: Segment, nxt: Segment) -> None:
        self.center = self.corner_finish(prev, nxt)
        self.ccw = (self.start - self.center).imag > 0 or (self.end - self.center).imag > 0
        self.finish = 0.0


@dataclass(slots=True)
class Chamfer(Straight):
    """A ``C`` corner: the chord of the fillet of the same size."""

    def do_finish(self, prev: Segment, nxt: Segment) -> None:
        self.corner_finish(prev, nxt)


def corner(kind: str, size: float, at: complex) -> Segment:
    seg: Segment = Fillet(at, at, size) if kind == "A" else Chamfer(at, at, size)
    return seg


# ---- intersections: the end of ``p`` and the start of ``s`` ---------------------------------
def _line_then_line(p: Straight, s: Segment) -> None:
    rot = _unit(s.start - s.end).conjugate()
    ps, pe = (p.start - s.end) * rot, (p.end - s.end) * rot
    if (ps - pe).imag == 0:
        raise ProfileError("Cannot intersect parallel lines")
    f = ps.imag / (ps - pe).imag
    hit = div(ps + f * (pe - ps), rot) + s.end
    s.start = p.end = hit


def _line_then_arc(p: Straight, s: Round) -> None:
    """A straight followed by an arc (LinuxCNC's round_segment::intersect_end(straight))."""
    if abs(s.start - p.end) < TOLERANCE:
        return
    rot = _unit(p.start - p.end).conjugate()
    pe, pc = (s.end - p.end) * rot, (s.center - p.end) * rot
    n = abs(pc - pe)
    b = n * n - pc.imag * pc.imag  # std::norm is |z| squared
    b = math.sqrt(b) if b >= 0 else 0.0
    s1, s2 = div(pc.real + b, rot) + p.end, div(pc.real - b, rot) + p.end
    s.start = p.end = s1 if abs(s.start - s1) < abs(s.start - s2) else s2


def _arc_then_line(p: Round, s: Straight) -> None:
    """An arc followed by a straight (LinuxCNC's straight_segment::intersect_end(round))."""
    if abs(s.start - p.end) < TOLERANCE:
        return
    rot = _unit(s.start - s.end).conjugate()
    pe, pc = (p.end - s.end) * rot, (p.center - s.end) * rot
    n = abs(pc - pe)
    b = n * n - pc.imag * pc.imag  # std::norm is |z| squared
    b = math.sqrt(b) if b >= 0 else 0.0
    s1, s2 = div(pc.real + b, rot) + s.end, div(pc.real - b, rot) + s.end
    s.start = p.end = s1 if abs(s.start - s1) < abs(s.start - s2) else s2


def _arc_then_arc(p: Round, s: Round) -> None:
    a = abs(s.start - s.center)
    b = abs(p.start - p.center)
    c = abs(s.center - p.center)
    cos_b = (c * c + a * a - b * b) / 2.0 / a / c if a and c else math.nan
    cos_b2 = min(cos_b * cos_b, 1.0)
    rot = complex(cos_b, math.sqrt(1 - cos_b2)) if not math.isnan(cos_b2) else _NAN
    hit = div(rot * (p.center - s.center), c) * a + s.center  # LinuxCNC's order of rounding
    p.end = s.start = hit


