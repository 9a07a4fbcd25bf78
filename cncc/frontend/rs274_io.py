"""LinuxCNC's input and output codes: ``M62``-``M65`` digital outputs, ``M66`` wait on an input,
``M67``/``M68`` analog outputs.

None of them moves an axis or changes the interpreter's state; on a machine they set HAL
pins (M62/M63/M67 with the next motion, M64/M65/M68 at once) or, for M66 with ``L`` other
than 0, wait up to ``Q`` seconds for an input edge or level.  The IR gets an
:class:`~cncc.ir.Aux` with the block's words, so the same dialect writes them back and a
translation to another dialect says that they are dropped (W0 ``XL_NO_CODE``).  LinuxCNC
2.9's stand-alone rs274 prints no canonical call for any of them; the canon trace has
none either.

The checks are rs274 2.9's, with its texts (learnt from the oracle, tests/oracle/cases.py):

* M62-M65 need a P word ("No valid P word with M62"); any value passes.
* M66 needs P >= 0 or E >= 0, not both; an analog input (E) only with ``L0``; a wait type
  other than 0 needs a timeout Q > 0.  A negative L is rs274's "Negative l word used".
* M67/M68 need E >= 0 ("Invalid analog index with M67"); Q may be missing (0).

They share one M modal group (frontend/op_catalogue.toml, ``m_group.io``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from cncc import diagnostics as dg
from cncc.dialects import CodeDef
from cncc.frontend import ops
from cncc.frontend.controller_errors import controller_error, reject
from cncc.ir import Aux

if TYPE_CHECKING:
    from cncc.frontend.interp import BlockContext, Interpreter

_WORDS = "PELQ"  # the words these codes read, in the order they are written back


def _value(ctx: BlockContext, letter: str) -> float | None:
    w = ctx.words.get(letter)
    return None if w is None else w.value


def _emit(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    args = tuple((k, v) for k in _WORDS if (v := _value(ctx, k)) is not None)
    ctx.out.append(Aux(ctx.span, it.frame, c.tenths, args))


@ops.handler("digital_out_sync", "digital_out_sync_off", "digital_out", "digital_out_off")
def _digital_out(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    if _value(ctx, "P") is None:
        reject(it, ctx.span, f"m{c.tenths // 10}_p", f"No valid P word with {c.name}")
        return
    _emit(it, ctx, c)


@ops.handler("wait_input")
def _wait_input(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    p, e = _value(ctx, "P"), _value(ctx, "E")
    digital, analog = p is not None and p >= 0, e is not None and e >= 0
    wait_type = round(_value(ctx, "L") or 0.0)
    timeout_s = _value(ctx, "Q") or 0.0
    if wait_type < 0:  # rs274's generic L check, the code cncc gives it for M98 L (E0316)
        it.emit_error(dg.MACRO_BAD_CALL, ctx.span, controller_error(it, "E0316:negative", "Negative l word used"))
    elif digital and analog:
        reject(it, ctx.span, "m66_both", "Invalid to select both a digital and an analog input with M66")
    elif not (digital or analog):
        reject(it, ctx.span, "m66_none", "Need to have either a valid P or a valid E word with M66")
    elif analog and wait_type != 0:
        reject(it, ctx.span, "m66_analog", "Can't select analog input with wait type != immediate return")
    elif wait_type != 0 and timeout_s <= 0:
        reject(it, ctx.span, "m66_timeout", "Zero timeout with wait type != immediate return")
    else:
        _emit(it, ctx, c)


@ops.handler("analog_out_sync", "analog_out")
def _analog_out(it: Interpreter, ctx: BlockContext, c: CodeDef) -> None:
    e = _value(ctx, "E")
    if e is None or e < 0:
        reject(it, ctx.span, f"m{c.tenths // 10}_e", f"Invalid analog index with {c.name}")
        return
    _emit(it, ctx, c)
