"""Calls, returns and jumps of the macro executor.

``M98 P_ L_`` (and SYNTEC's ``M98 H_``, SZGH's ``M98 Pname`` and ``PP name``) call
a subprogram in the caller's local scope; ``G65 P_ L_ args``, a ``G66`` modal call
and SZGH user macro G codes (``G152`` runs ``ProgramG152``) call a macro with a new
local scope holding the arguments.  ``M99`` returns (to ``N P`` of the caller when
``P`` is given; in a main program it ends the program, or loops when the dialect
option ``m99_in_main = "loop"``).  SZGH ``G22 L_ ... G800`` repeats blocks, ``M97
P_`` jumps, and the input-test M codes wait or jump on an input.

Nesting is limited per dialect: SZGH 4 calls in all; Fanuc 4 ``M98`` levels and 4
macro levels (dialect options ``max_subprogram_depth``, ``max_macro_depth``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from cncc import diagnostics as dg
from cncc.dialects import CodeDef
from cncc.frontend.macro.frames import CallFrame, ModalCall
from cncc.frontend.macro.program import Unit, program_key
from cncc.frontend.macro.values import MacroError
from cncc.frontend.syntax import Block, ProgramName, Word
from cncc.ir import CallBoundary, Wait
from cncc.source import Span

if TYPE_CHECKING:
    from cncc.frontend.macro.executor import Executor

MACRO_KINDS = frozenset({"G65", "G66", "user"})
# letters a special code takes for itself (they are not run as NC words)
CONSUMES = {
    "subprogram_call": "PLH", "subprogram_return": "P", "jump": "P", "block_loop": "L",
    "input_wait_on": "P", "input_wait_off": "P", "block_loop_end": "", "modal_call_off": "",
    "program_restart": "", "local_call": "PL",
}


def run_special(ex: Executor, fr: CallFrame, i: int, block: Block, words: tuple[Word, ...],
                special: list[tuple[Word, CodeDef]], names: list[ProgramName]) -> None:
    """A block with calls, returns, jumps or loops (``special``: the words that make it so)."""
    span = Span(ex.it.source_id, block.start, block.end)
    by_op = {c.op: (w, c) for w, c in special}
    if "macro_call" in by_op or "user_macro" in by_op:
        if "user_macro" in by_op:  # SZGH: the block's other G codes (G99, G91 ...) apply before the call
            modes = tuple(w for w in words if w.letter == "G" and w is not by_op["user_macro"][0])
            if modes:
                ex.run_nc(fr, block, modes, comments=False)
        _macro_call(ex, fr, words, by_op, names, span)
        return
    if "modal_call" in by_op:
        _modal_setup(ex, fr, words, names, span)
        return
    if "modal_call_off" in by_op:
        ex.modal = None
    taken = {id(w) for w, _ in special}
    letters = "".join(CONSUMES.get(c.op, "") for _, c in special)
    if any(n.call for n in names):
        letters += "PL"
    rest = tuple(w for w in words if id(w) not in taken and w.letter not in letters)
    if any(w.letter not in "NO" for w in rest) or block.comments:
        ex.run_nc(fr, block, rest)
        if ex.stopped or ex.it.ended:
            return
    if any(n.call for n in names) and "subprogram_call" not in by_op:
        _subprogram_call(ex, fr, words, names, span)
    for w, c in special:
        _one(ex, fr, i, c, w, words, names, span)
        if ex.stopped:
            return


def _one(ex: Executor, fr: CallFrame, i: int, c: CodeDef, w: Word, words: tuple[Word, ...],
         names: list[ProgramName], span: Span) -> None:
    op = c.op
    if op == "subprogram_call":
        _subprogram_call(ex, fr, words, names, span)
    elif op == "local_call":
        _local_call(ex, fr, c, words, span)
    elif op == "subprogram_return":
        p = _word(words, "P")
        ex.do_return(fr, _label(p) if p is not None else None, span)
    elif op == "jump":
        p = _word(words, "P")
        if p is None:
            ex.fail(dg.MACRO_BAD_CALL, span, f"{c.name} needs P, the sequence number to jump to")
            return
        ex.goto(fr, i, p.value, span)
    elif op == "block_loop":
        lw = _word(words, "L")
        count = int(lw.value) if lw is not None else 1
        if lw is not None and (lw.value != count or count < 1):
            ex.fail(dg.MACRO_BAD_CALL, span, f"{c.name} L must be a whole number of passes, 1 or more")
            return
        fr.block_loops.append([i, count - 1])
    elif op == "block_loop_end":
        if not fr.block_loops:
            ex.fail(dg.MACRO_END_WITHOUT_DO, span, f"{c.name} without a G22 that opens the loop")
            return
        top = fr.block_loops[-1]
        if top[1] > 0:
            top[1] -= 1
            fr.pc = top[0] + 1
        else:
            fr.block_loops.pop()
    elif op in ("input_wait_on", "input_wait_off"):
        _input_test(ex, fr, i, c, w, words, span)
    elif op == "program_restart":
        ex.end_program(span)


def _word(words: tuple[Word, ...], letter: str) -> Word | None:
    found = None
    for w in words:
        if w.letter == letter:
            found = w
    return found


def _label(w: Word) -> int:
    return round(w.value)


def _count(ex: Executor, words: tuple[Word, ...], span: Span) -> int | None:
    lw = _word(words, "L")
    if lw is None:
        return 1
    n = int(lw.value)
    if n != lw.value or n < 0 or n > 99999:
        ex.emit(dg.MACRO_BAD_CALL, span,
                f"L{lw.value:g}: the repeat count must be a whole number 0 to 99999; the call is skipped")
        return None
    return n


def _program(ex: Executor, words: tuple[Word, ...], names: list[ProgramName]) -> tuple[str, str] | None:
    """(lookup key, name as written) of the called program, from P or a program name."""
    if names:
        text = szgh_name(names[-1].text)
        return program_key(text), text
    p = _word(words, "P")
    if p is None:
        return None
    if p.value != int(p.value) or p.value < 0:
        return None
    return program_key(p.value), f"O{int(p.value):04d}"


def szgh_name(text: str) -> str:
    """SZGH program names: ``*01`` is ``HIDEFILE01``; ``[`` / ``]`` (USB disk) are dropped."""
    name = text.strip().strip("[]").strip()
    if name.startswith("*"):
        name = "HIDEFILE" + name[1:]
    return name


def push_call(ex: Executor, fr: CallFrame, kind: str, unit: Unit, index: int, repeats: int,
              args: dict[int, float] | None, span: Span, name: str) -> None:
    if repeats <= 0:
        return
    if not _depth_ok(ex, kind, span):
        return
    first, last = unit.section_range(index)
    new = CallFrame(unit, first, last, index, index, kind, span, name, repeats - 1, args is not None,
                    dict(args or {}), [], fr.in_modal or kind == "G66")
    if args is not None:
        ex.vars.push_scope(args)
    ex.stack.append(new)
    call_marker(ex, new, "call_begin")


def call_marker(ex: Executor, fr: CallFrame, name: str) -> None:
    """Record where a run of a called program begins or ends (translation keeps subprograms)."""
    if ex.opts.call_markers and fr.call_span is not None:
        key = f"{fr.unit.source.source_id}:{fr.entry}"
        ex.out.append(CallBoundary(fr.call_span, ex.it.frame, name == "call_begin", key, fr.name))


def _depth_ok(ex: Executor, kind: str, span: Span) -> bool:
    d = ex.dialect
    if ex.flavour == "szgh":
        limit = int(d.raw.get("macro", {}).get("max_call_depth", 4))
        depth = len(ex.stack) - 1
        what = "calls"
    elif kind in MACRO_KINDS:
        limit = int(d.option("max_macro_depth", 4))
        depth = sum(1 for f in ex.stack if f.kind in MACRO_KINDS)
        what = "macro calls (G65/G66)"
    else:
        limit = int(d.option("max_subprogram_depth", 4))
        depth = sum(1 for f in ex.stack if f.kind == "M98")
        what = "subprogram calls (M98)"
    if depth >= limit:
        ex.fail(dg.MACRO_NESTING, span, f"{what} nested more than {limit} deep")
        return False
    return True


def _subprogram_call(ex: Executor, fr: CallFrame, words: tuple[Word, ...], names: list[ProgramName],
                     span: Span) -> None:
    repeats = _count(ex, words, span)
    if repeats is None:
        return
    prog = _program(ex, words, names)
    h = _word(words, "H")
    p = _word(words, "P")
    if prog is None and not names and p is not None:
        ex.emit(dg.MACRO_BAD_CALL, span, f"P{p.value:g} is not a program number; the call is skipped")
        return
    if prog is not None and ex.flavour == "fanuc" and _word(words, "L") is None and prog[0].isdigit() \
            and int(prog[0]) > 9999:
        repeats, number = divmod(int(prog[0]), 10000)  # Fanuc: M98 P50010 = five calls of O0010
        prog = (str(number), f"O{number:04d}")
    if prog is None and h is None:
        ex.emit(dg.MACRO_BAD_CALL, span,
                "M98 needs P (the program) or H (a sequence number of this program); the call is skipped")
        return
    if prog is not None:
        found = ex.find_program(fr, prog[0], prog[1], span)
        if found is None:
            return
        unit, index = found
        name = prog[1]
    else:
        unit, index, name = fr.unit, fr.first, "this program"
    if h is not None:
        target = unit.find_label(_label(h), index)
        if target is None:
            ex.fail(dg.MACRO_NO_LABEL, span, f"there is no block N{_label(h)} in {name} to call")
            return
        index, name = target, f"N{_label(h)}"
    push_call(ex, fr, "M98", unit, index, repeats, None, span, name)


def _local_call(ex: Executor, fr: CallFrame, c: CodeDef, words: tuple[Word, ...], span: Span) -> None:
    """Haas ``M97 P_ L_``: run the blocks from ``N<P>`` of this file to its M99, L times."""
    repeats = _count(ex, words, span)
    p = _word(words, "P")
    if repeats is None:
        return
    if p is None or p.value != int(p.value) or p.value < 0:
        ex.fail(dg.MACRO_BAD_CALL, span, f"{c.name} needs P, the sequence number of the local subprogram")
        return
    target = fr.unit.find_label(_label(p), fr.first)
    if target is None:
        ex.fail(dg.MACRO_NO_LABEL, span, f"there is no block N{_label(p)} in this program to call")
        return
    push_call(ex, fr, "M98", fr.unit, target, repeats, None, span, f"N{_label(p)}")


def _macro_call(ex: Executor, fr: CallFrame, words: tuple[Word, ...], by_op: dict[str, tuple[Word, CodeDef]],
                names: list[ProgramName], span: Span) -> None:
    repeats = _count(ex, words, span)
    if repeats is None:
        return
    if "macro_call" in by_op:
        kind = "G65"
        trigger = by_op["macro_call"][0]
        prog = _program(ex, words, names)
        if prog is None:
            ex.emit(dg.MACRO_BAD_CALL, span, "G65 needs P, the macro program to call; the call is skipped")
            return
    else:
        kind = "user"
        trigger, c = by_op["user_macro"]
        macro = ex.dialect.raw.get("macro", {})
        template = str(macro.get("user_g_program" if c.letter == "G" else "user_m_program", "O{n}"))
        text = template.format(n=c.index)
        prog = (program_key(text), text)
        repeats = 1
    found = ex.find_program(fr, prog[0], prog[1], span)
    if found is None:
        return
    args = arguments(ex, tuple(w for w in words if w is not trigger))
    push_call(ex, fr, kind, found[0], found[1], repeats, args, span, prog[1])


def _modal_setup(ex: Executor, fr: CallFrame, words: tuple[Word, ...], names: list[ProgramName],
                 span: Span) -> None:
    repeats = _count(ex, words, span)
    prog = _program(ex, words, names)
    if repeats is None:
        return
    if prog is None:
        ex.emit(dg.MACRO_BAD_CALL, span, "G66 needs P, the macro program to call; the call is skipped")
        return
    found = ex.find_program(fr, prog[0], prog[1], span)
    if found is None:
        return
    args = arguments(ex, tuple(w for w in words if w.letter != "G"))
    ex.modal = ModalCall(found[0], found[1], prog[1], repeats, args, span)
    if ex.dialect.option("g66_block_calls", False):
        call_modal(ex, fr, dict(args), span)


def call_modal(ex: Executor, fr: CallFrame, args: dict[int, float], span: Span) -> None:
    """Invoke the G66 macro after a block (``span``) that moved."""
    m = ex.modal
    if m is None:
        return
    push_call(ex, fr, "G66", m.unit, m.index, m.repeats, args, span, m.name)


def do_return(ex: Executor, fr: CallFrame, label: int | None, span: Span) -> None:
    if fr.kind == "main":
        if label is not None:
            ex.goto(fr, fr.pc - 1, float(label), span)
        elif ex.dialect.option("m99_in_main", "end") == "loop":
            fr.pc = fr.entry
        else:
            ex.end_program(span)
        return
    call_marker(ex, fr, "call_end")
    if fr.repeats_left > 0 and label is None:
        call_marker(ex, fr, "call_begin")
        fr.repeats_left -= 1
        fr.pc = fr.entry
        fr.block_loops.clear()
        if fr.scoped:
            ex.vars.pop_scope()
            ex.vars.push_scope(fr.args)
        return
    ex.stack.pop()
    if fr.scoped:
        ex.vars.pop_scope()
    if label is None or not ex.stack:
        return
    caller = ex.stack[-1]
    target = caller.unit.find_label(label, caller.pc)
    if target is None or not caller.first <= target < caller.last:
        ex.fail(dg.MACRO_NO_LABEL, span, f"M99 P{label}: the calling program has no block N{label}")
        return
    caller.pc = target


def arguments(ex: Executor, words: tuple[Word, ...]) -> dict[int, float]:
    """Argument words -> local variables (Fanuc specification I, or II for repeated
    I/J/K; SZGH A->#0 ... Z->#20).  An integer written without a decimal point is in
    least input units where the dialect's LIU rule says so."""
    mapping = ex.vars.layout.arguments
    counts = {c: sum(1 for w in words if w.letter == c) for c in "IJK"}
    type2 = ex.flavour == "fanuc" and max(counts.values()) > 1
    out: dict[int, float] = {}
    set_k, last_pos = -1, 3
    for w in words:
        letter = w.letter
        if letter in NOT_ARGUMENT_LETTERS:
            continue
        v = _argument_value(ex, w)
        if type2 and letter in "IJK":
            pos = "IJK".index(letter)
            if pos <= last_pos:
                set_k += 1
            last_pos = pos
            if set_k >= 10:
                raise MacroError(dg.MACRO_BAD_CALL, "more than ten I/J/K argument sets", w.start, w.end)
            out[4 + 3 * set_k + pos] = v
            continue
        n = mapping.get(letter)
        if n is not None:
            out[n] = v
    return out


NOT_ARGUMENT_LETTERS = frozenset("GLNOP")


def _argument_value(ex: Executor, w: Word) -> float:
    d = ex.dialect
    if d.decimal_rule != "liu" or w.point:
        return w.value
    kind = d.addresses.get(w.letter, "real")
    if kind == "length":
        from cncc.ir import Units

        key = "length_inch" if ex.it.frame.units is Units.INCH else "length_mm"
        return w.value * d.liu.get(key, 0.001)
    if kind == "angle":
        return w.value * d.liu.get("angle_deg", 0.001)
    return w.value


def input_test_name(c: CodeDef, w: Word) -> str:
    if c.tenths >= 18000:  # M18nn / M28nn: input Xnn
        return f"X{(c.tenths // 10) % 100:02d}"
    return f"M{c.index}"


def _input_test(ex: Executor, fr: CallFrame, i: int, c: CodeDef, w: Word, words: tuple[Word, ...],
                span: Span) -> None:
    want_valid = c.op == "input_wait_on"
    name = input_test_name(c, w)
    p = _word(words, "P")
    state = ex.io.input_valid(name)
    if p is not None:
        if state is not None and state == want_valid:
            ex.goto(fr, i, p.value, span)
        return
    if state is not None and state != want_valid:
        ex.fail(dg.MACRO_INPUT_TIMEOUT, span,
                f"{c.name} waits for input {name} to be {'valid' if want_valid else 'invalid'}, "
                f"which the --io file never makes it")
        return
    ex.out.append(Wait(span, ex.it.frame, f"{name} {'valid' if want_valid else 'invalid'}"))
