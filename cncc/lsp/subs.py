"""Hover texts of LinuxCNC subroutines (``o<name> sub``) and named parameters (``#<name>``).

A subroutine's hover says where it is defined and which call parameters its body
reads: LinuxCNC passes the bracketed arguments of ``o<name> call [a] [b]`` as
``#1``, ``#2`` ... (up to ``#30``), and a body usually names them at its top
(``#<side> = #1``); both are read lexically from the body.  On a call the hover adds
the argument each parameter gets.  A named parameter's hover shows the value the
LinuxCNC executor saw at that very reference (:mod:`cncc.lsp.trace`), or says that
the run did not reach it.
"""

from __future__ import annotations

import re

from cncc.dialects import Dialect
from cncc.lsp.navigate import Outline, oword_key
from cncc.lsp.positions import LineIndex
from cncc.lsp.scan import Comments, tokens
from cncc.lsp.trace import VariableTrace

_PARAM_RE = re.compile(r"#\s*(\d+)(?!\d)")
_NAMES_RE = re.compile(r"#\s*<([^>]*)>\s*=\s*#\s*(\d+)(?!\d)")
MAX_ARGS = 30


def call_arguments(line: str) -> list[str]:
    """The bracketed arguments of a call line, outermost brackets only (``[1+[2]] [3]``)."""
    args: list[str] = []
    depth = 0
    start = 0
    for i, ch in enumerate(line.split("(")[0].split(";")[0]):
        if ch == "[":
            if depth == 0:
                start = i
            depth += 1
        elif ch == "]" and depth > 0:
            depth -= 1
            if depth == 0:
                args.append(line[start:i + 1])
    return args


def sub_hover(index: LineIndex, dialect: Dialect, out: Outline, key: str, line: int) -> str:
    """Markdown for subroutine ``key`` hovered on 0-based ``line`` (its definition or a call)."""
    shown = f"o<{key}>" if not key.isdigit() else f"o{key}"
    defs = out.definitions_of("sub", key)
    here = list(tokens(index.line_text(line), index.line_start(line), Comments.of(dialect)))
    found = oword_key(here) if here else None
    args = call_arguments(index.line_text(line)) if found is not None and found[1] == "CALL" else []
    if not defs:
        lines = [f"**{shown}** — LinuxCNC subroutine, not defined in this file "
                 f"(LinuxCNC looks for `{key}.ngc` in its subroutine path)."]
        lines += [f"- #{i + 1} = {a}" for i, a in enumerate(args[:MAX_ARGS])]
        return "\n".join(lines)
    start = defs[0].start
    end = out.sub_ends.get(key, len(index.text))
    body = index.text[start:end]
    first, last = index.line_of(start), index.line_of(max(start, end - 1))
    used = sorted({int(n) for n in _PARAM_RE.findall(body) if 1 <= int(n) <= MAX_ARGS})
    names = {int(n): "".join(name.split()).lower() for name, n in _NAMES_RE.findall(body)}
    lines = [f"**{shown}** — LinuxCNC subroutine, lines {first + 1}–{last + 1}"]
    head = index.line_text(first)
    note = head[head.find("(") + 1:head.rfind(")")].strip() if "(" in head and ")" in head else ""
    if note:
        lines.append(f"\n{note}")
    if used:
        lines.append("\nParameters (the call's bracketed arguments, in order):")
        for n in used:
            named = f" → `#<{names[n]}>`" if n in names else ""
            given = f" = {args[n - 1]}" if n - 1 < len(args) else (" — not given by this call (0)" if args else "")
            lines.append(f"- `#{n}`{named}{given}")
    else:
        lines.append("\nIt reads no call parameters (#1 … #30).")
    if args and len(args) > (used[-1] if used else 0):
        lines.append(f"\nThis call passes {len(args)} arguments; the body reads {len(used)}.")
    return "\n".join(lines)


def named_hover(name: str, site: int, trace: VariableTrace | None, changed: bool = False) -> str:
    """Markdown for the named parameter ``#<name>`` whose ``#`` is at offset ``site``
    (``changed``: the text differs from the one the trace comes from)."""
    from cncc.lsp.variables import traced_text

    head = f"#<{name}>"
    scope = "global" if name.startswith("_") else "local to the subroutine (or main program) it is in"
    if trace is None or not trace.ran:
        when = "the text changed since cncc last ran it" if changed else "cncc has not run the program yet"
        return f"**{head}** — named parameter ({scope}); {when}."
    seen = trace.at(site)
    if seen is None or not seen.passes:
        return (f"**{head}** — this reference was not reached when cncc ran the program "
                "(a branch not taken, a subroutine never called, or the run stopped before it).")
    return traced_text(head, seen) + f"\n\nNamed parameter, {scope}."
