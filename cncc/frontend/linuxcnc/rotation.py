"""The XY rotation of LinuxCNC's work systems (G10 L2 R) in the program position.

LinuxCNC places a program point on the machine as ``R(theta) (p + g92) + g5x`` in XY
(:class:`Placement`; the active work system's rotation turns the point after its G92
offset is added).  rs274's canon calls carry program coordinates, so the rotation shows
where the interpreter re-expresses the tool's position: a ``G53`` move's end and the home
leg of ``G28``/``G30`` are machine positions; ``G10 L20`` gives the current point the named
coordinates in the rotated system; a G92 change keeps ``p + g92``; a system select keeps
the machine point.  After ``G10 L2/L20`` of the active system rs274 2.9 keeps ``R p + g5x``
-- it leaves G92 out, so with a G92 offset in force the tool's point moves
(docs/dialects-notes.md); cncc gives the same program position.  The moves' frames carry the
rotation as a :class:`~cncc.ir.frame.Rotation` record marked ``work`` (:func:`rotate_frames`):
the canon trace keeps program coordinates, every other output is rotated by the rotation
pass (docs/dialects-notes.md).
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

from cncc.frontend.linuxcnc.placement import Placement
from cncc.frontend.syntax import Word
from cncc.ir import PROGRAMMED, Command, Frame, Linear, OriginKind, Plane, Rapid, Vec6
from cncc.ir.frame import Rotation

if TYPE_CHECKING:
    from cncc.frontend.interp import Interpreter


def placement(it: Interpreter) -> Placement:
    """The active work system's placement of program XY."""
    from cncc.frontend.rs274_g10 import rotation_deg

    return Placement.of_frame(it.frame, rotation_deg(it, it.frame.work_index))


def rotation_in_use(it: Interpreter) -> bool:
    """Some work system has an XY rotation (G10 L2 R) in this program."""
    from cncc.frontend.rs274 import state

    return any(state(it).rotation_deg.values())


def _with_xy(p: Vec6, xy: tuple[float, float]) -> Vec6:
    return (xy[0], xy[1], p[2], p[3], p[4], p[5])


def reexpress(it: Interpreter, before: Placement, start: Vec6, words: tuple[Word, ...], out: list[Command],
              at: int, *, select: bool = False) -> None:
    """Correct the program position (and G53 move ends) of one executed block for the rotation."""
    after = placement(it)
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
    if moves or (before.g5x, before.theta_deg) == (after.g5x, after.theta_deg):
        return  # a G92 change is made in program coordinates: no re-expression
    if not select:  # G10 L2/L20 of the active system: rs274 2.9 leaves G92 out (a select does not)
        before, after = replace(before, g92=(0.0, 0.0)), replace(after, g92=(0.0, 0.0))
    it.pos = _with_xy(it.pos, after.program(*before.machine(start[0], start[1])))


def work_rotation(theta_deg: float, f: Frame) -> Rotation | None:
    """The frame record of a work system's XY rotation (None when it has none): about the point
    ``-g92`` of the program (LinuxCNC adds the G92 offset before it turns the point)."""
    g92 = f.g92_offset_mm
    return Rotation(Plane.XY, (-g92[0] + 0.0, -g92[1] + 0.0), theta_deg, work=True) if theta_deg else None


def rotate_frames(it: Interpreter, out: list[Command], at: int) -> None:
    """The frames of one executed block's commands, and the interpreter's, carry the rotation of
    their work system (the rotation pass turns the moves; the canon trace keeps them)."""
    from cncc.frontend.rs274_g10 import rotation_deg

    done: dict[int, Frame] = {}

    def framed(f: Frame) -> Frame:
        got = done.get(id(f))
        if got is None:
            want = work_rotation(rotation_deg(it, f.work_index), f)
            got = f if f.rotation == want or (f.rotation is not None and not f.rotation.work) \
                else replace(f, rotation=want)
            done[id(f)] = got
        return got

    for k in range(at, len(out)):
        c = out[k]
        f = framed(c.frame)
        if f is not c.frame:
            out[k] = replace(c, frame=f)
    it.frame = framed(it.frame)
