"""Syntax-tree builders for the rs274ngc grammar's own rules (``cncc/grammar/rs274ngc.lark``).

A mixin of the parser's lark transformer (as :mod:`cncc.frontend.szgh_builder` is
for SZGH): O-word lines, named parameters, ``**``/logic operators and ``ATAN[a]/[b]``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from lark import Token

from cncc.frontend import syntax as sx


@dataclass(frozen=True, slots=True)
class OWord:
    """``O<label> keyword [arg]...``: ``label`` is ``"<name>"`` (lower case, no blanks) or a number."""

    label: str
    keyword: str  # lower case; "" for a bare O<number> (an M98 program start)
    args: tuple[sx.Expr, ...]
    start: int
    end: int
    label_expr: sx.Expr | None = None  # o#<n> call, O[...] call: the number is computed when the line runs


def oword_of(statements: tuple[object, ...]) -> OWord | None:
    """The O-word statement of a block, if it has one."""
    for st in statements:
        if isinstance(st, OWord):
            return st
    return None


def label_key(text: str) -> str:
    """``"O <My Sub>"`` -> ``"<mysub>"``, ``"o0100"`` -> ``"100"``."""
    body = "".join(text[1:].split()).lower()
    return body if body.startswith("<") else str(int(body))


def param_name(text: str) -> str:
    """``"#< My_Var >"`` -> ``"my_var"`` (LinuxCNC ignores blanks and case in names)."""
    inner = text[text.index("<") + 1:text.rindex(">")]
    return "".join(inner.split()).lower()


class LinuxcncBuilder:
    """Methods for the rs274ngc rules; mixed into the parser's transformer."""

    base: int

    def _binary(self, items: list[Any]) -> sx.Expr:  # provided by the transformer
        raise NotImplementedError

    def logic(self, items: list[Any]) -> sx.Expr:
        return self._binary(items)

    def power(self, items: list[Any]) -> sx.Expr:
        return self._binary(items)

    def named_var(self, items: list[Any]) -> sx.Var:
        tok: Token = items[0]
        start = self.base + (tok.start_pos or 0)
        return sx.Var(None, start, start + len(str(tok)), name=param_name(str(tok)))

    def atan2(self, items: list[Any]) -> sx.Call:
        func, a, b = items
        start = self.base + (func.start_pos or 0)
        return sx.Call("ATAN", (a, b), start, int(b.end) + 1)

    def oword(self, items: list[Any]) -> OWord:
        label: Token = items[0]
        start = self.base + (label.start_pos or 0)
        end = start + len(str(label))
        keyword = ""
        args: list[sx.Expr] = []
        for it in items[1:]:
            if isinstance(it, Token) and it.type == "OKEYWORD":
                keyword = "".join(str(it).split()).lower()  # "else if", "end sub" as LinuxCNC reads them
                end = self.base + (it.start_pos or 0) + len(str(it))
            elif isinstance(it, sx.CommentItem):
                continue
            else:
                args.append(it)
                end = int(it.end) + 1
        return OWord(label_key(str(label)), keyword, tuple(args), start, end)

    def computed_oword(self, items: list[Any]) -> OWord:
        tok: Token = items[0]
        start = self.base + (tok.start_pos or 0)
        inner = self.oword([Token("OLABEL", "o0", start_pos=tok.start_pos), *items[2:]])
        return OWord("", inner.keyword, inner.args, start, inner.end, label_expr=items[1])
