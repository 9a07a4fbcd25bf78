"""LinuxCNC's lathe modes: G7 (diameter) and G8 (radius, the power-on mode).

In diameter mode every X word of a block is half its value (rs274 halves X as it reads
the word, and a G7/G8 in the block applies to the block's own X word: ``G7 X10`` moves to
X5 in the IR).  I/K arc centres are radii either way; ``G76``'s I/J/K follow the mode
(:mod:`cncc.frontend.linuxcnc.g76`).  Positions read back (#5420, #<_x>) are radii, as
in LinuxCNC.  :func:`block_words` is the executor's hook that rewrites a block's words.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from cncc.dialects import CodeDef
from cncc.frontend import ops
from cncc.frontend.syntax import Word
from cncc.ir import Comment

if TYPE_CHECKING:
    from cncc.frontend.interp import BlockContext, Interpreter

G7, G8, G76 = 70, 80, 760  # G code tenths


@dataclass(slots=True)
class LatheState:
    diameter: bool = False


def _state(it: Interpreter) -> LatheState:
    """The interpreter's lathe record (a layer record: cncc/frontend/run_state.py)."""
    st = it.extras.get(LatheState)
    return st if st is not None else it.extras.attach(LatheState())


def diameter_mode(it: Interpreter) -> bool:
    return _state(it).diameter


def block_words(it: Interpreter, words: tuple[Word, ...], *, capture: bool = False) -> tuple[Word, ...]:
    """The block's words as rs274 uses them: X halved in diameter mode (the mode after the block's own
    G7/G8; in a G7x profile, which does not run G7/G8, the mode in force).  A G7 or G8 that changes the
    mode in a G76 block also halves or doubles that block's I/J/K (rs274 2.9 does, before G76 applies
    the mode again)."""
    tenths = [round(w.value * 10) for w in words if w.letter == "G"]
    old = _state(it).diameter
    new = old
    if not capture and (G7 in tenths or G8 in tenths):
        new = G7 in tenths
    if not new and new == old:
        return words
    ijk = 1.0
    if new != old and G76 in tenths:
        ijk = 0.5 if new else 2.0
    out = []
    for w in words:
        if w.letter == "X" and new:
            w = Word("X", w.value / 2, w.point, w.start, w.end)
        elif w.letter in "IJK" and ijk != 1.0:
            w = Word(w.letter, w.value * ijk, w.point, w.start, w.end)
        out.append(w)
    return tuple(out)


@ops.handler("diameter_mode", "radius_mode")
def _mode(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    st = _state(it)
    on = c.op == "diameter_mode"
    if on != st.diameter:
        st.diameter = on
        text = "diameter" if on else "radius"
        ctx.out.append(Comment(ctx.span, it.frame, f"interpreter: Lathe diameter mode changed to {text}"))
