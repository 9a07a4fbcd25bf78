"""``--annotate-time``: the program with each block's elapsed time as a comment.

Consumes a :class:`TimingReport` (its primary column) and the program text;
produces the same text with ``(t 12.345 s +1.200 s)`` -- the wall time when the
block's last command ends, and the block's own time -- on every line that produced
commands, written in the dialect's first comment syntax: parentheses go before any
``//`` or ``;`` tail of the block, ``;`` and ``//`` comments go at the end of the
line (appended to an existing tail comment).  Lines that produced nothing (``%``,
blank lines, control flow) are left as they were, so the result compiles to the same
motion.  The note holds no ``=``: some controls read ``(NAME=...)`` as a setting.

With ``-E`` the driver uses :func:`annotate_commands` instead: the expanded program's
commands with a timing comment after every executed block, for the G-code emitter.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence

from cncc.backends.timing.model import TimingReport, to_s
from cncc.dialects import Dialect
from cncc.ir import Command, Comment
from cncc.source import SourceFile

_OPENERS = {"paren": "(", "semicolon": ";", "slash": "//"}


def _tail_start(text: str, dialect: Dialect) -> int:
    """Where a tail comment or the block end begins (outside parentheses), else the end."""
    slash = "slash" in dialect.comments
    semi = "semicolon" in dialect.comments or dialect.block_end == ";"
    depth = 0
    for k, ch in enumerate(text):
        if ch == "(":
            depth += 1
        elif ch == ")" and depth:
            depth -= 1
        elif depth == 0 and ((slash and text.startswith("//", k)) or (semi and ch == ";")):
            return k
    return len(text)


def annotate_line(text: str, note: str, dialect: Dialect) -> str:
    """``text`` (no line ending) with ``note`` added as a comment of ``dialect``."""
    style = dialect.comments[0] if dialect.comments else "paren"
    body = text.rstrip()
    cut = _tail_start(body, dialect)
    if style == "paren":
        head = body[:cut].rstrip()
        tail = body[cut:]
        return f"{head} ({note})" + (f" {tail}" if tail else "")
    opener = _OPENERS.get(style, ";")
    if body[cut:].startswith(opener):
        return f"{body} {note}"  # the line ends in a comment of this style already: extend it
    return f"{body} {opener} {note}"


def annotate_time(rep: TimingReport, src: SourceFile, dialect: Dialect) -> str:
    notes: dict[int, str] = {}
    rows = zip(rep.lines.elapsed_ns.tolist(), rep.lines.times_ns[:, 0].tolist(), rep.index.line_keys, strict=True)
    for end_ns, t_ns, (sid, line) in rows:
        if sid == src.source_id:
            notes[line] = f"t {to_s(end_ns):.3f} s +{to_s(t_ns):.3f} s"
    out = []
    for number, raw in enumerate(src.text.splitlines(keepends=True), 1):
        body = raw.rstrip("\r\n")
        ending = raw[len(body):]
        out.append(annotate_line(body, notes[number], dialect) + ending if number in notes else raw)
    return "".join(out)


def annotate_commands(cmds: Sequence[Command], rep: TimingReport) -> Iterator[Command]:
    """``-E --annotate-time``: ``cmds`` with a timing :class:`Comment` after each executed block.

    ``rep`` is the report of ``cmds`` (its primary column).  A block is a run of
    consecutive commands from one source line, so every pass through a loop or a
    subprogram gets its own elapsed time; the emitter writes the comments in the
    target dialect's syntax.
    """
    import numpy as np

    if not cmds:
        return
    ends = np.cumsum(rep.primary.cmd_ns).tolist()
    lines = rep.index.cmd_line.tolist()
    start_ns = 0
    moved = False
    for i, c in enumerate(cmds):
        yield c
        moved = moved or not isinstance(c, Comment)
        if i + 1 < len(cmds) and lines[i + 1] == lines[i]:
            continue
        if moved:
            note = f"t {to_s(ends[i]):.3f} s +{to_s(ends[i] - start_ns):.3f} s"
            yield Comment(c.span, c.frame, note)
        start_ns, moved = ends[i], False
