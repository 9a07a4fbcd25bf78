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

import bisect
from collections.abc import Iterator
from typing import TYPE_CHECKING, Any

import numpy as np

from cncc.backends import numtext as nt
from cncc.backends.gcode.arcs import ARC_LETTERS
from cncc.backends.gcode.frames import add, sub
from cncc.backends.gcode.numbers import LARGEST, fixed
from cncc.ir import Frame
from cncc.ir.batch import ARC, LINEAR, RAPID, MoveBatch
from cncc.source import Span

if TYPE_CHECKING:
    from cncc.backends.gcode.emit import GcodeEmitter

AXES = "XYZABC"
_WINDOW = 1 << 14
ANGLE_DECIMALS = 4


def batch_lines(em: GcodeEmitter, b: MoveBatch) -> Iterator[str]:
    """The lines of ``b``'s commands (see the module docstring)."""
    kinds = b.kind
    n = len(b)
    arc = kinds == ARC
    arcs = np.flatnonzero(arc).tolist()
    hard = np.flatnonzero(arc & ~_simple_arcs(em, b)).tolist()  # arcs the segment never writes
    plane_axes = {b.plane.first, b.plane.second}
    i = 0
    window = _WINDOW  # rows a segment looks at: shrinks where segments end early (null moves, helices)
    while i < n:
        stop = i
        if i and _plain(em, b):
            # the rows the segment writes: rapids, lines and single-block arcs (no arc while a plane axis
            # is off the grid: the emitter then takes the centre offsets from the position itself)
            stops = arcs if plane_axes & em.offgrid else hard
            k = bisect.bisect_left(stops, i)
            stop = min(stops[k] if k < len(stops) else n, i + window)
        done = _segment(em, b, i, stop) if stop > i else ("", i)
        if done is None:  # not safely vectorised: the segment's rows through the emitter
            for cmd in b.rows(i, stop).commands():
                yield from em.one(cmd)
            i = stop
        elif done[1] == i:  # this row through the emitter
            for cmd in b.rows(i, i + 1).commands():
                yield from em.one(cmd)
            i += 1
        else:
            yield done[0]
            window = min(_WINDOW, 2 * window) if done[1] == stop else max(64, 4 * (done[1] - i))
            i = done[1]


def _simple_arcs(em: GcodeEmitter, b: MoveBatch) -> np.ndarray[Any, Any]:
    """Per row: an arc :meth:`GcodeEmitter._arc` writes as one block of I/J words whose feed is the
    arc's own (one turn, flat in program coordinates, not near a full circle the target would split),
    so the segment can write it; False on the other rows."""
    t = em.t
    kinds = b.kind
    arc = kinds == ARC
    if not bool(arc.any()) or t.single_quadrant or t.arc_form == "r":
        return np.zeros(len(b), dtype=bool)
    pl = b.plane
    i, j, nrm = pl.first, pl.second, pl.normal
    start = b.starts()
    end, c = b.end, b.center
    ok = arc & (np.abs(b.turns) == 1) & (end[:, nrm] == start[:, nrm])
    if not t.full_circle:  # a circle the target cannot write in one block is split: leave those to the emitter
        a0 = np.arctan2(start[:, j] - c[:, j], start[:, i] - c[:, i])
        a1 = np.arctan2(end[:, j] - c[:, j], end[:, i] - c[:, i])
        d = np.where(b.turns > 0, a1 - a0, a0 - a1) % (2.0 * np.pi)
        ok &= (d > 1e-6) & (d < np.radians(359.99))
    out: np.ndarray[Any, Any] = ok
    return out


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


def _segment(em: GcodeEmitter, b: MoveBatch, lo: int, hi: int) -> tuple[str, int] | None:
    """The lines of rows ``lo`` .. ``stop - 1`` (rapids, lines and the arcs :func:`_simple_arcs`
    admits) and ``stop`` (``hi``, or the first null move or arc whose written numbers rise along the
    plane's normal), with the emitter's state updated; None (state untouched) when a row of the
    segment needs the per-command path (a value not finite, a line too long)."""
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
    kinds = b.kind[lo:hi]
    arc = kinds == ARC
    pl = b.plane
    changed = q != prev
    changed[:, pl.first] |= arc  # an arc writes both plane axes (full circles too)
    changed[:, pl.second] |= arc
    # a null move (the emitter chooses its one word) and a helix (its F is the projection's, from the
    # rise written) go to the emitter: the segment ends before the first one
    odd = ~changed.any(axis=1) | (arc & (q[:, pl.normal] != prev[:, pl.normal]))
    if bool(odd.any()):
        first = int(np.flatnonzero(odd)[0])
        return ("", lo) if first == 0 else _segment(em, b, lo, lo + first)
    written, feed_texts, feed_index = _feed_words(em, b, lo, hi, kinds != RAPID)
    t = em.t
    code_index = np.where(kinds == LINEAR, 1, 0)
    arcs = np.flatnonzero(arc)
    if len(arcs):
        code_index[arcs] = np.where(b.turns[lo:hi][arcs] > 0, 2, 3)
    code = nt.choice([t.code("rapid"), t.code("linear"), t.code("arc_ccw"), t.code("arc_cw")], code_index)
    parts = [code]
    for axis in range(6):
        if not bool(changed[:, axis].any()):
            continue
        words = _words(AXES[axis], q[:, axis], dec if axis < 3 else ANGLE_DECIMALS)
        parts.append(np.where(changed[:, axis][:, None], words, nt.PAD).astype(np.uint8))
    if len(arcs):
        centre = _centre_words(em, b, lo, hi, arcs, prev, fold)
        if centre is None:
            return None
        parts += centre
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
    return text, hi


def _feed_words(em: GcodeEmitter, b: MoveBatch, lo: int, hi: int, feeding: np.ndarray[Any, Any]
                ) -> tuple[float | None, list[str], np.ndarray[Any, Any]]:
    """The F words of the feed moves of rows ``lo`` .. ``hi - 1``: only where the feed differs from
    the row before can one be written (the feed written last, the texts, per row its text)."""
    m = hi - lo
    k = em.units.mm_per_unit
    feed_index = np.zeros(m, dtype=np.intp)
    feed_texts = [""]
    written = em.feed
    rows = np.flatnonzero(feeding)
    if len(rows):
        fl = b.feed[lo:hi][rows]
        points = np.flatnonzero(np.concatenate(([True], fl[1:] != fl[:-1])))
        for p in points.tolist():
            f = float(fl[p])
            if written is not None and abs(written - f) <= 1e-9 * max(1.0, f):
                continue
            written = f
            feed_texts.append(" F" + fixed(f / k, max(em.decimals, 3)))
            feed_index[rows[p]] = len(feed_texts) - 1
    return written, feed_texts, feed_index


def _centre_words(em: GcodeEmitter, b: MoveBatch, lo: int, hi: int, arcs: np.ndarray[Any, Any],
                  prev: np.ndarray[Any, Any], fold: np.ndarray[Any, Any]) -> list[nt.Matrix] | None:
    """The I/J (J/K, K/I) words of the arcs among rows ``lo`` .. ``hi - 1``, as
    :meth:`GcodeEmitter._centre_offsets` makes them with no plane axis off the grid: the centre's
    counts less the written start's (``prev``)."""
    pl = b.plane
    k = em.units.mm_per_unit
    centre = b.center[lo:hi][arcs]
    out = []
    for axis, letter in zip((pl.first, pl.second), ARC_LETTERS[pl], strict=True):
        cq = _counts((centre[:, axis] + fold[axis]) / k, em.decimals)
        if cq is None:
            return None
        words = _words(letter, cq - prev[arcs, axis], em.decimals)
        col = np.zeros((hi - lo, words.shape[1]), dtype=np.uint8)
        col[arcs] = words
        out.append(col)
    return out
