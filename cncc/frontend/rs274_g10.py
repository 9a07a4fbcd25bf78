"""G10 with the meaning LinuxCNC (and grbl, for L2/L20) gives it.

- ``L1 P<tool>``: tool table entry: Z (and X ...) length offsets, R radius.
- ``L10 P<tool>``: the tool's offsets so that the current position has the given
  coordinates; ``L11`` the same measured in G59.3 (system 9).
- ``L2 P<0-9>``: a work system's offsets (P0 the active one), R its XY rotation.
- ``L20 P<0-9>``: a work system's offsets so that the current position has the
  given coordinates.

The dialect's ``options.g10_systems`` is the number of work systems (9 LinuxCNC, 6
grbl); errors use the dialect's controller texts in ``[errors]`` when it has them.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import TYPE_CHECKING

from cncc.dialects import CodeDef
from cncc.frontend.controller_errors import reject
from cncc.frontend.ops import AXES
from cncc.ir import SetWorkSystem, SetXyRotation, Vec6, WriteToolTable, WriteWorkTable

if TYPE_CHECKING:
    from cncc.frontend.interp import BlockContext, Interpreter


def run_g10(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    lw, pw = ctx.words.get("L"), ctx.words.get("P")
    table = int(lw.value) if lw is not None else -1
    if table not in (1, 2, 10, 11, 20):
        reject(it, ctx.span, "g10_l", "Line with G10 does not have L1, L10, L11, L2, or L20")
        return
    if pw is None:
        reject(it, ctx.span, "g10_p", "Line with G10 does not have P word")
        return
    p = round(pw.value)
    if table in (1, 10, 11):
        if p < 1 or p != pw.value:
            reject(it, ctx.span, "g10_tool", "Invalid tool number")
            return
        _tool_entry(it, ctx, table, p)
        return
    systems = int(it.dialect.option("g10_systems", 9))
    if p < 0 or p > systems or p != pw.value:
        reject(it, ctx.span, "g10_p_range", f"P value out of range with G10 L{table}")
        return
    if table == 20 and "R" in ctx.words and it.dialect.option("g10_l20_rejects_r", False):
        reject(it, ctx.span, "g10_l20_r", "R not allowed in G10 L20")
        return
    _work_entry(it, ctx, table, p or it.frame.work_index)


def _tool_entry(it: Interpreter, ctx: BlockContext, table: int, tool: int) -> None:
    zw, rw = ctx.words.get("Z"), ctx.words.get("R")
    lengths, radii = it.options.tool_lengths_mm, it.options.tool_radii_mm
    if zw is not None:
        z = it.reader.length_mm(zw)
        if table == 1:
            lengths[tool] = z
        else:
            f = it.frame
            base = f.total_offset_mm[2]
            if table == 11:
                base = it.options.work_offsets_mm.get(9, (0.0,) * 6)[2]
            machine_z = f.total_offset_mm[2] + it.pos[2] + f.tool_length_mm
            lengths[tool] = machine_z - base - z
    if rw is not None:
        radii[tool] = abs(it.reader.length_mm(rw))
    ctx.out.append(WriteToolTable(ctx.span, it.frame, tool, lengths.get(tool, 0.0), 2.0 * radii.get(tool, 0.0)))


def _work_entry(it: Interpreter, ctx: BlockContext, table: int, index: int) -> None:
    old = it.options.work_offsets_mm.get(index, (0.0,) * 6)
    vals = list(old)
    f = it.frame
    mxy = machine_xy(it)
    for k, letter in enumerate(AXES):
        w = ctx.words.get(letter)
        if w is None:
            continue
        v = it.reader.axis_value(w)
        if table == 2:
            vals[k] = v
        else:  # L20: the current position gets the value v
            machine = mxy[k] if k < 2 else f.total_offset_mm[k] + it.pos[k]
            vals[k] = machine - f.local_offset_mm[k] - f.g92_offset_mm[k] - v
    if table == 20:
        _rotated_l20(it, ctx, index, old, vals)
    new: Vec6 = (vals[0], vals[1], vals[2], vals[3], vals[4], vals[5])
    it.options.work_offsets_mm[index] = new
    ctx.out.append(WriteWorkTable(ctx.span, it.frame, index, old, new))  # translation writes it (G10)
    rw = ctx.words.get("R")
    if rw is not None and table == 2:
        from cncc.frontend.rs274_state import state

        state(it).rotation_deg[index] = rw.value
    if f.work_index == index:  # LinuxCNC reports the active system's offsets and rotation, changed or not
        if new != f.work_offset_mm:
            it.set_frame(replace(f, work_offset_mm=new))
        ctx.out.append(SetWorkSystem(ctx.span, it.frame, index))
        ctx.out.append(SetXyRotation(ctx.span, it.frame, rotation_deg(it, index)))


def _rotated_l20(it: Interpreter, ctx: BlockContext, index: int, old: Vec6, vals: list[float]) -> None:
    """G10 L20 X Y when the active system or system ``index`` is rotated (LinuxCNC): the current
    point gets the named coordinates in system ``index``'s rotated terms and keeps its coordinates
    there for an unnamed X or Y: ``offset = R(active) p + g5x - R(index) q``."""
    from cncc.frontend.linuxcnc.placement import Placement

    # G92 stays out of it (rs274 2.9)
    here = replace(Placement.of_frame(it.frame, rotation_deg(it, it.frame.work_index)), g92=(0.0, 0.0))
    theta = rotation_deg(it, index)
    if not (here.theta_deg or theta) or not ("X" in ctx.words or "Y" in ctx.words):
        return
    f = it.frame
    mx, my = here.machine(it.pos[0], it.pos[1])
    system = Placement((old[0] + f.local_offset_mm[0], old[1] + f.local_offset_mm[1]), (0.0, 0.0), theta)
    q = list(system.program(mx, my))
    for k, letter in enumerate("XY"):
        w = ctx.words.get(letter)
        if w is not None:
            q[k] = it.reader.axis_value(w)
    ox, oy = Placement((0.0, 0.0), (0.0, 0.0), theta).machine(q[0], q[1])
    vals[0], vals[1] = mx - ox - f.local_offset_mm[0], my - oy - f.local_offset_mm[1]
def machine_xy(it: Interpreter) -> tuple[float, float]:
    """The tool's machine XY: the program point placed by the active system's offsets and XY rotation,
    ``R(theta) (p + g92) + g5x`` (as :class:`cncc.frontend.linuxcnc.rotation.Placement`)."""
    f = it.frame
    theta = math.radians(rotation_deg(it, f.work_index))
    c, s = math.cos(theta), math.sin(theta)
    u, v = it.pos[0] + f.g92_offset_mm[0], it.pos[1] + f.g92_offset_mm[1]
    return (c * u - s * v + f.work_offset_mm[0] + f.local_offset_mm[0],
            s * u + c * v + f.work_offset_mm[1] + f.local_offset_mm[1])


def rotation_deg(it: Interpreter, index: int) -> float:
    """The XY rotation of work system ``index`` (G10 L2 R: frames carry it, :mod:`cncc.frontend.linuxcnc.rotation`)."""
    from cncc.frontend.rs274_state import state

    return state(it).rotation_deg.get(index, 0.0)
