"""Vectorised number text: columns of floats as ``'%.Nf' % v`` writes them, byte for byte.

The backends write a batch of moves (:mod:`cncc.ir.batch`) as one block of text.  Its lines
are built as a matrix of bytes -- one row per line, fixed-width fields, ``0`` bytes as padding
-- whose padding is dropped at the end (:func:`join_rows`).  A number becomes its digits by
integer arithmetic on ``rint(v * 10**N)``, which is the correctly rounded decimal Python prints
as long as ``v * 10**N`` is not within its rounding error of a half; :func:`fixed` returns
``None`` for a column where some value is that close (or too large), and the caller writes
that batch the ordinary way.  ``tests/backends/test_numtext.py`` compares with ``%`` on
random and adversarial values.
"""

from __future__ import annotations

from typing import Any

import numpy as np

Matrix = np.ndarray[Any, np.dtype[np.uint8]]
PAD = 0
_LIMIT = 1e15  # |v * 10**N| above this: no safe integer digits


def constant(text: str, rows: int) -> Matrix:
    """``text`` on every row."""
    b = np.frombuffer(text.encode("ascii"), dtype=np.uint8)
    out: Matrix = np.broadcast_to(b, (rows, len(b)))
    return out


def choice(texts: list[str], index: np.ndarray[Any, Any]) -> Matrix:
    """Row ``r`` holds ``texts[index[r]]`` (padded)."""
    width = max(len(t) for t in texts)
    table = np.zeros((len(texts), width), dtype=np.uint8)
    for k, t in enumerate(texts):
        table[k, :len(t)] = np.frombuffer(t.encode("ascii"), dtype=np.uint8)
    out: Matrix = table[index]
    return out


def _groups_table() -> np.ndarray[Any, np.dtype[np.uint32]]:
    """The four ASCII digits of 0..9999 as one 32-bit word each (the bytes in memory order)."""
    k = np.arange(10_000)
    table = (np.stack([k // 1000, k // 100 % 10, k // 10 % 10, k % 10], axis=1) + 48).astype(np.uint8)
    words: np.ndarray[Any, np.dtype[np.uint32]] = np.ascontiguousarray(table).view(np.uint32).ravel()
    return words


_GROUPS32 = _groups_table()
_POW10 = np.array([10**k for k in range(19)], dtype=np.int64)


def digit_count(a: np.ndarray[Any, Any]) -> np.ndarray[Any, Any]:
    """Decimal digits of the non-negative int64s ``a`` (``0`` has one)."""
    out: np.ndarray[Any, Any] = np.searchsorted(_POW10[1:], a, side="right") + 1
    return out


def zero_padded(a: np.ndarray[Any, Any], width: int) -> Matrix:
    """``(n, width)``: the ``width`` lowest decimal digits of the non-negative int64s ``a``, leading
    zeros kept -- four digits at a time from a table of 10 000 words, the one digit formatter of
    the backends (the batch text here, the pulse writers' rows in ``pulses/text.py``)."""
    n = len(a)
    groups = max(1, -(-width // 4))
    words = np.empty((n, groups), np.uint32)
    rest = np.asarray(a, dtype=np.int64)
    for gi in range(groups - 1, 0, -1):
        high = rest // 10_000
        words[:, gi] = np.take(_GROUPS32, rest - high * 10_000)
        rest = high
    words[:, 0] = np.take(_GROUPS32, rest % 10_000 if int(rest.max(initial=0)) >= 10_000 else rest)
    out: Matrix = words.view(np.uint8).reshape(n, 4 * groups)[:, 4 * groups - width:]
    return out


def _digits(a: np.ndarray[Any, Any], width: int, lead_pad: bool) -> Matrix:
    """The ``width`` lowest decimal digits of the non-negative int64s ``a``; with ``lead_pad`` the
    leading zeros (all but the last digit) are padding."""
    out = np.array(zero_padded(a, width))
    if lead_pad and width > 1:
        out[np.arange(width)[None, :] < (width - digit_count(a))[:, None]] = PAD
    return out


def fixed(values: np.ndarray[Any, Any], decimals: int, minus_zero: bool = False) -> Matrix | None:
    """``'%.{decimals}f' % v`` for every value, as padded rows; ``minus_zero``: a value that rounds
    to zero keeps its ``-`` (``'-0.0000'``), else it is written ``0.0000`` (the canon trace's rule).
    None when some value is not safely rounded by integer arithmetic (see the module docstring)."""
    v = np.asarray(values, dtype=np.float64)
    scale = 10.0 ** decimals
    s = v * scale
    mag = np.abs(s)
    if not bool((mag < _LIMIT).all()):
        return None
    frac = mag - np.floor(mag)
    if bool((np.abs(frac - 0.5) <= mag * 4.5e-16 + 1e-9).any()):
        return None
    q = np.rint(mag).astype(np.int64)
    neg = np.signbit(v) if minus_zero else (np.signbit(v) & (q != 0))
    one = 10 ** decimals
    ip, fp = q // one, q % one
    top = int(ip.max()) if len(ip) else 0
    nd = max(1, len(str(top)))
    sign = np.where(neg, ord("-"), PAD).astype(np.uint8)[:, None]
    parts = [sign, _digits(ip, nd, True)]
    if decimals:
        parts += [constant(".", len(v)), _digits(fp, decimals, False)]
    return np.concatenate(parts, axis=1)


def integers(values: np.ndarray[Any, Any]) -> Matrix:
    """``str(int(v))`` for every value, as padded rows."""
    a = np.asarray(values, dtype=np.int64)
    mag = np.abs(a)
    top = int(mag.max()) if len(mag) else 0
    sign = np.where(a < 0, ord("-"), PAD).astype(np.uint8)[:, None]
    return np.concatenate([sign, _digits(mag, max(1, len(str(top))), True)], axis=1)


def join_rows(parts: list[Matrix]) -> Matrix:
    """The fields side by side."""
    return np.concatenate(parts, axis=1)


def text_of(rows: Matrix) -> str:
    """The rows one after the other, padding dropped."""
    flat = np.ascontiguousarray(rows).ravel()
    text: str = flat[flat != PAD].tobytes().decode("ascii")
    return text


def stack(blocks: list[Matrix]) -> list[Matrix]:
    """The blocks padded to one width (so that their rows can be interleaved)."""
    width = max(b.shape[1] for b in blocks)
    out = []
    for b in blocks:
        if b.shape[1] < width:
            b = np.concatenate([b, np.zeros((b.shape[0], width - b.shape[1]), dtype=np.uint8)], axis=1)
        out.append(b)
    return out


__all__ = ["PAD", "choice", "constant", "digit_count", "fixed", "integers", "join_rows", "stack", "text_of",
           "zero_padded"]
