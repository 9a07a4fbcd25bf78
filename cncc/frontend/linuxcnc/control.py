"""O-word statements and M98/M99 of a running LinuxCNC program.

Consumes one ``O<label> keyword [args]`` line (or an M98/M99 word) and moves the
executor's program counter or call stack.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from cncc import diagnostics as dg
from cncc.frontend.linuxcnc.builder import OWord
from cncc.frontend.syntax import Block, Word
from cncc.source import Span

if TYPE_CHECKING:
    from cncc.frontend.linuxcnc.executor import Frame, LinuxcncExecutor


def run_oword(ex: LinuxcncExecutor, fr: Frame, i: int, ow: OWord) -> None:
    fx = fr.index
    if ow.label_expr is not None:  # a computed number: only a call can have one
        from dataclasses import replace

        span = fx.span_of(ow.start, ow.end)
        if ow.keyword != "call":
            ex.fail(dg.OWORD_STRUCTURE, span, f"a computed O number is only allowed with call, not {ow.keyword}")
            return
        ow = replace(ow, label=str(round(ex.ev.number(ow.label_expr))), label_expr=None)
    kw = ow.keyword
    args = [ex.ev.number(a) for a in ow.args]
    span = fx.span_of(ow.start, ow.end)
    if kw == "":
        return  # a bare O<number> or O<name> line names the program (an M98 target); running it does nothing
    if kw == "sub":
        fr.pc = fx.subs[ow.label][1] + 1  # a definition met in the flow is skipped
    elif kw in ("endsub", "return"):
        _return(ex, fr, ow, args, span)
    elif kw == "call":
        _call(ex, fr, ow, args, span)
    elif kw in ("if", "elseif"):
        if kw == "if":
            fr.repeats.pop(-fx.endif[i] - 1, None)  # a fresh if: no branch taken yet
        if not args:
            ex.fail(dg.OWORD_STRUCTURE, span, f"o{ow.label} {kw} needs a condition [ ... ]")
        elif kw == "elseif" and _came_from_branch(fr, i):
            fr.pc = fx.endif[i] + 1
        elif args[0] != 0.0:
            _mark_taken(fr, fx.endif[i])
        else:
            fr.pc = fx.next_branch[i]
    elif kw == "else":
        if _came_from_branch(fr, i):
            fr.pc = fx.endif[i] + 1
        else:
            _mark_taken(fr, fx.endif[i])
    elif kw == "endif":
        fr.repeats.pop(-i - 1, None)  # the branch marker of this if
    else:
        _loop_word(ex, fr, i, ow, args, span)


# An if branch that was entered marks its endif (key -endif-1 in the frame's counters), so
# that reaching a later elseif/else line jumps to the endif.
def _mark_taken(fr: Frame, endif: int) -> None:
    fr.repeats[-endif - 1] = 1


def _came_from_branch(fr: Frame, i: int) -> bool:
    endif = fr.index.endif[i]
    return fr.repeats.get(-endif - 1) == 1


def _loop_word(ex: LinuxcncExecutor, fr: Frame, i: int, ow: OWord, args: list[float], span: Span) -> None:
    fx, kw = fr.index, ow.keyword
    lp = fx.loop_at.get(i)
    if kw in ("break", "continue"):
        lp = fx.enclosing_loop(ow.label, i)
        if lp is None:
            ex.fail(dg.OWORD_STRUCTURE, span, f"o{ow.label} {kw} is not inside a loop labelled o{ow.label}")
            return
        if kw == "break":
            fr.repeats.pop(lp.head, None)
            fr.pc = lp.end + 1
        else:
            fr.pc = lp.end if lp.kind in ("do", "repeat") else lp.head
        return
    assert lp is not None
    if kw == "do":
        return
    if kw == "while" and lp.kind == "do":  # the closing while of do ... while
        if args and args[0] != 0.0:
            fr.pc = lp.head + 1
        return
    if kw == "while":
        if not args:
            ex.fail(dg.OWORD_STRUCTURE, span, f"o{ow.label} while needs a condition [ ... ]")
        elif args[0] == 0.0:
            fr.pc = lp.end + 1
        return
    if kw == "endwhile":
        fr.pc = lp.head
        return
    if kw == "repeat":
        _repeat(ex, fr, i, ow, args, lp.end)
        return
    if kw == "endrepeat":
        fr.pc = lp.head


def _repeat(ex: LinuxcncExecutor, fr: Frame, i: int, ow: OWord, args: list[float], end: int) -> None:
    """``oN repeat [n]``: the count left is kept per frame; 2.9 has no break/continue for repeat."""
    fx = fr.index
    jump = fx.repeat_jumps.get(i)
    if jump is not None:
        ex.fail(dg.OWORD_STRUCTURE, fx.span(fx.blocks[jump]), f"no matching while/do label: 'o{ow.label} "
                f"{fx.owords[jump].keyword}' (o{ow.label} is a repeat loop: break and continue are for while "
                "and do)")
        return
    left = fr.repeats.get(i)
    if left is None:
        left = round(args[0]) if args else 0
    if left <= 0:
        fr.repeats.pop(i, None)
        fr.pc = end + 1
    else:
        fr.repeats[i] = left - 1


def _call(ex: LinuxcncExecutor, fr: Frame, ow: OWord, args: list[float], span: Span) -> None:
    from cncc.frontend.linuxcnc.frames import Frame

    index = fr.index
    found = index.subs.get(ow.label)
    if found is None and ow.label in index.programs:
        ex.fail(dg.SUB_STYLE_MIXED, span, f"O{ow.label} is a program number (O{ow.label} ... M99): call it with M98")
        return
    if found is None:
        name = ow.label.strip("<>")
        loaded = ex.load_sub(name)
        if loaded is None or ow.label not in loaded.subs:
            ex.fail(dg.OWORD_NO_SUB, span, f"o{ow.label} is not defined in this file or as {name}.ngc in an -I "
                    "folder", name)
            return
        index, found = loaded, loaded.subs[ow.label]
    if len(ex.stack) > ex.max_depth:
        ex.fail(dg.MACRO_NESTING, span, f"subroutine calls nested deeper than {ex.max_depth}")
        return
    ex.push_scope(args)
    ex.stack.append(Frame(index, found[0] + 1, ow.label, fr.pc, fr, span))


def _return(ex: LinuxcncExecutor, fr: Frame, ow: OWord, args: list[float], span: Span) -> None:
    if fr.caller is None or fr.name != ow.label:
        if fr.caller is None:
            ex.fail(dg.OWORD_STRUCTURE, span, f"o{ow.label} {ow.keyword} outside a subroutine call")
        else:
            ex.fail(dg.OWORD_STRUCTURE, span, f"o{ow.label} {ow.keyword} inside the subroutine o{fr.name}")
        return
    ex.pop_scope()
    ex.stack.pop()
    ex.params.globals_named["_value"] = args[0] if args else 0.0
    ex.params.globals_named["_value_returned"] = 1.0 if args else 0.0


def m98_block(ex: LinuxcncExecutor, fr: Frame, block: Block, words: tuple[Word, ...]) -> tuple[Word, ...]:
    """A block with M98 or M99, as rs274 2.9 reads it; the words left to run as an ordinary block.

    M98 is read only as the block's first word (after N): the call, every other word of the block
    ignored; anywhere else it is an unknown M code.  M99 alone returns from an M98 program; in the
    main program it ends the program as M2 does (the rest of the block runs)."""
    lead = next((w for w in words if w.letter != "N"), None)
    span = fr.index.span(block)
    for w in words:
        if w.letter != "M" or round(w.value) not in (98, 99):
            continue
        if round(w.value) == 98:
            if w is not lead:
                ex.fail(dg.UNKNOWN_M, ex.it.word_span(w), "M98 must be the first word of its block (LinuxCNC reads "
                        "it nowhere else)")
                return ()
            if ex.reporter.allowed(span, words):  # its other words are not run, but a stray Q is an error
                run_m98(ex, fr, block, words, w)
            return ()
        if fr.caller is None:  # M99 in the main program: the end of the program
            return tuple(Word("M", 2.0, False, x.start, x.end) if x is w else x for x in words)
        if any(x.letter not in "NM" or (x is not w and x.letter == "M") for x in words):
            ex.fail(dg.SUB_STYLE_MIXED, span, "M99 must stand alone in its block to return from a subprogram")
            return ()
        run_m98(ex, fr, block, words, w)
        return ()
    return words


def run_m98(ex: LinuxcncExecutor, fr: Frame, block: Block, words: tuple[Word, ...], m: Word) -> None:
    """Fanuc-style M98 P<n> L<count> (call program O<n> of this file) and M99 (return)."""
    from cncc.frontend.linuxcnc.frames import Frame

    span = fr.index.span(block)
    if round(m.value) == 99:
        if fr.caller is None:
            ex.it.ended = True  # M99 in the main program ends it (cncc does not restart it)
            return
        if not fr.m98_count:
            ex.fail(dg.SUB_STYLE_MIXED, span, f"M99 cannot end o{fr.name} sub: it ends with o{fr.name} endsub or "
                    "return")
            return
        if fr.m98_count > 1:
            fr.m98_count -= 1
            fr.pc = fr.m98_start
            return
        ex.stack.pop()
        return
    pw = next((w for w in words if w.letter == "P"), None)
    lw = next((w for w in words if w.letter == "L"), None)
    if pw is None:
        ex.fail(dg.MACRO_BAD_CALL, span, "M98 needs P, the program number")
        return
    for w in (pw, lw):
        if w is not None and w.value != int(w.value):
            ex.fail(dg.MACRO_BAD_CALL, ex.it.word_span(w), f"M98 {w.letter} must be a whole number")
            return
    if lw is not None and lw.value < 0:
        ex.fail(dg.MACRO_BAD_CALL, ex.it.word_span(lw), "M98 with a negative L")
        return
    label = str(round(pw.value))
    start = fr.index.programs.get(label)
    if start is None and label in fr.index.subs:
        ex.fail(dg.SUB_STYLE_MIXED, span, f"M98 P{label}: o{label} is an O-word subroutine: call it with o{label} "
                "call")
        return
    if start is None:
        ex.fail(dg.OWORD_NO_SUB, span, f"M98 P{label}: there is no O{label} in this file", label)
        return
    count = round(lw.value) if lw is not None else 1
    if count < 1:
        return
    if len(ex.stack) > ex.max_depth:
        ex.fail(dg.MACRO_NESTING, span, f"subprogram calls nested deeper than {ex.max_depth}")
        return
    new = Frame(fr.index, start + 1, label, fr.pc, fr, span, m98_count=count, m98_start=start + 1)
    ex.stack.append(new)
