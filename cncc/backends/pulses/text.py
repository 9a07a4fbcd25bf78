"""Text rows rendered by numpy, for the writers that print one line per event (VCD, CSV).

A row is a sequence of :class:`Cells` — decimal integers (:func:`decimal`), one of a few
fixed byte strings (:func:`choice`) or a constant (:func:`literal`) — each a byte matrix
``(n, width)`` with a mask of the bytes that are kept; :func:`render` lays the cells side
by side and keeps the masked bytes, row by row, as one ``bytes``.  No Python loop runs
per row: a chunk of a million events is a handful of array operations.  The digits come
from :func:`cncc.backends.numtext.zero_padded`, the backends' one number formatter.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from cncc.backends.numtext import digit_count, zero_padded

I64 = npt.NDArray[np.int64]
U8 = npt.NDArray[np.uint8]
Mask = npt.NDArray[np.bool_]


@dataclass(frozen=True, slots=True)
class Cells:
    """Bytes ``(n, width)`` and the mask of those that are written."""

    data: U8
    keep: Mask

    def only(self, rows: Mask) -> Cells:
        """The same cells, written only on ``rows``."""
        return Cells(self.data, self.keep & rows[:, None])


def decimal(values: I64) -> Cells:
    """Non-negative integers in decimal, without leading zeros (``0`` is ``"0"``)."""
    v = np.asarray(values, dtype=np.int64)
    n = v.shape[0]
    if n and int(v.min()) < 0:
        raise ValueError("decimal() takes non-negative integers")
    top = int(v.max()) if n else 0
    groups = max(len(str(top)) + 3, 4) // 4  # four digits a group, most significant first
    width = 4 * groups
    keep = np.arange(width)[None, :] >= (width - digit_count(v))[:, None]
    return Cells(zero_padded(v, width), keep)


def signed(values: I64) -> Cells:
    """Integers in decimal with a leading ``-`` where negative."""
    v = np.asarray(values, dtype=np.int64)
    mag = decimal(np.abs(v))
    minus = Cells(np.full((v.shape[0], 1), ord("-"), np.uint8), (v < 0)[:, None])
    return join_cells([minus, mag])


def choice(options: Sequence[bytes], index: npt.NDArray[np.integer]) -> Cells:
    """``options[index[r]]`` in row ``r``."""
    width = max((len(o) for o in options), default=0)
    table = np.zeros((len(options), max(width, 1)), np.uint8)
    lengths = np.zeros(len(options), np.int64)
    for k, o in enumerate(options):
        table[k, :len(o)] = np.frombuffer(o, np.uint8)
        lengths[k] = len(o)
    idx = np.asarray(index, dtype=np.int64)
    keep = np.arange(table.shape[1])[None, :] < lengths[idx][:, None]
    return Cells(table[idx], keep)


def literal(text: bytes, n: int) -> Cells:
    """The same bytes in each of ``n`` rows."""
    row = np.frombuffer(text, np.uint8)
    return Cells(np.broadcast_to(row, (n, row.shape[0])), np.ones((n, row.shape[0]), bool))


def join_cells(cells: Sequence[Cells]) -> Cells:
    return Cells(np.concatenate([c.data for c in cells], axis=1), np.concatenate([c.keep for c in cells], axis=1))


def render(cells: Sequence[Cells]) -> bytes:
    """The rows, cells side by side, masked bytes dropped, rows one after the other."""
    if not cells or cells[0].data.shape[0] == 0:
        return b""
    row = join_cells(cells)
    out: bytes = row.data[row.keep].tobytes()
    return out


def stamped(t: I64, new_time: Mask, tokens: Sequence[bytes], code: npt.NDArray[np.integer]) -> bytes:
    """Rows ``#<t>\\n<token>`` where ``new_time``, ``<token>`` elsewhere (VCD value changes);
    ``tokens`` all of one length; ``t`` non-negative."""
    n = t.shape[0]
    if n == 0:
        return b""
    tw = len(tokens[0])
    if any(len(tok) != tw for tok in tokens):
        raise ValueError("stamped() takes tokens of one length")
    top = int(t.max())
    if int(t.min()) < 0:
        raise ValueError("stamped() takes non-negative times")
    groups = max(len(str(top)) + 3, 4) // 4
    dw = 4 * groups
    width = 1 + dw + 1 + tw  # a spare column for '#', the digits, '\n', the token
    data = np.empty((n, width), np.uint8)
    data[:, 1:1 + dw] = zero_padded(t, dw)
    data[:, 1 + dw] = ord("\n")
    table = np.frombuffer(b"".join(tokens), np.uint8).reshape(len(tokens), tw)
    idx = np.asarray(code, np.int64)
    for col in range(tw):
        data[:, 2 + dw + col] = np.take(table[:, col], idx)
    digits = digit_count(t)
    start = np.where(new_time, dw - digits, dw + 2)  # the '#' column, or the token's first
    rows = np.flatnonzero(new_time)
    data[rows, start[rows]] = ord("#")
    keep = np.arange(width, dtype=np.int64)[None, :] >= start[:, None]
    out: bytes = data[keep].tobytes()
    return out
