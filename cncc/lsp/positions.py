"""Character offsets <-> LSP positions (line, UTF-16 code unit column).

Spans in cncc count Python characters (code points).  The Language Server
Protocol counts columns in UTF-16 code units by default, so a character outside
the Basic Multilingual Plane (an emoji in a comment) is two columns wide.  This is
the only place that converts; everything inside the server works on offsets.
"""

from __future__ import annotations

import bisect
from itertools import accumulate


class LineIndex:
    """Line starts of one text, for converting offsets and positions both ways.

    ``encoding`` is the negotiated position encoding: ``utf-16`` (the LSP default),
    ``utf-32`` (code points) or ``utf-8`` (bytes).
    """

    __slots__ = ("_starts", "encoding", "text")

    def __init__(self, text: str, encoding: str = "utf-16") -> None:
        self.text = text
        self.encoding = encoding
        # running sums of the line lengths (+1 for each newline), all in C
        starts = list(accumulate(map((1).__add__, map(len, text.split("\n"))), initial=0))
        starts.pop()
        self._starts = starts

    @classmethod
    def after_edit(cls, old: LineIndex, text: str, prefix: int, suffix: int) -> LineIndex:
        """The index of ``text``, which equals ``old.text`` but for the characters between its
        first ``prefix`` and last ``suffix`` ones: the old line starts are kept (shifted after
        the change) and only the changed part is scanned."""
        new = cls.__new__(cls)
        new.text = text
        new.encoding = old.encoding
        starts = old._starts
        keep = bisect.bisect_right(starts, prefix)
        end_new = len(text) - suffix
        region = []
        i = text.find("\n", prefix, end_new)
        while i >= 0:
            region.append(i + 1)
            i = text.find("\n", i + 1, end_new)
        tail = bisect.bisect_left(starts, len(old.text) - suffix + 1)
        delta = len(text) - len(old.text)
        moved = starts[tail:] if delta == 0 else [s + delta for s in starts[tail:]]
        new._starts = starts[:keep] + region + moved
        return new

    @property
    def line_count(self) -> int:
        return len(self._starts)

    def line_start(self, line: int) -> int:
        """Offset of the first character of 0-based ``line`` (clamped)."""
        line = min(max(line, 0), len(self._starts) - 1)
        return self._starts[line]

    def line_end(self, line: int) -> int:
        """Offset just past the last character of ``line`` (before ``\\r\\n``)."""
        line = min(max(line, 0), len(self._starts) - 1)
        end = self._starts[line + 1] - 1 if line + 1 < len(self._starts) else len(self.text)
        if end > self._starts[line] and self.text[end - 1] == "\r":
            end -= 1
        return end

    def line_text(self, line: int) -> str:
        return self.text[self.line_start(line):self.line_end(line)]

    def line_of(self, offset: int) -> int:
        """0-based line of a character offset."""
        return bisect.bisect_right(self._starts, max(offset, 0)) - 1

    def position(self, offset: int) -> tuple[int, int]:
        """(line, UTF-16 column) of a character offset (clamped to the text)."""
        offset = min(max(offset, 0), len(self.text))
        line = self.line_of(offset)
        start = self._starts[line]
        return line, column_units(self.text[start:offset], self.encoding)

    def offset(self, line: int, character: int) -> int:
        """Character offset of an LSP position (UTF-16 column; clamped to the line)."""
        if line >= len(self._starts):
            return len(self.text)
        start = self.line_start(line)
        end = self.line_end(line)
        if self.encoding == "utf-32" or self.text[start:end].isascii():
            return min(start + max(character, 0), end)
        units = 0
        i = start
        while i < end and units < character:
            units += column_units(self.text[i], self.encoding)
            i += 1
        return i


def column_units(text: str, encoding: str = "utf-16") -> int:
    """Length of ``text`` in the code units of ``encoding``."""
    if text.isascii() or encoding == "utf-32":
        return len(text)
    if encoding == "utf-8":
        return len(text.encode("utf-8", "surrogatepass"))
    return len(text) + sum(1 for ch in text if ord(ch) > 0xFFFF)
