"""Syntax tree: what was written, with character offsets, and no machine meaning.

The parser produces one :class:`Block` per block of the program.  Offsets are
absolute character offsets in the source text (``start``/``end``), so spans are
built without recomputation.
"""

from __future__ import annotations

from dataclasses import dataclass


# ---- expressions (macro languages) ------------------------------------------------
@dataclass(frozen=True, slots=True)
class Num:
    value: float
    point: bool
    start: int
    end: int


@dataclass(frozen=True, slots=True)
class Var:
    """``#n`` (``index`` a :class:`Num`), ``#[expr]``, or a named ``#<name>``."""

    index: Expr | None
    start: int
    end: int
    name: str = ""


@dataclass(frozen=True, slots=True)
class Neg:
    operand: Expr
    start: int
    end: int


@dataclass(frozen=True, slots=True)
class BinOp:
    op: str  # upper-case: + - * / AND OR XOR MOD EQ NE GT GE LT LE
    left: Expr
    right: Expr
    start: int
    end: int


@dataclass(frozen=True, slots=True)
class Call:
    func: str  # upper-case function name
    args: tuple[Expr, ...]
    start: int
    end: int


Expr = Num | Var | Neg | BinOp | Call


# ---- block items --------------------------------------------------------------
@dataclass(frozen=True, slots=True)
class Word:
    """An address letter and its value.

    For a plain number, ``value`` is the number and ``point`` says whether it was
    written with a decimal point (the LIU rule needs to know); ``expr`` is None.
    For a macro value (``X#1``, ``X[#1+2]``) ``expr`` holds the expression.
    """

    letter: str
    value: float
    point: bool
    start: int
    end: int
    expr: Expr | None = None


@dataclass(frozen=True, slots=True)
class CommentItem:
    text: str
    start: int
    end: int


@dataclass(frozen=True, slots=True)
class Assign:
    target: Var
    expr: Expr
    start: int
    end: int


@dataclass(frozen=True, slots=True)
class Goto:
    target: Expr
    start: int
    end: int


@dataclass(frozen=True, slots=True)
class If:
    cond: Expr
    then: Goto | Assign | tuple[Word, ...]
    start: int
    end: int


@dataclass(frozen=True, slots=True)
class While:
    cond: Expr
    loop_id: int
    start: int
    end: int


@dataclass(frozen=True, slots=True)
class EndLoop:
    loop_id: int
    start: int
    end: int


Statement = Assign | Goto | If | While | EndLoop


@dataclass(frozen=True, slots=True)
class Block:
    """One block: its words in order, comments, macro statements and flags."""

    line: int  # 1-based line number
    start: int
    end: int
    words: tuple[Word, ...]
    comments: tuple[CommentItem, ...] = ()
    statements: tuple[Statement, ...] = ()
    block_delete: int = 0  # 0: none, 1..9: the '/n' level (plain '/' is 1)
    percent: bool = False

    @property
    def is_empty(self) -> bool:
        return not self.words and not self.statements and not self.comments
