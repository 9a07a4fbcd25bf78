"""Completion of codes and words that make sense at the cursor.

The modal context is read lexically: the dialect's power-on codes, then every G
code above the cursor updates its modal group.  After ``G``/``M`` the server
offers the dialect's codes, leaving out those whose modal group already has a code
in this block and marking the one already in force.  Elsewhere it offers the
address letters the block's codes and the motion in force read (I J K R for an arc,
R Q P for a drilling cycle, P H L for a call ...).
"""

from __future__ import annotations

from dataclasses import dataclass

from cncc.dialects import CodeDef, Dialect
from cncc.lsp.hover import LETTERS
from cncc.lsp.positions import LineIndex
from cncc.lsp.scan import Comments, Token, in_comment, tokens

AXES = ("X", "Y", "Z")
# Address letters read by an operation (beyond the axes when the op moves).
OP_WORDS: dict[str, tuple[str, ...]] = {
    "rapid": AXES,
    "linear": (*AXES, "F"),
    "arc_cw": (*AXES, "I", "J", "K", "R", "F"),
    "arc_ccw": (*AXES, "I", "J", "K", "R", "F"),
    "cycle": (*AXES, "R", "Q", "P", "F", "K", "L"),
    "dwell": ("X", "P"),
    "comp_left": ("D",), "comp_right": ("D",),
    "length_plus": ("H",), "length_minus": ("H",),
    "subprogram_call": ("P", "H", "L"), "subprogram_return": ("P",),
    "macro_call": ("P", "L", "A", "B", "C", "I", "J", "K"), "modal_call": ("P", "L"),
    "data_input": ("L", "P", "R", *AXES),
    "local_offset": AXES, "set_origin": AXES, "home": AXES, "home2": (*AXES, "P"),
    "rotate_on": ("X", "Y", "R"), "scale_on": (*AXES, "P", "I", "J", "K"), "mirror_on": AXES,
    "tool_change": ("T",), "spindle_cw": ("S",), "spindle_ccw": ("S",),
    "thread": (*AXES, "F"),
}


@dataclass(frozen=True, slots=True)
class Item:
    label: str
    detail: str
    doc: str
    kind: str  # "code" or "word"
    sort: str
    start: int  # offsets of the text the item replaces
    end: int


def modal_context(index: LineIndex, dialect: Dialect, line: int) -> dict[str, CodeDef]:
    """The G codes in force (by modal group) at the start of 0-based ``line``."""
    state: dict[str, CodeDef] = {}
    for group, name in dialect.defaults.items():
        cdef = _by_name(dialect, name)
        if cdef is not None:
            state[group] = cdef
    comments = Comments.of(dialect)
    for ln in range(max(0, line - 100_000), line):
        text = index.line_text(ln)
        if "G" not in text and "g" not in text:
            continue
        for tok in tokens(text, 0, comments):
            if tok.kind == "word" and tok.text == "G" and tok.tenths is not None:
                cdef = dialect.code("G", tok.tenths)
                if cdef is not None and cdef.group != "non_modal":
                    state[cdef.group] = cdef
    return state


def _by_name(dialect: Dialect, name: str) -> CodeDef | None:
    from cncc.dialects import code_tenths

    return dialect.code(name[0], code_tenths(name[1:])) if len(name) > 1 else None


def complete(index: LineIndex, dialect: Dialect, offset: int) -> list[Item]:
    line = index.line_of(offset)
    base = index.line_start(line)
    text = index.line_text(line)
    col = offset - base
    comments = Comments.of(dialect)
    if in_comment(text, col, comments):
        return []
    toks = list(tokens(text, base, comments))
    here = next((t for t in toks if t.start < offset <= t.end and t.kind == "word"), None)
    others = [t for t in toks if t is not here]
    state = modal_context(index, dialect, line)
    if here is not None and here.text in "GM" and offset > here.start:
        return _codes(dialect, here, others, state)
    start = here.start if here is not None else offset
    return _words(dialect, others, state, start, offset)


def _codes(dialect: Dialect, here: Token, others: list[Token], state: dict[str, CodeDef]) -> list[Item]:
    used_groups = set()
    for t in others:
        if t.kind == "word" and t.text in "GM" and t.tenths is not None:
            cdef = dialect.code(t.text, t.tenths)
            if cdef is not None and cdef.group != "non_modal":
                used_groups.add(cdef.group)
    items = []
    for cdef in sorted(dialect.codes.values(), key=lambda c: c.tenths):
        if cdef.letter != here.text:
            continue
        if cdef.letter == "G" and cdef.group in used_groups:
            continue
        in_force = state.get(cdef.group) is cdef
        detail = f"{cdef.group}" + (" — in force" if in_force else "")
        items.append(Item(cdef.name, detail, cdef.summary, "code", f"{1 if in_force else 0}{cdef.tenths:06d}",
                          here.start, here.end))
    return items


def _words(dialect: Dialect, others: list[Token], state: dict[str, CodeDef], start: int, end: int) -> list[Item]:
    present = {t.text for t in others if t.kind == "word"}
    ops = []
    for t in others:
        if t.kind == "word" and t.text in "GM" and t.tenths is not None:
            cdef = dialect.code(t.text, t.tenths)
            if cdef is not None:
                ops.append(cdef.op)
    motion = state.get("motion")
    cycle = state.get("cycle")
    if not any(op in OP_WORDS for op in ops):
        if cycle is not None and cycle.op == "cycle":
            ops.append("cycle")
        elif motion is not None:
            ops.append(motion.op)
    wanted: list[str] = []
    for op in ops:
        for letter in OP_WORDS.get(op, ()):
            if letter not in wanted:
                wanted.append(letter)
    items = []
    for rank, letter in enumerate([*wanted, "G", "M"]):
        if letter in present and letter not in "GM":
            continue
        why = "read by " + ", ".join(sorted(set(ops))) if letter in wanted else "code"
        items.append(Item(letter, why, LETTERS.get(letter, ""), "word", f"{rank:03d}", start, end))
    for letter in ("N", "S", "T", "F"):
        if letter not in present and letter not in wanted:
            items.append(Item(letter, "address", LETTERS.get(letter, ""), "word", f"9{letter}", start, end))
    return items
