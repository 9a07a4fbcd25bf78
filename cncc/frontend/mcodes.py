"""Machine functions: M codes the machine handles, smoothing settings, extra work systems.

A Fanuc-family control does not interpret most M codes itself: it hands them to the
machine builder's ladder (PMC/PLC) and waits for the finish signal.  So an M code the
dialect table does not list is not an error there; the dialect option
``unknown_m_code`` says what the control does with it:

* ``"machine"`` — passed to the machine: an :class:`~cncc.ir.Aux` command, and a
  warning (W0270, once per code and program) unless the machine model lists the code (``[[m_codes]]`` in a machine
  file, with its meaning and the seconds it takes, which the timing report counts);
* ``"error"`` (the default) — the control rejects it (grbl, LinuxCNC, SZGH): E0202.

Handlers registered here: ``aux`` (an M code with no modelled effect), ``smoothing``
(G05.1, Haas G187/G103: a setting the path planner may read; no motion), and
``work_extended`` (G54.1 P / Haas G154 P: work system 6 + P).
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

from cncc import diagnostics as dg
from cncc.dialects import CodeDef, Dialect, code_name
from cncc.frontend.ops import handler
from cncc.ir import Aux, SetMode

if TYPE_CHECKING:
    from cncc.frontend.interp import BlockContext, Interpreter
    from cncc.frontend.syntax import Word

EXTENDED_WORK_BASE = 6
"""G54.1 P1 / G154 P1 is work system 7 (after G54-G59), as Haas's G110 is."""


def passes_to_machine(dialect: Dialect) -> bool:
    return str(dialect.option("unknown_m_code", "error")) == "machine"


def machine_m_code(it: Interpreter, w: Word, tenths: int) -> CodeDef | None:
    """The code the machine handles for an M word the dialect does not define, or None
    (the caller reports E0202)."""
    known = it.options.machine_m_codes.get(tenths)
    if known is None and not passes_to_machine(it.dialect):
        return None
    name = code_name("M", tenths)
    warned = it.notes.m_codes_warned
    if known is None and tenths not in warned:  # once per code and program
        warned.add(tenths)
        it.sink.emit(dg.M_CODE_TO_MACHINE, it.word_span(w),
                     f"{name} is not a {it.dialect.name} code; the control passes it to the machine "
                     f"(list it in the machine model's [[m_codes]] to say what it does)")
    return CodeDef("M", tenths, name, "aux", "non_modal", known or "machine function")


@handler("aux")
def _aux(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    ctx.out.append(Aux(ctx.span, it.frame, c.tenths))


@handler("smoothing")
def _smoothing(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    values = tuple((k, ctx.words[k].value) for k in sorted(c.words) if k in ctx.words)
    ctx.out.append(SetMode(ctx.span, it.frame, "smoothing", (c.name, values)))


@handler("work_extended")
def _work_extended(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    p = ctx.words.get("P")
    if p is None or p.value != int(p.value) or p.value < 1:
        it.emit_error(dg.MACRO_BAD_CALL if p is None else dg.NUMBER_RANGE, ctx.span,
                      f"{c.name} needs P, the number of the additional work system (1 or more)")
        return
    index = EXTENDED_WORK_BASE + int(p.value)
    off = it.options.work_offsets_mm.get(index, (0.0,) * 6)
    if index != it.frame.work_index or off != it.frame.work_offset_mm:
        it.set_frame(replace(it.frame, work_index=index, work_offset_mm=off))
        ctx.out.append(SetMode(ctx.span, it.frame, "g5x_offset", index))
