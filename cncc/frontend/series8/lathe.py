"""SERIES 8 on a lathe: X as a diameter (A-25) and constant surface speed on G95 moves.

* ``lathe_diameter_x`` (default true, spec A-25): in a program that uses a lathe-only
  code (G96, or G92 with R or S), X words are diameters, so the block hook halves
  them before the shared ops read them (not the X of G04, a dwell time).  A program
  without those codes is a mill program and keeps X as a position.
* Feed moves in G95 under G96 get a :class:`~cncc.ir.css.Css` record on their
  ``Motion``: the surface speed (S in ft/min or m/min), the G92 S clamp, the feed per
  revolution and the radius ``R + (X - X_ref)`` from ``G92 R`` at ``X_ref`` (no G92 R:
  the radius is X), both in the frame of the move.  ``feed_mm_min`` becomes the feed at the start of the move.
"""

from __future__ import annotations

import re
from dataclasses import replace
from typing import TYPE_CHECKING

from cncc.frontend.series8 import state
from cncc.frontend.series8.layer import LAYER
from cncc.ir import Command, Linear, Units
from cncc.ir.css import Css

if TYPE_CHECKING:
    from cncc.frontend.interp import BlockContext, Interpreter

_COMMENT = re.compile(r";.*|\([^)\n]*\)")
_G96 = re.compile(r"G0*96(?![0-9.])")
_G92_RS = re.compile(r"G0*92(?![0-9.]).*[RS]")
MM_PER_FOOT = 304.8


def is_lathe_program(text: str) -> bool:
    """True when the program uses a lathe-only code: G96, or G92 with R or S."""
    for line in text.upper().splitlines():
        code = _COMMENT.sub("", line)
        if _G96.search(code) or _G92_RS.search(code):
            return True
    return False


def _diameter_hook(it: Interpreter, ctx: BlockContext) -> None:
    st = state.get(it)
    if st is None or not st.x_diameter:
        return
    w = ctx.words.get("X")
    if w is None or w.expr is not None or any(cd.op == "dwell" for cd in ctx.codes):
        return
    ctx.words["X"] = replace(w, value=w.value / 2)


def with_css(it: Interpreter, cmds: list[Command]) -> list[Command]:
    """Put the CSS record on the block's G95 feed lines while G96 is in force."""
    st = state.get(it)
    if st is None or not (it.modal.css and it.modal.per_rev) or it.modal.spindle_rpm <= 0:
        return cmds
    factor = MM_PER_FOOT if it.frame.units is Units.INCH else 1000.0
    shift = it.frame.total_offset_mm[0]
    # G92 R at X_ref (program X of this frame): r = R + (X - X_ref); without it the radius is X
    offset = st.css_reference[0] - st.css_reference[1] - shift if st.css_reference is not None else -shift
    out: list[Command] = []
    for c in cmds:
        if isinstance(c, Linear) and c.motion.css is None:
            css = Css(it.modal.spindle_rpm * factor, it.modal.spindle_clamp_rpm,
                      c.feed_mm_min / it.modal.spindle_rpm, 0, offset)
            motion = it.intern_motion(replace(c.motion, css=css))
            c = replace(c, feed_mm_min=css.feed_at_mm_min(c.start, shift), motion=motion)
        out.append(c)
    return out


LAYER.hook_first(_diameter_hook)
