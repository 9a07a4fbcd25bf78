"""``--emit=ir``: the IR text (:mod:`cncc.ir.text`, docs/ir.md) with each command's source line as a comment.

The text reads back with :func:`cncc.ir.text.parse_ir` (the comments are ignored).
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from cncc.ir import Command
from cncc.ir.text import print_ir
from cncc.source import SourceMap


def dump_ir(cmds: Iterable[Command], sources: SourceMap) -> Iterator[str]:
    return print_ir(cmds, sources)
