"""SZGH G25 (save the position), G61/G611-G614 (rapid back to it) and G26/G261-G264
(rapid back to the program start point).

Consumes the blocks' codes; produces rapids.  The SZGH 990MDb manual (002 §3.11-§3.13,
spec E002-12):

* G25 "memorises the current coordinate position of all axes (XYZA)";
* G61 returns all axes to the point G25 saved (G611..G614: only X, Y, Z or A), at
  G00 speed; without a saved point it acts as G26 (spec A-25);
* G26 returns all axes to the program start point, "the coordinate position of the
  N0000 block" (G261..G264: one axis), at G00 speed.

Points are kept as machine positions (program position plus the frame's offsets and
tool length), so a work-offset change in between does not move them; the rapid goes
to that machine position in the current frame.  The code's ``index`` in the dialect
table (1..4) names the single axis.
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

from cncc.dialects import CodeDef
from cncc.frontend.ops import block_motion, handler
from cncc.ir import Frame, Rapid, Vec6

if TYPE_CHECKING:
    from cncc.frontend.interp import BlockContext, Interpreter

_ALL_AXES = (0, 1, 2, 3)  # X Y Z A (the manual's "XYZA")


def _offset(f: Frame) -> Vec6:
    o = list(f.total_offset_mm)
    o[f.tool_length_axis] += f.tool_length_mm
    return (o[0], o[1], o[2], o[3], o[4], o[5])


def _to_machine(p: Vec6, f: Frame) -> Vec6:
    o = _offset(f)
    return (p[0] + o[0], p[1] + o[1], p[2] + o[2], p[3] + o[3], p[4] + o[4], p[5] + o[5])


@handler("save_point")
def _g25(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    it.refs = replace(it.refs, saved_machine_mm=_to_machine(it.pos, it.frame))


@handler("return_saved", "return_start")
def _return(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    ctx.axis_used = True
    target = it.refs.saved_machine_mm if c.op == "return_saved" else None
    machine = target if target is not None else it.refs.start_machine_mm  # G61 without G25 acts as G26
    axes = (c.index - 1,) if c.index else _ALL_AXES
    o = _offset(it.frame)
    end = list(it.pos)
    for k in axes:
        end[k] = machine[k] - o[k]
    new: Vec6 = (end[0], end[1], end[2], end[3], end[4], end[5])
    ctx.out.append(Rapid(ctx.span, it.frame, it.pos, new, block_motion(it, ctx), origin=c.name))
    it.pos = new
    it.release_axes(axes)


__all__: list[str] = []
