"""G-code for a batch of moves (:mod:`cncc.ir.batch`), a segment of rows at a time.

Consumes a :class:`~cncc.ir.batch.MoveBatch` and the emitter's state; produces the lines
:meth:`GcodeEmitter.one` writes for the batch's commands, and leaves the emitter in the state
it would have after them.  The first row, every arc and every row the plain case does not
cover go through :meth:`GcodeEmitter.one` (the definition); runs of rapids and lines that
follow it in the same frame -- where the emitter's per-move work is only the changed axis
words and the feed word -- are written with the vectorised number text of
:mod:`cncc.backends.numtext`: counts rounded as :func:`numbers.quantize` rounds (half away
from zero), words as :func:`numbers.counts_text` writes them.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING, Any

import numpy as np

from cncc.backends import numtext as nt
from cncc.backends.gcode.frames import add, sub
from cncc.backends.gcode.numbers import LARGEST, fixed
from cncc.ir import Frame
from cncc.ir.batch import ARC, LINEAR, MoveBatch
from cncc.source import Span

if TYPE_CHECKING:
    from cncc.backends.gcode.emit import GcodeEmitter

AXES = "XYZABC"
ANGLE_DECIMALS = 4


def batch_lines(em: GcodeEmitter, b: MoveBatch) -> Iterator[str]:
    """The lines of ``b``'s commands (see the module docstring)."""
    kinds = b.kind
    n = len(b)
    i = 0
    while i < n:
        if i == 0 or kinds[i] == ARC or not _plain(em, b):
            for cmd in b.rows(i, i + 1).commands():
                yield from em.one(cmd)
            i += 1
            continue
        stop = i
        while stop < n and kinds[stop] != ARC:
            stop += 1
        text = _segment(em, b, i, stop)
        if text is None:  # not safely vectorised: the segment's rows one by one
            for cmd in b.rows(i, stop).commands():
                yield from em.one(cmd)
        else:
            yield text
        i = stop


def _plain(em: GcodeEmitter, b: MoveBatch) -> bool:
    """The emitter's per-move work is the changed words only (its frame state converged on ``b``'s)."""
    f = b.frame
    return (em.probe is None and not em.call_depth and not em.in_alt and not em.opt.line_numbers
            and not em.g91_block and em.qpos is not None and not f.incremental and not em.all_axes
            and not em.restate
            and em.cycle_initial is None and em.held == f.held_axes and _synced(em, f))


def _synced(em: GcodeEmitter, f: Frame) -> bool:
    """:meth:`GcodeEmitter._sync` of ``f`` writes nothing and changes nothing (as after the row before)."""
    tf, t = em.tf, em.t
    if em.g92_force or tf.work_mm is None or (em.forced is None and f.units is not em.units) or f.plane is not em.plane:
        return False
    if f.work_index != tf.work_index and f.work_index in t.work:
        return False
    if sub(f.g92_offset_mm, tf.g92_in_local_mm) != tf.g92_mm:
        return False
    if add(f.local_offset_mm, tf.g92_in_local_mm) != tf.local_mm and t.has("local_offset"):
        return False
    if (f.tool_length_mm, f.tool_length_index) != (tf.tool_mm, tf.tool_index):
        return False
    if tf.fold(f, False) != em.fold:
        return False
    return not ((f.mirror != em.mirror and t.has("mirror_on")) or (f.rotation != em.rotation and t.has("rotate_on"))
                or (f.scaling != em.scaling and t.has("scale_on")))


def _counts(values: np.ndarray[Any, Any], decimals: int) -> np.ndarray[Any, Any] | None:
    """:func:`numbers.quantize` of every value (None: a value is not finite)."""
    scaled = values * float(10 ** decimals)
    if not bool(np.isfinite(scaled).all()):
        return None
    q = np.floor(np.minimum(np.abs(scaled), LARGEST) + 0.5).astype(np.int64)
    return np.where(scaled < 0, -q, q)


def _words(letter: str, counts: np.ndarray[Any, Any], decimals: int) -> nt.Matrix:
    """`` X<counts_text>`` per row: a point always, trailing zeros dropped, ``0.`` for zero."""
    m = len(counts)
    mag = np.abs(counts)
    one = 10 ** decimals
    whole, frac = mag // one, mag % one
    top = int(whole.max()) if m else 0
    sign = np.where(counts < 0, ord("-"), nt.PAD).astype(np.uint8)[:, None]
    parts = [nt.constant(" " + letter, m), sign, nt._digits(whole, max(1, len(str(top))), True), nt.constant(".", m)]
    if decimals:
        digits = nt._digits(frac, decimals, False)
        # trailing zeros of the fraction are dropped: a digit is kept if some digit at or after it is not 0
        nonzero = digits != 48
        keep = np.flip(np.logical_or.accumulate(np.flip(nonzero, axis=1), axis=1), axis=1)
        parts.append(np.where(keep, digits, nt.PAD).astype(np.uint8))
    return np.concatenate(parts, axis=1)


def _segment(em: GcodeEmitter, b: MoveBatch, lo: int, hi: int) -> str | None:
    """The lines of rows ``lo`` .. ``hi - 1`` (rapids and lines) with the emitter's state updated;
    None (state untouched) when a row needs the per-command path."""
    fold = np.array(em.fold or (0.0,) * 6)
    k = em.units.mm_per_unit
    dec = em.decimals
    end = b.end[lo:hi] + fold
    m = hi - lo
    q = np.empty((m, 6), dtype=np.int64)
    for axis in range(6):
        col = _counts(end[:, axis] / k, dec) if axis < 3 else _counts(end[:, axis], ANGLE_DECIMALS)
        if col is None:
            return None
        q[:, axis] = col
    prev = np.empty_like(q)
    prev[0] = em.qpos or [0] * 6  # never None here (_plain)
    prev[1:] = q[:-1]
    changed = q != prev
    if not bool(changed.any(axis=1).all()):  # a null move: the emitter chooses its one word
        return None
    kinds = b.kind[lo:hi]
    linear = kinds == LINEAR
    # the F words: only where the feed differs from the row before can one be written
    feed_index = np.zeros(m, dtype=np.intp)
    feed_texts = [""]
    written = em.feed
    rows = np.flatnonzero(linear)
    if len(rows):
        fl = b.feed[lo:hi][rows]
        points = np.flatnonzero(np.concatenate(([True], fl[1:] != fl[:-1])))
        for p in points.tolist():
            f = float(fl[p])
            if written is not None and abs(written - f) <= 1e-9 * max(1.0, f):
                continue
            written = f
            feed_texts.append(" F" + fixed(f / k, max(dec, 3)))
            feed_index[rows[p]] = len(feed_texts) - 1
    t = em.t
    code = nt.choice([t.code("rapid"), t.code("linear")], linear.astype(np.intp))
    parts = [code]
    for axis in range(6):
        if not bool(changed[:, axis].any()):
            continue
        words = _words(AXES[axis], q[:, axis], dec if axis < 3 else ANGLE_DECIMALS)
        parts.append(np.where(changed[:, axis][:, None], words, nt.PAD).astype(np.uint8))
    parts.append(nt.choice(feed_texts, feed_index))
    parts.append(nt.constant(t.dialect.block_end + "\n", m))
    rows_matrix = nt.join_rows(parts)
    limit = t.max_line_length
    if limit:
        lengths = (rows_matrix != nt.PAD).sum(axis=1) - 1
        if t.count_words_only:
            lengths -= (rows_matrix == 32).sum(axis=1) + len(t.dialect.block_end)
        if bool((lengths > limit).any()):
            return None
    text = nt.text_of(rows_matrix)
    # the state the per-command path leaves
    em.feed = written
    em.qpos = q[-1].tolist()
    moved = {axis for axis in range(6) if bool(changed[:, axis].any())}
    em.offgrid -= moved
    em.unknown -= moved
    em.span = Span(b.source_id, int(b.span_start[hi - 1]), int(b.span_end[hi - 1]))
    return text
