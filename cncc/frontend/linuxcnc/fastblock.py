"""The plain-move fast path of the LinuxCNC executor.

Most blocks of a long LinuxCNC program are ``G1 X.. Y.. F..``: a straight move in a
plain state.  :func:`run_plain` lowers such a block to ``Rapid``/``Linear`` (and a
``FeedRate`` for its F word) directly, as the shared interpreter and the LinuxCNC
reporter together would, without building a block context, sorting the block's
commands or asking the reporter.  It declines (returns ``None``) whenever anything
else could happen: any word other than one G0/G1, axis words and F; any comment or
statement; a canned cycle, cutter compensation, inverse-time or
per-revolution feed, an XY rotation, a transform, G53, no feed, F0 or the
program ended.  ``tests/frontend/test_linuxcnc_fastblock.py`` checks that both paths
give the same canon trace on the LinuxCNC test programs.

A new LinuxCNC mode that changes what a plain move means (a new frame field, G7
diameter mode, ...) must make :func:`plain_state` false.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from cncc.frontend.syntax import Block, Word
from cncc.ir import Command, CompSide, FeedRate, Linear, Rapid, Vec6
from cncc.ir.frame import NOT_HELD
from cncc.source import Span

if TYPE_CHECKING:
    from cncc.frontend.interp import Interpreter

_AXES = {"X": 0, "Y": 1, "Z": 2}
_MOTION = {0.0: "rapid", 1.0: "linear"}


def plain_state(it: Interpreter, *, own_motion: bool = False) -> bool:
    """The interpreter's modes leave a straight move nothing else to do (``own_motion``: the block names
    G0 or G1, so the modal motion before it, an arc say, does not matter)."""
    from cncc.frontend.rs274 import state

    f, m = it.frame, it.modal
    if it.ended or m.cycle or m.per_rev or (not own_motion and m.motion not in ("rapid", "linear", "none")):
        return False
    if f.comp_side is not CompSide.OFF or f.polar is not None or f.scaling is not None or f.mirror is not None \
            or f.rotation is not None or f.machine_coords:
        return False
    st = state(it)
    return not st.inverse_time and not any(st.rotation_deg.values())


def _plain_words(motion: str, words: tuple[Word, ...]) -> tuple[str, list[int], Word | None] | None:
    """The block's motion, named axes and F word when it has only one G0/G1, X/Y/Z and F (N aside)."""
    axes: list[int] = []
    feed_word = None
    g_seen = False
    for w in words:
        letter = w.letter
        if w.expr is not None:
            return None
        if letter in _AXES:
            axes.append(_AXES[letter])
        elif letter == "G":
            got = _MOTION.get(w.value)
            if got is None or g_seen:  # another G code, or a second G0/G1
                return None
            motion, g_seen = got, True
        elif letter == "F" and feed_word is None:
            feed_word = w
        elif letter != "N":
            return None
    if not axes or motion not in ("rapid", "linear") or len(set(axes)) != len(axes):  # G38.x etc.: the full path
        return None
    return motion, axes, feed_word


def run_plain(it: Interpreter, block: Block, words: tuple[Word, ...]) -> list[Command] | None:
    """The commands of ``block`` (its ``words`` evaluated) when it is a plain move in a plain state,
    else None (nothing changed)."""
    if block.statements or block.comments:
        return None
    got = _plain_words(it.modal.motion, words)
    if got is None or not plain_state(it, own_motion=any(w.letter == "G" for w in words)):
        return None
    motion, axes, feed_word = got
    modal = it.modal
    feed = modal.feed if feed_word is None else feed_word.value
    if (motion == "linear" and (feed is None or feed <= 0.0)) or (feed_word is not None and feed_word.value < 0):
        return None  # no feed, F0 or a negative F: the interpreter reports it
    if it.frame.held_axes != NOT_HELD and not modal.incremental:
        it.release_axes(axes)  # as ops._release_named: named absolutely, no longer held
    end = _end(it, words)
    out: list[Command] = []
    frame, k, p = it.frame, it.frame.units.mm_per_unit, it.pos
    if feed_word is not None:
        out.append(FeedRate(Span(it.source_id, feed_word.start, feed_word.end), frame, feed_word.value * k, False))
    span = Span(it.source_id, block.start, block.end)
    if motion == "linear":
        assert feed is not None
        out.append(Linear(span, frame, p, end, feed * k, modal.path))
    else:
        out.append(Rapid(span, frame, p, end, modal.path))
    if motion != modal.motion or feed_word is not None:
        it.modal = modal.with_(motion=motion, feed=feed)
        code = it.dialect.code("G", 0 if motion == "rapid" else 10) if motion != modal.motion else None
        if code is not None:
            it.group_codes["motion"] = code.name
    it.pos = end
    return out


def _end(it: Interpreter, words: tuple[Word, ...]) -> Vec6:
    """The block's end point: its axis words, absolute or incremental, in mm."""
    rd, inc = it.reader, it.modal.incremental
    q = list(it.pos)
    for w in words:
        axis = _AXES.get(w.letter)
        if axis is not None:
            v = rd.axis_value(w)
            q[axis] = q[axis] + v if inc else v
    return (q[0], q[1], q[2], q[3], q[4], q[5])
