"""What a target dialect can write: a :class:`Target` read from a dialect's tables.

Consumes a :class:`cncc.dialects.Dialect`; produces the reverse tables the emitter
needs (canonical op -> code name, work index -> code, cycle kind -> code), the
number format, the comment and block-end syntax, the arc forms and the limits.

Almost everything is derived from the tables the front end already reads (codes,
word kinds, comments, block end, the decimal-point rule, options).  What only an
emitter needs lives in the dialect's optional ``[emit]`` table; every key has a
default, so a new dialect file works as a target without one (``docs/translation.md``
lists the keys):

``arc_form``              ``"ijk"`` (default) or ``"r"``: how arcs are written
``arc_single_quadrant``   arcs split at quadrant boundaries, I/J unsigned (Series 8)
``full_circle``           a full circle may be one block (default true)
``arc_turns_word``        letter for extra helix turns (default none: split)
``max_line_length``       characters per line the control reads (0: no limit)
``line_length_counts``    ``"all"`` or ``"words"`` (grbl counts without spaces/comments)
``max_line_number``       largest N number (default 99999)
``program_numbers``       ``[low, high]`` O numbers (default [1, 9999])
``max_call_depth``        subprogram nesting (default: option ``max_call_depth`` or ``max_subprogram_depth``, else
                          ``[macro] max_call_depth``, else 4)
``subprogram_form``       kept subprograms: ``"m98"`` (default: M98 P / O...M99 after the main
                          program) or ``"oword"`` (LinuxCNC o<n> sub/endsub/call before it)
``percent``               wrap the program in ``%`` lines (default false)
``prefer``                code names that win when several codes share one op
``ops``                   ``{ dwell = "G04" }``: the code that means a canonical op when the
                          dialect's own op name differs (a code with its own front-end handler)
``decimals_mm`` / ``decimals_inch``  default output precision (3 / 4)
``word_max``              per-letter largest value, e.g. ``{ T = 255 }`` (T: option ``max_tool_number``)
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from cncc.dialects import CodeDef, Dialect, code_tenths


@dataclass(frozen=True, slots=True)
class Target:
    """A dialect seen from the emitter."""

    dialect: Dialect
    by_op: dict[str, CodeDef]
    work: dict[int, CodeDef]
    cycles: dict[str, CodeDef]
    arc_form: str = "ijk"
    single_quadrant: bool = False
    full_circle: bool = True
    turns_word: str = ""
    max_line_length: int = 0
    count_words_only: bool = False
    max_line_number: int = 99999
    program_numbers: tuple[int, int] = (1, 9999)
    max_call_depth: int = 4
    percent: bool = False
    decimals_mm: int = 3
    decimals_inch: int = 4
    word_max: dict[str, float] = field(default_factory=dict)

    @property
    def name(self) -> str:
        return self.dialect.name

    def code(self, op: str) -> str:
        """The code name for ``op`` ("" when the target has none)."""
        c = self.by_op.get(op)
        return c.name if c is not None else ""

    def has(self, op: str) -> bool:
        return op in self.by_op

    @property
    def liu(self) -> bool:
        """Integers without a point are least input units (so lengths always get a point)."""
        return self.dialect.decimal_rule == "liu"

    def comment(self, text: str) -> str:
        """``text`` in the target's comment syntax (parentheses inside are made square)."""
        styles = self.dialect.comments
        if "paren" in styles:
            return "(" + text.replace("(", "[").replace(")", "]") + ")"
        if "semi" in styles:
            return "; " + text
        if "slash" in styles:
            return "// " + text
        return ""

    def option(self, key: str, default: Any = None) -> Any:
        return self.dialect.option(key, default)


def _rank(c: CodeDef, prefer: list[str]) -> tuple[int, int, int]:
    """Sort key among codes with one op: listed in ``prefer`` first, then whole numbers, then higher."""
    listed = prefer.index(c.name) if c.name in prefer else len(prefer)
    return (listed, 1 if c.tenths % 10 else 0, -c.tenths)


def make_target(dialect: Dialect) -> Target:
    emit: dict[str, Any] = dict(dialect.raw.get("emit", {}))
    prefer = [str(p) for p in emit.get("prefer", [])]
    by_op: dict[str, CodeDef] = {}
    work: dict[int, CodeDef] = {}
    cycles: dict[str, CodeDef] = {}
    for cdef in sorted(dialect.codes.values(), key=lambda c: _rank(c, prefer)):
        if cdef.op == "work" and cdef.index:
            work.setdefault(cdef.index, cdef)
        if cdef.op == "cycle" and cdef.cycle:
            cycles.setdefault(cdef.cycle, cdef)
        by_op.setdefault(cdef.op, cdef)
    for op, name in dict(emit.get("ops", {})).items():  # canonical op -> the code that means it here
        letter, number = str(name)[:1].upper(), str(name)[1:]
        found = dialect.code(letter, code_tenths(number)) if number else None
        if found is not None:
            by_op[str(op)] = found
    macro: dict[str, Any] = dict(dialect.raw.get("macro", {}))
    numbers = emit.get("program_numbers", [1, 9999])
    return Target(
        dialect=dialect, by_op=by_op, work=work, cycles=cycles,
        arc_form=str(emit.get("arc_form", "ijk")),
        single_quadrant=bool(emit.get("arc_single_quadrant", False)),
        full_circle=bool(emit.get("full_circle", True)),
        turns_word=str(emit.get("arc_turns_word", "")),
        max_line_length=int(emit.get("max_line_length", dialect.option("line_max_chars", 0))),
        count_words_only=str(emit.get("line_length_counts", "words" if dialect.option("line_max_chars") else "all"))
        == "words",
        max_line_number=int(emit.get("max_line_number", dialect.option("max_line_number", 99999)) or 99999),
        program_numbers=(int(numbers[0]), int(numbers[1])),
        max_call_depth=int(emit.get("max_call_depth", _call_depth(dialect, macro))),
        percent=bool(emit.get("percent", False)),
        decimals_mm=int(emit.get("decimals_mm", 3)),
        decimals_inch=int(emit.get("decimals_inch", 4)),
        word_max=_word_max(dialect, emit),
    )


def _call_depth(dialect: Dialect, macro: dict[str, Any]) -> int:
    """Nesting of called programs: option max_call_depth, max_subprogram_depth, [macro] max_call_depth, 4."""
    return int(dialect.option("max_call_depth", dialect.option("max_subprogram_depth", macro.get("max_call_depth", 4))))


def _word_max(dialect: Dialect, emit: dict[str, Any]) -> dict[str, float]:
    out = {str(k): float(v) for k, v in dict(emit.get("word_max", {})).items()}
    tools = dialect.option("max_tool_number")
    if tools is not None:
        out.setdefault("T", float(tools))
    return out
