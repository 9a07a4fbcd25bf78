"""The XY rotation of LinuxCNC's work systems (G10 L2 R) in the program position.

LinuxCNC places a program point on the machine as ``R(theta) (p + g92) + g5x`` in XY (the
rotation of the active work system about its origin).  rs274's canon calls carry program
coordinates, so the rotation shows where the interpreter re-expresses the tool's position:
after a change of the active system's offsets or rotation (``G10 L2 P0 ... R``, a system
select) the machine position stays and the program position follows, and a ``G53`` move's
end is a machine position.  cncc's motion passes do not rotate the moves yet
(docs/dialects-notes.md); this module keeps the program coordinates LinuxCNC's.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

from cncc.frontend.syntax import Word
from cncc.ir import PROGRAMMED, Command, Frame, Linear, OriginKind, Rapid, Vec6

if TYPE_CHECKING:
    from cncc.frontend.interp import Interpreter


@dataclass(frozen=True, slots=True)
class Placement:
    """Where program XY lands on the machine: ``R(theta) (p + g92) + g5x``."""

    g5x: tuple[float, float]
    g92: tuple[float, float]
    theta_deg: float

    @staticmethod
    def of(it: Interpreter) -> Placement:
        from cncc.frontend.rs274_g10 import rotation_deg

        return Placement.of_frame(it.frame, rotation_deg(it, it.frame.work_index))

    @staticmethod
    def of_frame(f: Frame, theta_deg: float) -> Placement:
        g5x = (f.work_offset_mm[0] + f.local_offset_mm[0], f.work_offset_mm[1] + f.local_offset_mm[1])
        return Placement(g5x, (f.g92_offset_mm[0], f.g92_offset_mm[1]), theta_deg)

    def machine(self, x: float, y: float) -> tuple[float, float]:
        c, s = math.cos(math.radians(self.theta_deg)), math.sin(math.radians(self.theta_deg))
        u, v = x + self.g92[0], y + self.g92[1]
        return c * u - s * v + self.g5x[0], s * u + c * v + self.g5x[1]

    def program(self, mx: float, my: float) -> tuple[float, float]:
        c, s = math.cos(math.radians(self.theta_deg)), math.sin(math.radians(self.theta_deg))
        u, v = mx - self.g5x[0], my - self.g5x[1]
        return c * u + s * v - self.g92[0], -s * u + c * v - self.g92[1]


def rotation_in_use(it: Interpreter) -> bool:
    """Some work system has an XY rotation (G10 L2 R) in this program."""
    from cncc.frontend.rs274 import state

    return any(state(it).rotation_deg.values())


def _with_xy(p: Vec6, xy: tuple[float, float]) -> Vec6:
    return (xy[0], xy[1], p[2], p[3], p[4], p[5])


def reexpress(it: Interpreter, before: Placement, start: Vec6, words: tuple[Word, ...], out: list[Command],
              at: int) -> None:
    """Correct the program position (and G53 move ends) of one executed block for the rotation."""
    after = Placement.of(it)
    if before.theta_deg == 0.0 and after.theta_deg == 0.0:
        return
    moves = [k for k in range(at, len(out)) if isinstance(out[k], Rapid | Linear)]
    g53 = [k for k in moves if getattr(out[k], "origin", PROGRAMMED).kind is OriginKind.MACHINE]
    if g53:
        given = {w.letter: it.reader.axis_value(w) for w in words if w.letter in "XY"}
        for k in g53:
            c = out[k]
            assert isinstance(c, Rapid | Linear)
            cur = after.machine(c.start[0], c.start[1]) if k != g53[0] else before.machine(start[0], start[1])
            machine = (given.get("X", cur[0]), given.get("Y", cur[1]))
            end = _with_xy(c.end, after.program(*machine))
            out[k] = replace(c, end=end)
            if k + 1 < len(out) and isinstance(out[k + 1], Rapid | Linear):
                out[k + 1] = replace(out[k + 1], start=end)  # type: ignore[arg-type]
            it.pos = end
        return
    if moves or before == after:
        return
    it.pos = _with_xy(it.pos, after.program(*before.machine(start[0], start[1])))
