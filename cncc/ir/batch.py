"""A run of plain moves as arrays: :class:`MoveBatch` (docs/ir.md, "Batches").

Between mode changes a CAM program is thousands of rapids, lines and arcs that share one
frame, one path mode and one plane.  The front end's fast path hands such a run on as a
single :class:`MoveBatch` -- a struct of numpy arrays, one row per move -- instead of one
command object per move; passes and backends that know batches work on the arrays
(vectorised), every other stage sees the equivalent commands (:meth:`MoveBatch.commands`,
:func:`expand`), so stages adopt batches one at a time.

A batch stands for exactly this command sequence, for each row ``i`` in order:

* when ``feed_start[i] >= 0``: ``FeedRate(Span(source_id, feed_start[i], feed_end[i]),
  frame, feed[i])`` (the block's F word, written before its move);
* ``Rapid`` (``kind`` 0), ``Linear`` (1) or ``Arc`` (2) with span ``(span_start[i],
  span_end[i])``, the batch's ``frame`` and ``motion``, origin ``PROGRAMMED``, ``start`` =
  the previous row's end (``start0`` for row 0), ``end[i]``; a linear move has feed
  ``feed[i]``; an arc has ``center[i]``, ``turns[i]``, ``plane`` and ``feed[i]``.

Moves are continuous by construction: each starts where the one before ended.  This
module imports numpy only inside its functions, so importing it costs nothing at start-up.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from cncc.ir.commands import PROGRAMMED, Arc, Command, FeedRate, Linear, Motion, Rapid
from cncc.ir.frame import Frame, Plane, Vec6
from cncc.source import Span

if TYPE_CHECKING:
    import numpy as np
    import numpy.typing as npt

    F64 = npt.NDArray[np.float64]
    I64 = npt.NDArray[np.int64]
    I8 = npt.NDArray[np.int8]

RAPID, LINEAR, ARC = 0, 1, 2
_ZERO6 = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)


@dataclass(frozen=True, slots=True, eq=False)
class MoveBatch:
    """Consecutive moves under one frame, motion and plane (see the module docstring)."""

    source_id: int
    frame: Frame
    motion: Motion
    plane: Plane
    start0: Vec6  # where the first move starts
    kind: I8  # (n,) RAPID / LINEAR / ARC
    end: F64  # (n, 6) end points, mm and degrees, in the frame's program coordinates
    center: F64  # (n, 6) arc centres (the full 6-vector of Arc.center); rows of other moves unused
    turns: I8  # (n,) arcs: +1 counter-clockwise, -1 clockwise; 0 for other moves
    feed: F64  # (n,) the path feed in force for each move, mm/min
    span_start: I64  # (n,) each move's block, character offsets in ``source_id``
    span_end: I64
    feed_start: I64  # (n,) the F word before the move (-1: none)
    feed_end: I64

    def __len__(self) -> int:
        return len(self.kind)

    @property
    def span(self) -> Span:
        """The span of the first command the batch stands for."""
        fs = int(self.feed_start[0])
        if fs >= 0:
            return Span(self.source_id, fs, int(self.feed_end[0]))
        return Span(self.source_id, int(self.span_start[0]), int(self.span_end[0]))

    @property
    def last_end(self) -> Vec6:
        e = self.end[-1].tolist()
        return (e[0], e[1], e[2], e[3], e[4], e[5])

    @property
    def passes_whole(self) -> bool:
        """True when a pass that leaves these moves alone may pass the batch through whole.

        The per-command passes re-derive a move's start from the offset end of the move before
        whenever another command (an F word's ``FeedRate``) came between them, which changes the
        start's last bits under non-zero offsets; without F words, or without offsets, it does not."""
        f = self.frame
        if f.total_offset_mm == _ZERO6 and (f.rotation is None or not f.rotation.work):
            return True
        return not bool((self.feed_start >= 0).any())

    def starts(self) -> F64:
        """(n, 6): where each move starts (``start0``, then the previous ends)."""
        import numpy as np

        out = np.empty_like(self.end)
        out[0] = self.start0
        out[1:] = self.end[:-1]
        return out

    def commands(self) -> Iterator[Command]:
        """The commands this batch stands for, in order (equal to what the command path makes)."""
        sid, frame, motion, plane = self.source_id, self.frame, self.motion, self.plane
        kinds = self.kind.tolist()
        ends = [tuple(r) for r in self.end.tolist()]
        feeds = self.feed.tolist()
        s0, s1 = self.span_start.tolist(), self.span_end.tolist()
        f0, f1 = self.feed_start.tolist(), self.feed_end.tolist()
        has_arcs = ARC in kinds
        centres = [tuple(r) for r in self.center.tolist()] if has_arcs else []
        turns = self.turns.tolist() if has_arcs else []
        p: Vec6 = self.start0
        for i, k in enumerate(kinds):
            if f0[i] >= 0:
                yield FeedRate(Span(sid, f0[i], f1[i]), frame, feeds[i], False)
            q: Any = ends[i]
            span = Span(sid, s0[i], s1[i])
            if k == LINEAR:
                yield Linear(span, frame, p, q, feeds[i], motion, PROGRAMMED)
            elif k == RAPID:
                yield Rapid(span, frame, p, q, motion, PROGRAMMED)
            else:
                yield Arc(span, frame, p, q, centres[i], turns[i], plane, feeds[i], motion, PROGRAMMED)
            p = q

    def with_(self, **changes: Any) -> MoveBatch:
        """A copy with some fields replaced (the arrays are shared, never written)."""
        fields = {name: getattr(self, name) for name in _FIELDS}
        fields.update(changes)
        return MoveBatch(**fields)

    def rows(self, lo: int, hi: int) -> MoveBatch:
        """The moves ``lo`` .. ``hi - 1`` as a batch of their own."""
        start0 = self.start0 if lo == 0 else _vec(self.end[lo - 1])
        return MoveBatch(self.source_id, self.frame, self.motion, self.plane, start0, self.kind[lo:hi],
                         self.end[lo:hi], self.center[lo:hi], self.turns[lo:hi], self.feed[lo:hi],
                         self.span_start[lo:hi], self.span_end[lo:hi], self.feed_start[lo:hi],
                         self.feed_end[lo:hi])


_FIELDS = ("source_id", "frame", "motion", "plane", "start0", "kind", "end", "center", "turns", "feed",
           "span_start", "span_end", "feed_start", "feed_end")

Item = Command | MoveBatch
"""What flows between the stages of the compiler: a command, or a batch of moves."""


def _vec(row: Any) -> Vec6:
    r = row.tolist()
    return (r[0], r[1], r[2], r[3], r[4], r[5])


def expand(items: Iterable[Item]) -> Iterator[Command]:
    """``items`` with every batch replaced by its commands."""
    for x in items:
        if isinstance(x, MoveBatch):
            yield from x.commands()
        else:
            yield x


def command_count(items: Iterable[Item]) -> int:
    """How many commands ``items`` stand for (a batch counts its moves and F words)."""
    n = 0
    for x in items:
        if type(x) is MoveBatch:
            n += len(x) + int((x.feed_start >= 0).sum())
        else:
            n += 1
    return n


__all__ = ["ARC", "LINEAR", "RAPID", "Item", "MoveBatch", "command_count", "expand"]


REBATCH_MIN = 16  # shorter runs of moves stay commands
REBATCH_MAX = 8192  # rows per batch (bounds the memory a run holds)


def rebatch(items: Iterable[Item], sink: Any = None) -> Iterator[Item]:
    """``items`` with runs of consecutive moves made into batches again (batches pass as they are).

    A run is what :meth:`MoveBatch.commands` gives back exactly: programmed rapids, lines and arcs
    of one frame object, motion and source, arcs in the frame's plane, each starting where the one
    before ended, and ``FeedRate`` commands (not per revolution, same frame) just before a move
    whose feed is theirs.  A pass that works move by move (cutter compensation) hands on batches
    again this way, so the stages after it keep their vectorised paths.

    Diagnostics keep their order: what the stages before report while a run is held is taken out
    of ``sink``'s list, the run is handed on (the stages after report on its moves), and the
    reports are put back after those, as the command path orders them.  The same objects go
    back, so a stage that updates its own report in place (W0513's list of offsets) finds it."""
    run: list[Command] = []
    feed_in_force = -1.0  # a rapid row's feed: the last feed seen (the front end's rule)
    before = -1.0  # the feed in force before the run
    def flush() -> Iterator[Item]:
        if len(run) - (isinstance(run[-1], FeedRate) if run else 0) >= REBATCH_MIN:
            tail = [run.pop()] if isinstance(run[-1], FeedRate) else []
            yield _batch_of(run, before)
            yield from tail
        else:
            yield from run
        run.clear()

    sink = _innermost(sink)
    source = iter(items)
    while True:
        held = len(sink.items) if sink is not None and run else -1
        x = next(source, None)
        if 0 <= held < len(sink.items):  # reports of the stages before: after the stages after saw the run
            early = sink.items[held:]
            del sink.items[held:]
            yield from flush()
            sink.items.extend(early)
        if x is None:
            break
        if isinstance(x, MoveBatch):
            yield from flush()
            yield x
            feed_in_force = float(x.feed[-1])
            continue
        if run and not _continues(run, x):
            yield from flush()
        if not run:
            before = feed_in_force
        if isinstance(x, FeedRate):
            feed_in_force = x.feed
            if x.per_rev:
                yield x
                continue
            run.append(x)
        elif _row(x):
            assert isinstance(x, Rapid | Linear | Arc)
            run.append(x)
            if isinstance(x, Linear | Arc):
                feed_in_force = x.feed_mm_min
            if len(run) >= REBATCH_MAX:
                yield from flush()
        else:
            yield x
    yield from flush()


def _innermost(sink: Any) -> Any:
    """A wrapping sink's reports reach its inner sink: those are the ones to keep back."""
    while sink is not None and hasattr(sink, "inner"):
        sink = sink.inner
    return sink


def _row(c: Command) -> bool:
    """A move a batch row can stand for."""
    return isinstance(c, Rapid | Linear | Arc) and c.origin == PROGRAMMED and (
        not isinstance(c, Arc) or (c.plane is c.frame.plane and abs(c.turns) < 100))


def _continues(run: list[Command], c: Command) -> bool:
    """``c`` may follow the run (see :func:`rebatch`)."""
    last = run[-1]
    frame = last.frame
    if c.frame is not frame or c.span.source_id != last.span.source_id:
        return False
    if isinstance(c, FeedRate):
        return not isinstance(last, FeedRate) and not c.per_rev
    if not _row(c):
        return False
    assert isinstance(c, Rapid | Linear | Arc)
    if isinstance(last, FeedRate):
        if isinstance(c, Linear | Arc) and c.feed_mm_min != last.feed:
            return False
        if len(run) < 2:
            return True
        prev = run[-2]
    else:
        prev = last
    assert isinstance(prev, Rapid | Linear | Arc)
    return c.motion == prev.motion and c.start == prev.end


def _batch_of(run: list[Command], last_feed: float) -> MoveBatch:
    import numpy as np

    moves = [c for c in run if not isinstance(c, FeedRate)]
    first = moves[0]
    assert isinstance(first, Rapid | Linear | Arc)
    n = len(moves)
    kind = np.empty(n, dtype=np.int8)
    feed = np.empty(n)
    turns = np.zeros(n, dtype=np.int8)
    centre = np.zeros((n, 6))
    fs = np.full(n, -1, dtype=np.int64)
    fe = np.full(n, -1, dtype=np.int64)
    s0 = np.empty(n, dtype=np.int64)
    s1 = np.empty(n, dtype=np.int64)
    ends = []
    k = 0
    pending: FeedRate | None = None
    for c in run:
        if isinstance(c, FeedRate):
            pending = c
            continue
        assert isinstance(c, Rapid | Linear | Arc)
        ends.append(c.end)
        s0[k], s1[k] = c.span.start, c.span.end
        if pending is not None:
            fs[k], fe[k] = pending.span.start, pending.span.end
            last_feed = pending.feed
            pending = None
        if isinstance(c, Rapid):
            kind[k], feed[k] = RAPID, last_feed
        elif isinstance(c, Linear):
            kind[k], feed[k] = LINEAR, c.feed_mm_min
            last_feed = c.feed_mm_min
        else:
            assert isinstance(c, Arc)
            kind[k], feed[k], turns[k] = ARC, c.feed_mm_min, c.turns
            centre[k] = c.center
            last_feed = c.feed_mm_min
        k += 1
    return MoveBatch(first.span.source_id, first.frame, first.motion, first.frame.plane, first.start, kind,
                     np.array(ends, dtype=np.float64), centre, turns, feed, s0, s1, fs, fe)
