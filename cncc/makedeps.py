"""Make rules for ``-M``, ``-MM``, ``-MD``, ``-MF``, ``-MT``, ``-MP`` (as gcc writes them).

``TARGET: program called-file...``: the program and every program file its calls
loaded (``-MM``: without the files of the dialect's own macro library).  Names are
escaped for make (space and ``#`` with a backslash, ``$`` as ``$$``); long rules are
continued with a backslash.  ``-MP`` adds an empty rule for each called file.
"""

from __future__ import annotations

import os
from collections.abc import Sequence

WIDTH = 76


def escape(name: str) -> str:
    return name.replace("$", "$$").replace("#", "\\#").replace(" ", "\\ ")


def default_target(program: str, output: str | None, emit: str) -> str:
    """-MT absent: the -o file, else the program's stem with the emit kind as extension (``part.canon``)."""
    if output and output != "-":
        return output
    stem = os.path.splitext(os.path.basename(program))[0] or "stdin"
    return f"{stem}.{emit}"


def rule(targets: Sequence[str], program: str, deps: Sequence[str], phony: bool = False) -> str:
    called = [d for d in dict.fromkeys(deps) if d != program]
    words = [" ".join(escape(t) for t in targets) + ":", escape(program), *(escape(d) for d in called)]
    lines, cur = [], words[0]
    for w in words[1:]:
        if len(cur) + 1 + len(w) > WIDTH:
            lines.append(cur + " \\")
            cur = " " + w
        else:
            cur += " " + w
    lines.append(cur)
    text = "\n".join(lines) + "\n"
    if phony:
        text += "".join(f"\n{escape(d)}:\n" for d in called)
    return text


def under(path: str, folder: str) -> bool:
    real, top = os.path.realpath(path), os.path.realpath(folder)
    return real == top or real.startswith(top + os.sep)
