"""The command line before argparse: ``@file`` response files and gcc's glued ``-MF``/``-MT`` values.

As gcc: ``@FILE`` is replaced by the options in FILE, separated by white space, with
single or double quotes and backslashes as in a POSIX shell; a response file may name
further ``@files`` (nesting is bounded).  An ``@FILE`` that cannot be read is left as it
is (it is then an input file name, reported when it cannot be read).
"""

from __future__ import annotations

import shlex
from collections.abc import Sequence

MAX_DEPTH = 16
GLUED = ("-MF", "-MT")  # -MFdeps.d is -MF deps.d


class ArgfileError(ValueError):
    pass


def expand(args: Sequence[str], depth: int = 0) -> list[str]:
    out: list[str] = []
    for arg in args:
        if arg.startswith("@") and len(arg) > 1:
            try:
                with open(arg[1:], encoding="utf-8") as fh:
                    text = fh.read()
            except (OSError, UnicodeDecodeError):
                out.append(arg)
                continue
            if depth >= MAX_DEPTH:
                raise ArgfileError(f"{arg}: response files nested more than {MAX_DEPTH} deep")
            try:
                words = shlex.split(text, comments=False, posix=True)
            except ValueError as exc:
                raise ArgfileError(f"{arg}: {exc}") from None
            out.extend(expand(words, depth + 1))
            continue
        out.extend(_unglue(arg))
    return out


def _unglue(arg: str) -> list[str]:
    for opt in GLUED:
        if arg.startswith(opt) and len(arg) > len(opt):
            return [opt, arg[len(opt):]]
    return [arg]
