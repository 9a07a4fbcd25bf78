"""LinuxCNC 2.9's extra words: ``@`` / ``^`` polar coordinates and the ``$`` spindle number.

``@`` is a radius and ``^`` an angle (degrees) about the program origin in the XY plane,
for a motion block instead of X and Y (rs274's ``find_ends``).  In G90 a missing ``@``
keeps the current radius and a missing ``^`` the current angle; in G91 both add to the
current ones.  rs274's errors: X or Y beside them, G53, G91 at the origin, ``@`` without
``^`` at the origin.  The words become the block's X and Y before the motion is lowered.

``$`` selects the spindle of S, M3/M4/M5, M19, M51, G33, G33.1, G76, G95 and G96.  The
stand-alone rs274 has one spindle: ``$0`` and ``$-1`` (all spindles) are accepted (the
value truncated to an integer), other numbers and a ``$`` with nothing to use it are
errors with rs274's texts.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from cncc import diagnostics as dg
from cncc.frontend import registry
from cncc.frontend.controller_errors import reject
from cncc.frontend.syntax import Word

if TYPE_CHECKING:
    from cncc.frontend.interp import BlockContext, Interpreter

POLAR = ("@", "^")
_SPINDLE_USERS = frozenset({"spindle_cw", "spindle_ccw", "spindle_off", "spindle_orient", "speed_override",
                            "spindle_sync_rs274", "rigid_tap_rs274", "lathe_thread", "feed_per_rev_rs274", "css_on"})
_NO_USER = ("$ (spindle selection) word with no M3, M4, M5, M19, M51, G33, G33.1, G76, G95, G96 or G97 to use it")


def polar_to_xy(it: Interpreter, ctx: BlockContext) -> bool:
    """Replace the block's ``@``/``^`` by X and Y words; False after an error (no motion)."""
    words = ctx.words
    for letter in "XY":
        if letter in words:
            return reject(it, ctx.span, f"polar_and_{letter.lower()}",
                         f"Cannot specify both polar coordinate and {letter} word")
    if "machine_coords" in ctx.block_flags:
        return reject(it, ctx.span, "polar_g53", "Cannot use polar coordinates with G53")
    k = it.frame.units.mm_per_unit
    cx, cy = it.pos[0] / k, it.pos[1] / k
    at_origin = cx == 0.0 and cy == 0.0
    rw, aw = words.pop("@", None), words.pop("^", None)
    if it.modal.incremental:
        if at_origin:
            return reject(it, ctx.span, "polar_incremental_origin",
                         "Incremental motion with polar coordinates is indeterminate when at the origin")
        radius = math.hypot(cx, cy) + (rw.value if rw is not None else 0.0)
        angle = math.atan2(cy, cx) + (math.radians(aw.value) if aw is not None else 0.0)
    else:
        if aw is None and at_origin:
            return reject(it, ctx.span, "polar_no_angle", "Must specify angle in polar coordinate if at the origin")
        radius = rw.value if rw is not None else math.hypot(cx, cy)
        angle = math.radians(aw.value) if aw is not None else math.atan2(cy, cx)
    x, y = radius * math.cos(angle), radius * math.sin(angle)
    if it.modal.incremental:  # the words become increments from the current point
        x, y = x - cx, y - cy
    src = rw if rw is not None else aw
    assert src is not None
    words["X"] = Word("X", x, True, src.start, src.end)
    words["Y"] = Word("Y", y, True, src.start, src.end)
    return True


def spindle_word(it: Interpreter, ctx: BlockContext) -> None:
    """Block hook: check and drop the ``$`` word."""
    w = ctx.words.pop("$", None)
    if w is None:
        return
    ops_here = {c.op for c in ctx.codes}
    if "S" not in ctx.words and not ops_here & _SPINDLE_USERS:
        reject(it, ctx.span, "spindle_word_unused", _NO_USER)
        return
    n = int(w.value)  # rs274 truncates
    spindles = int(it.dialect.option("spindles", 1))  # [TRAJ] SPINDLES of an INI file
    if n == -1 or 0 <= n < spindles:
        if n > 0:
            it.sink.emit(dg.ONE_SPINDLE, it.word_span(w), f"${n}: cncc models one spindle; this block's spindle "
                         "codes run on it (LinuxCNC would address spindle " + str(n) + ")")
        return
    if "S" in ctx.words:
        reject(it, ctx.span, "spindle_number_s", "Invalid spindle ($) number in Spindle speed command")
        return
    m = next((c.name for c in ctx.codes if c.op in ("spindle_cw", "spindle_ccw", "spindle_off")), "")
    reject(it, ctx.span, "spindle_number_m", f"Spindle ($) number out of range in {m.replace('M0', 'M')} Command"
          if m else "Invalid spindle ($) number")


registry.BLOCK_HOOKS.append(spindle_word)
