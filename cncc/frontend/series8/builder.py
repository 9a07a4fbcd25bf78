"""Syntax-tree builder for the SERIES 8 grammar's own rule (``cncc/grammar/series8.lark``).

A mixin of the parser's lark transformer (as :mod:`cncc.frontend.szgh_builder` is for
SZGH): a bare axis letter (``G00XZ``) is the word with the value 0.
"""

from __future__ import annotations

from typing import Any

from cncc.frontend import syntax as sx


class Series8Builder:
    """Methods for the SERIES 8 rules; mixed into the parser's transformer."""

    base: int

    def bare_axis(self, items: list[Any]) -> sx.Word:
        tok = items[0]
        start = self.base + (tok.start_pos or 0)
        return sx.Word(str(tok).upper(), 0.0, False, start, start + 1)
