"""Vectorised range queries used by the planners (sparse tables, O(n log n)).

* :func:`range_min` / :func:`range_max`: for each query ``[lo, hi)`` the min/max of
  ``values[lo:hi]`` (``+inf``/``-inf`` for empty ranges).
* :func:`cover_min`: for each position ``e`` the min of the values of all ranges
  ``[lo, hi)`` that contain ``e`` (``+inf`` where none does).
"""

from __future__ import annotations

import numpy as np

from cncc.ir.trajectory import FloatArray


def _levels(n: int) -> int:
    return max(1, int(np.ceil(np.log2(max(n, 1)))) + 1)


def range_min(values: FloatArray, lo: np.ndarray, hi: np.ndarray) -> FloatArray:
    return _range_reduce(values, lo, hi, np.minimum, np.inf)


def range_max(values: FloatArray, lo: np.ndarray, hi: np.ndarray) -> FloatArray:
    return _range_reduce(values, lo, hi, np.maximum, -np.inf)


def _range_reduce(values: FloatArray, lo: np.ndarray, hi: np.ndarray, op: np.ufunc, empty: float) -> FloatArray:
    n = values.shape[0]
    lo = np.clip(lo, 0, n)
    hi = np.clip(hi, 0, n)
    out = np.full(lo.shape, empty)
    if n == 0:
        return out
    tables = [values.astype(float)]
    width = 1
    longest = int((hi - lo).max()) if lo.size else 0
    while width * 2 <= min(n, longest):
        prev = tables[-1]
        tables.append(op(prev[:-width], prev[width:]))
        width *= 2
    length = hi - lo
    ok = length > 0
    k = np.zeros_like(length)
    k[ok] = np.floor(np.log2(length[ok])).astype(np.int64)
    for level in np.unique(k[ok]):
        sel = ok & (k == level)
        tab = tables[int(level)]
        a = tab[lo[sel]]
        b = tab[hi[sel] - (1 << int(level))]
        out[sel] = op(a, b)
    return out


def cover_min(n: int, lo: np.ndarray, hi: np.ndarray, vals: FloatArray) -> FloatArray:
    """Min over covering ranges for each of ``n`` positions.

    ``vals`` is ``(q,)`` or ``(q, m)`` (``m`` independent columns); the result ``(n,)`` or
    ``(n, m)``.  Only levels up to the longest range are built.
    """
    lo = np.clip(lo, 0, n)
    hi = np.clip(hi, 0, n)
    ok = hi > lo
    lo, hi, vals = lo[ok], hi[ok], vals[ok]
    levels = _levels(min(n, int((hi - lo).max()) if lo.size else 1))
    shape = (n, *vals.shape[1:])
    tables = [np.full(shape, np.inf) for _ in range(levels)]
    if lo.size:
        length = hi - lo
        k = np.floor(np.log2(length)).astype(np.int64)
        for level in np.unique(k):
            sel = k == level
            tab = tables[int(level)]
            np.minimum.at(tab, lo[sel], vals[sel])
            np.minimum.at(tab, hi[sel] - (1 << int(level)), vals[sel])
    for level in range(levels - 1, 0, -1):
        half = 1 << (level - 1)
        tab, below = tables[level], tables[level - 1]
        np.minimum(below, tab, out=below)
        below[half:] = np.minimum(below[half:], tab[:-half])
    return tables[0]
