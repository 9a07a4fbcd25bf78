"""The canon trace of a batch of moves (:mod:`cncc.ir.batch`) as one block of text.

Consumes a :class:`~cncc.ir.batch.MoveBatch`; produces the lines :mod:`cncc.backends.canon`
writes for its commands (``SET_FEED_RATE`` before a move with an F word, then
``STRAIGHT_TRAVERSE`` / ``STRAIGHT_FEED`` / ``ARC_FEED``), built with the vectorised number
text of :mod:`cncc.backends.numtext`; None when a number is not safely rounded that way
(the caller then writes the batch's commands one by one).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from cncc.backends.numtext import Matrix, choice, constant, fixed, integers, join_rows, stack, text_of
from cncc.ir.batch import ARC, MoveBatch

PREFIX = " N..... "


def batch_text(b: MoveBatch, feed_in_program_units: bool) -> str | None:
    """The trace lines of ``b`` joined by newlines (no newline after the last); None: not safely."""
    k = b.frame.units.mm_per_unit
    arcs = b.kind == ARC
    lines: list[Matrix] = []
    order: list[np.ndarray[Any, Any]] = []  # the sort key of every row of every block
    straight = np.flatnonzero(~arcs)
    if len(straight):
        rows = _straight(b, straight, k)
        if rows is None:
            return None
        lines.append(rows)
        order.append(2 * straight + 1)
    curved = np.flatnonzero(arcs)
    if len(curved):
        rows = _arcs(b, curved, k)
        if rows is None:
            return None
        lines.append(rows)
        order.append(2 * curved + 1)
    with_f = np.flatnonzero(b.feed_start >= 0)
    if len(with_f):
        feed = b.feed[with_f] / k if feed_in_program_units else b.feed[with_f]
        num = fixed(feed, 4)
        if num is None:
            return None
        m = len(with_f)
        lines.append(join_rows([constant(PREFIX + "SET_FEED_RATE(", m), num, constant(")\n", m)]))
        order.append(2 * with_f)
    blocks = stack(lines)
    allrows = np.concatenate(blocks, axis=0)
    keys = np.concatenate(order)
    return text_of(allrows[np.argsort(keys, kind="stable")])[:-1]


def _pos(cols: list[np.ndarray[Any, Any]]) -> list[Matrix] | None:
    out: list[Matrix] = []
    for c in cols:
        if len(c) > 1 and bool((c == c[0]).all()) and not bool(np.signbit(c).any() != np.signbit(c[0])):
            one = fixed(c[:1], 4)  # a column of one value (the rotary axes, a constant Z): formatted once
            m = None if one is None else np.broadcast_to(one, (len(c), one.shape[1]))
        else:
            m = fixed(c, 4)
        if m is None:
            return None
        out.append(m)
    return out


def _straight(b: MoveBatch, rows: np.ndarray[Any, Any], k: float) -> Matrix | None:
    e = b.end[rows]
    nums = _pos([e[:, 0] / k, e[:, 1] / k, e[:, 2] / k, e[:, 3], e[:, 4], e[:, 5]])
    if nums is None:
        return None
    m = len(rows)
    name = choice([PREFIX + "STRAIGHT_TRAVERSE(", PREFIX + "STRAIGHT_FEED("], (b.kind[rows] != 0).astype(np.intp))
    sep = constant(", ", m)
    parts = [name]
    for i, num in enumerate(nums):
        if i:
            parts.append(sep)
        parts.append(num)
    parts.append(constant(")\n", m))
    return join_rows(parts)


def _arcs(b: MoveBatch, rows: np.ndarray[Any, Any], k: float) -> Matrix | None:
    p = b.plane
    e, c = b.end[rows], b.center[rows]
    nums = _pos([e[:, p.first] / k, e[:, p.second] / k, c[:, p.first] / k, c[:, p.second] / k])
    rest = _pos([e[:, p.normal] / k, e[:, 3], e[:, 4], e[:, 5]])
    if nums is None or rest is None:
        return None
    m = len(rows)
    sep = constant(", ", m)
    parts = [constant(PREFIX + "ARC_FEED(", m)]
    for num in nums:
        parts += [num, sep]
    parts += [integers(b.turns[rows])]
    for num in rest:
        parts += [sep, num]
    parts.append(constant(")\n", m))
    return join_rows(parts)
