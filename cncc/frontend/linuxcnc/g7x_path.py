"""The profile geometry of LinuxCNC's lathe cycles G70 (finish), G71/G72 (rough).

A port of LinuxCNC 2.9's ``interp_g7x.cc`` (its ``segment``/``g7x`` classes), so that the
motion cncc lowers a cycle to is the motion ``rs274`` prints.  Points are complex numbers
``z + x*1j`` in program units (LinuxCNC works in the length unit in force); the profile is
turned and mirrored (``flip_state``) so that the cut always runs towards decreasing Z and X,
and every move is mapped back on output.

:class:`Path` takes the profile as a list of segments, the first one being the approach
from the cycle's start point to the first point of the profile; :meth:`Path.g70` and
:meth:`Path.g71` call the :class:`Motion` sink with the moves.  Geometric failures raise
:class:`ProfileError` with LinuxCNC's texts ("Not monotonic", ...).

One deliberate difference from 2.9 (``docs/dialects-notes.md``): where 2.9's roughing loop
makes no progress (a level where no segment of the profile is met, or an offset that never
reaches its distance) and so never ends, cncc stops with :class:`ProfileError`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from cncc.frontend.linuxcnc.g7x_segments import (
    TOLERANCE,
    Cursor,
    Motion,
    ProfileError,
    Round,
    Segment,
    Straight,
    div,
)

MAX_LEVELS = 100_000  # roughing strokes / offset steps before cncc calls the loop endless


# ---- the path -----------------------------------------------------------------------------------
_MAPS: dict[int, tuple[Callable[[complex], complex], bool]] = {
    0: (lambda p: p, False), 1: (lambda p: -p.conjugate(), True), 2: (lambda p: p.conjugate(), True),
    3: (lambda p: -p, False), 4: (lambda p: 1j * p, False), 5: (lambda p: (1j * p).conjugate(), True),
    6: (lambda p: -(1j * p).conjugate(), True), 7: (lambda p: -1j * p, False),
}


@dataclass(slots=True)
class _Mapped:
    """The moves of the turned/mirrored profile, mapped back to the program's Z/X."""

    out: Motion
    state: int

    def straight_move(self, end: complex) -> None:
        self.out.straight_move(_MAPS[self.state][0](end))

    def straight_rapid(self, end: complex) -> None:
        self.out.straight_rapid(_MAPS[self.state][0](end))

    def circular_move(self, ccw: bool, center: complex, end: complex) -> None:
        f, flips = _MAPS[self.state]
        self.out.circular_move(ccw != flips, f(center), f(end))


@dataclass(slots=True)
class Path:
    segs: list[Segment]
    delta: float = 0.5
    escape: complex = 0.3 + 0.3j
    flip_state: int = 0
    pocket_starts: list[complex] = field(default_factory=list)
    budget: int = MAX_LEVELS

    def copy(self) -> Path:
        return Path([s.dup() for s in self.segs], self.delta, self.escape, self.flip_state)

    def _spend(self) -> None:
        self.budget -= 1
        if self.budget < 0:
            raise ProfileError("the roughing loop makes no progress (LinuxCNC 2.9 loops for ever here)")

    def rotate(self) -> None:
        for s in self.segs:
            s.rotate()
        self.flip_state ^= 4

    def swap(self) -> None:
        """Mirror the profile so that it runs towards decreasing X and Z."""
        d = self.segs[0].end - self.segs[-1].end
        if d.imag > 0:
            for s in self.segs:
                s.flip_imag()
            self.flip_state ^= 2
        if d.real < 0:
            for s in self.segs:
                s.flip_real()
            self.flip_state ^= 1

    def monotonic(self) -> None:
        first = self.segs[0]
        if (first.end - first.start).real > 0:
            first.start = complex(first.end.real, first.start.imag)
        if not all(s.monotonic() for s in self.segs):
            raise ProfileError("Not monotonic")

    def do_finish(self) -> None:
        for h in range(1, len(self.segs) - 1):
            self.segs[h].do_finish(self.segs[h - 1], self.segs[h + 1])
        self.segs = [s for s in self.segs if not s.radius() < 1e-3]
        if not self.segs:
            raise ProfileError("the profile is empty")

    # --- G70
    def g70(self, out: Motion, x: float, z: float, d: float, e: float, passes: float) -> None:
        self.segs[0].start = complex(z, x)
        probe = self.copy()
        probe.segs.pop(0)
        if not probe.segs:
            raise ProfileError("the profile is empty")
        probe.swap()
        if not all(s.monotonic() for s in probe.segs):
            probe.rotate()
            probe.swap()
        probe.monotonic()
        if probe.flip_state & 4:
            self.rotate()
        self.swap()
        self.do_finish()
        self.monotonic()
        mapped = _Mapped(out, self.flip_state)
        n = int(passes)
        for k in range(n, 0, -1):
            distance = (k - 1) * (d - e) / passes + e
            path = self.copy()
            path.add_distance(distance)
            mapped.straight_rapid(path.segs[0].start)
            mapped.straight_rapid(path.segs[0].end)
            for s in path.segs[1:]:
                s.draw(mapped)

    # --- G71 / G72
    def g71(self, out: Motion, cycle: int, x: float, z: float, u: float, w: float, d: float, i: float,
            r: float, rotate: bool = False) -> None:
        self.segs[0].start = complex(z, x)
        if rotate:
            self.rotate()
        self.swap()
        self.do_finish()
        self.monotonic()
        self.add_distance(d)
        for s in self.segs:
            s.move(complex(w, u))
        mapped = _Mapped(out, self.flip_state)
        self.delta = max(i, 2 * TOLERANCE)
        self.escape = r * (1 + 1j)
        first, last = self.segs[0].start, self.segs[-1].end
        mapped.straight_rapid(first)
        if last.imag < first.imag:
            self.segs.append(Straight(last, complex(last.real, first.imag)))
        self.pocket_starts.append(first)
        self._pocket(cycle, first, 0, mapped)

    def _pocket(self, cycle: int, location: complex, p: int, out: Motion) -> None:
        segs = self.segs
        loc = Cursor(location)
        x = self.pocket_starts[-1].imag
        if cycle == 2:  # skip the first roughing pass
            while p < len(segs):
                if segs[p].dive(loc, -1e9, out, p == 0):
                    break
                p += 1
            cycle = 3
        while p < len(segs):
            self._spend()
            while x - TOLERANCE > loc.at.imag:
                x -= self.delta
            state = (p, x, loc.at)
            if segs[p].dive(loc, x, out, p == 0):
                self._climb_out(cycle, loc, p, out)
                return
            if abs(loc.at.imag - x) > TOLERANCE:
                p += 1  # below the current segment: on to the next
                continue
            p, x = self._cut_level(loc, p, x, out)
            if (p, x, loc.at) == state:
                raise ProfileError(f"no part of the profile is met at X{x:g} (LinuxCNC 2.9 loops for ever here)")

    def _climb_out(self, cycle: int, loc: Cursor, p: int, out: Motion) -> None:
        segs = self.segs
        if cycle == 1:  # after the roughing pass, follow the final contour and stop
            for s in segs[p:]:
                s.climb_only(loc, out)
            return
        while p < len(segs):  # follow the contour to the next pocket, then cut it
            if segs[p].climb(loc, out):
                if cycle == 3:
                    if loc.at.imag > self.pocket_starts[-1].imag and len(self.pocket_starts) > 1:
                        self.pocket_starts.pop()
                    if len(self.pocket_starts) == 1:
                        self.pocket_starts.append(loc.at)
                self._pocket(cycle, loc.at, p, out)
                return
            p += 1

    def _cut_level(self, loc: Cursor, p: int, x: float, out: Motion) -> tuple[int, float]:
        """One roughing stroke at level ``x`` from the diving segment ``p``: the new segment and level."""
        segs = self.segs
        for ip in range(p, len(segs)):
            hits = segs[ip].intersection_z(loc.at.imag)
            if not hits:
                continue
            dest_z = hits[0] if ip != p else hits[-1]
            distance = abs(dest_z - loc.at.real)
            if dest_z - TOLERANCE > loc.at.real:
                continue  # the diving curve met at the starting point only
            if distance < TOLERANCE:
                if p == ip:
                    continue
                if abs(loc.at - segs[ip].start) < TOLERANCE:
                    return ip, x  # another curve at its entry point: go on along it
                return p, x - self.delta  # a zero-length stroke: this level is done
            dest = complex(dest_z, loc.at.imag)
            out.straight_move(dest)
            scale = min(1.0, distance / 2 / self.escape.real)
            dest += scale * self.escape
            out.straight_rapid(dest)
            out.straight_rapid(loc.at - (scale * self.escape).conjugate())
            if p == 0:
                out.straight_rapid(loc.at)
            else:
                out.straight_move(loc.at)
            return p, x - self.delta
        return p, x  # nothing met at this level: 2.9 tries it again for ever (the budget ends it)

    # --- offsetting
    def add_distance(self, distance: float) -> None:
        segs = self.segs
        v1 = segs[0].end - segs[0].start
        v2 = segs[-1].start - segs[0].start
        if div(v1, v2).imag < 0:
            distance = -distance
        first = segs.pop(0)
        current = 0.0
        while current != distance and (current < distance) == (distance > 0):
            self._spend()
            step = min([1e9, *(s.radius() / 2 for s in segs), abs(distance - current)])
            if distance < 0:
                step = -step
            for s in segs:
                s.offset(step)
            segs[:] = [s for s in segs if not s.radius() < 1e-3]
            k = 0
            while k < len(segs) - 1:  # a gap opened at a corner: join it with an arc
                s, n = segs[k], segs[k + 1]
                if (s.end - n.start).real > 1e-2:
                    a, b = s.dup(), n.dup()
                    a.offset(-step)
                    b.offset(-step)
                    segs.insert(k + 1, Round(s.end, n.start, ccw=distance > 0, center=(a.end + b.start) / 2.0))
                    k += 1
                k += 1
            self._trim(segs)
            current += step  # 2.9 loops for ever when rounding steps past the distance; cncc stops there
        for k in range(len(segs) - 1):
            mid = (segs[k].end + segs[k + 1].start) / 2.0
            segs[k].end = segs[k + 1].start = mid
        first.end = segs[0].start if segs else first.end
        segs.insert(0, first)

    @staticmethod
    def _trim(segs: list[Segment]) -> None:
        """Drop segments that turned back or vanished, and meet each with the next."""
        k = 0
        while k < len(segs) - 1:
            if not segs[k].monotonic():
                if k == 0:
                    raise ProfileError("Not monotonic")
                drop = k if segs[k].radius() < segs[k - 1].radius() else k - 1
                del segs[drop]
                k = 0
                if len(segs) < 2:
                    return
            if segs[k].radius() < 1e-3:
                del segs[k]
                k = 1  # LinuxCNC restarts at begin() and then steps past it
                continue
            segs[k].intersect(segs[k + 1])
            k += 1
