"""Syntax-tree builders for the SZGH grammar's own rules (``cncc/grammar/szgh.lark``).

A mixin of the parser's lark transformer: each method turns one SZGH rule into a
:mod:`cncc.frontend.syntax` node with absolute offsets (``self.base`` is the offset
of the line being parsed).
"""

from __future__ import annotations

import re
from typing import Any

from lark import Token

from cncc.frontend import syntax as sx

_BRACKETED = re.compile(r"^\s*[\(\[](.*)[\)\]]\s*$", re.DOTALL)


def _inner(text: str) -> str:
    m = _BRACKETED.match(text)
    return m.group(1).strip() if m else text.strip()


class SzghBuilder:
    """Methods for the SZGH rules; mixed into the parser's transformer."""

    base: int

    def _pos(self, tok: Token) -> tuple[int, int]:
        start = self.base + (tok.start_pos or 0)
        return start, start + len(str(tok))

    def szgh_if(self, items: list[Any]) -> sx.If | sx.IfBlock:
        kw, cond = items[0], items[1]
        start = self.base + (kw.start_pos or 0)
        if len(items) == 2:
            return sx.IfBlock(cond, start, int(cond.end) + 1)
        then = items[2]
        end = then.end if not isinstance(then, tuple) else then[-1].end
        return sx.If(cond, then, start, end)

    def else_stmt(self, items: list[Any]) -> sx.Else:
        return sx.Else(*self._pos(items[0]))

    def elif_stmt(self, items: list[Any]) -> sx.ElseIf:
        start, end = self._pos(items[0])
        cond = items[1] if len(items) > 1 else None
        return sx.ElseIf(cond, start, int(cond.end) + 1 if cond is not None else end)

    def endif_stmt(self, items: list[Any]) -> sx.EndIf:
        return sx.EndIf(*self._pos(items[0]))

    def _io(self, items: list[Any]) -> tuple[bool, str, int, int]:
        kw, sign, sig = items
        start, _ = self._pos(kw)
        _, end = self._pos(sig)
        return sign == "+", str(sig).upper(), start, end

    def wat_stmt(self, items: list[Any]) -> sx.IoWait:
        return sx.IoWait(*self._io(items))

    def out_stmt(self, items: list[Any]) -> sx.IoOut:
        return sx.IoOut(*self._io(items))

    def msg_stmt(self, items: list[Any]) -> sx.MessageStmt:
        tok = items[0]
        text = str(tok)
        pause = text[:3].upper() == "MSG"
        return sx.MessageStmt(_inner(text[3 if pause else 4:]), pause, *self._pos(tok))

    def file_stmt(self, items: list[Any]) -> sx.FileStmt:
        tok = items[0]
        text = str(tok)
        return sx.FileStmt(text[:6].upper(), _inner(text[6:]) if len(text) > 6 else "", *self._pos(tok))

    def prog_name(self, items: list[Any]) -> sx.ProgramName:
        tok = items[0]
        text = str(tok)
        call = tok.type == "PP_NAME"
        name = text[2:] if call else text[1:]
        return sx.ProgramName(name.strip(), call, *self._pos(tok))
