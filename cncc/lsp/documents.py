"""Open documents whose incremental changes cost the size of the change, not of the file.

pygls applies an incremental ``didChange`` by splitting the whole text into lines and
writing every line into a new buffer: about 30 ms per keystroke on a 100,000-line CAM
file, more than the incremental analysis itself.  :class:`FastTextDocument` finds the
two offsets of the change (C-level ``str.split``/``find``) and splices the text; the
server gives every opened document this class (:func:`speed_up`).
``tests/lsp/test_incremental.py`` checks it against pygls on random edits.
"""

from __future__ import annotations

from typing import Any

from pygls.workspace import TextDocument

from cncc.lsp.positions import column_units


def offset_of(text: str, line: int, character: int, encoding: str) -> int:
    """Character offset of the LSP position (``line``, ``character`` in ``encoding`` code units),
    clamped to the line's end (its ``\\n``) and to the text."""
    if line <= 0:
        base = 0
    else:
        parts = text.split("\n", line)
        if len(parts) <= line:
            return len(text)
        base = len(text) - len(parts[-1])
    end = text.find("\n", base)
    end = len(text) if end < 0 else end
    if character <= 0:
        return base
    row = text[base:end]
    if encoding == "utf-32" or row.isascii():
        return base + min(character, len(row))
    units = 0
    for i, ch in enumerate(row):
        if units >= character:
            return base + i
        units += column_units(ch, encoding)
    return end


class FastTextDocument(TextDocument):
    def _apply_incremental_change(self, change: Any) -> None:
        text = self._source or ""
        rng = change.range
        enc = getattr(self._position_codec, "encoding", "utf-16")
        encoding = str(getattr(enc, "value", enc)).lower()
        start = offset_of(text, rng.start.line, rng.start.character, encoding)
        end = start if (rng.end.line, rng.end.character) == (rng.start.line, rng.start.character) \
            else offset_of(text, rng.end.line, rng.end.character, encoding)
        self._source = text[:start] + change.text + text[max(start, end):]


def speed_up(doc: object) -> None:
    """Give an opened pygls document the fast incremental change (when it is pygls' own class)."""
    if type(doc) is TextDocument and hasattr(doc, "_source") and hasattr(doc, "_position_codec"):
        doc.__class__ = FastTextDocument
