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


# ---- SZGH macro statements (cncc/grammar/szgh.lark) ---------------------------
@dataclass(frozen=True, slots=True)
class ProgramName:
    """A program named by text (``M98 PHIDEFILE01``, ``Psub/1390``, ``PP[FFDE``).

    ``call`` is True for the ``PP name`` short form, which is a call by itself.
    """

    text: str
    call: bool
    start: int
    end: int


@dataclass(frozen=True, slots=True)
class IfBlock:
    """``IF (cond)`` alone: opens an IF ... [ELIF ...] [ELSE ...] ENDIF block."""

    cond: Expr
    start: int
    end: int


@dataclass(frozen=True, slots=True)
class ElseIf:
    cond: Expr | None  # None: a bare ELIF (read as ELSE)
    start: int
    end: int


@dataclass(frozen=True, slots=True)
class Else:
    start: int
    end: int


@dataclass(frozen=True, slots=True)
class EndIf:
    start: int
    end: int


@dataclass(frozen=True, slots=True)
class IoWait:
    """``WAT+X12`` (wait until input X12 is valid) / ``WAT-X12`` (invalid)."""

    valid: bool
    signal: str  # e.g. "X12"
    start: int
    end: int


@dataclass(frozen=True, slots=True)
class IoOut:
    """``OUT+Y03`` / ``OUT-Y03``: switch an output on / off."""

    on: bool
    signal: str
    start: int
    end: int


@dataclass(frozen=True, slots=True)
class MessageStmt:
    """``MSG(text)`` (show and pause) or ``STAF(text)`` (show, go on)."""

    text: str
    pause: bool
    start: int
    end: int


@dataclass(frozen=True, slots=True)
class FileStmt:
    """``FILEON(name) FILEWD(blocks) FILEWC FILECE FILEMS(name)``."""

    op: str  # "FILEON" ...
    arg: str
    start: int
    end: int


Statement = (Assign | Goto | If | While | EndLoop | ProgramName | IfBlock | ElseIf | Else | EndIf | IoWait | IoOut
             | MessageStmt | FileStmt)


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
