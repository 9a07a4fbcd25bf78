"""LinuxCNC's ``M61 Q``: make tool Q the tool in the spindle without a tool change.

As on a LinuxCNC machine, the tool number in the spindle becomes Q (``Q0``: no tool):
a later G43 without H and G41/G42 without D use it, and ``#<_current_tool>`` reads it.
No tool length offset is applied until a G43.  The canon trace gets LinuxCNC's
``CHANGE_TOOL_NUMBER(q)``.  Q is rounded to the nearest integer (rs274's
``round_to_int``); a missing or negative Q, and a tool that the tool table (when one was
given) does not list, are errors with rs274's texts.

LinuxCNC 2.9's stand-alone ``rs274`` prints the call but keeps its own spindle tool
unchanged (its canon has no tool changer that would load the tool): that is the one
deliberate difference (docs/dialects-notes.md, tests/oracle/allow.toml).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from cncc import diagnostics as dg
from cncc.dialects import CodeDef
from cncc.frontend import registry
from cncc.frontend.controller_errors import reject
from cncc.frontend.ops import not_in_tool_table, tool_not_found
from cncc.ir import SetToolNumber

if TYPE_CHECKING:
    from cncc.frontend.interp import BlockContext, Interpreter


@registry.handler("set_tool_number")
def m61(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    qw = ctx.words.get("Q")
    tool = math.floor(qw.value + 0.5) if qw is not None else -1
    if tool < 0:
        reject(it, ctx.span, "m61_q", "Need non-negative Q-word to specify tool number with M61")
        return
    if not_in_tool_table(it, tool):
        it.emit_error(dg.CONTROLLER_REJECTS, ctx.span, tool_not_found(it, tool))
        return
    it.modal = it.modal.with_(tool_loaded=tool)
    ctx.out.append(SetToolNumber(ctx.span, it.frame, tool))
