"""The ISO/EIA tape frame: text after the closing ``%`` is not part of the program."""

from __future__ import annotations

import re

from cncc.source import SourceFile

_NEXT_TAPE = re.compile(r"\s*(%|[O:]\s*\d)", re.I)  # another tape or program follows: a concatenation


def before_tape_end(src: SourceFile) -> SourceFile:
    """The program up to its closing ``%`` (ISO/EIA tape format: a ``%`` line after the
    first block ends the tape, and the control reads nothing after it).  A file that goes
    on with another tape (``%``) or program (``O1000``) is a concatenation and is kept
    whole.  Offsets are unchanged (the text is cut, not moved)."""
    text = src.text
    pos, seen_block = 0, False
    n = len(text)
    while pos < n:
        nl = text.find("\n", pos)
        end = n if nl < 0 else nl
        line = text[pos:end].strip()
        if line == "%" and seen_block:
            if text[end:].strip() and _NEXT_TAPE.match(text, end) is None:
                return SourceFile(src.source_id, src.name, text[:end])
            return src
        if line and line != "%":
            seen_block = True
        pos = end + 1
    return src

