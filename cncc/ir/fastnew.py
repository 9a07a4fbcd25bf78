"""Fast constructors for the hottest IR objects.

A frozen dataclass's generated ``__init__`` calls ``object.__setattr__`` through a
global lookup for every field; on a million-line program that is a measurable part
of the front end.  These helpers build the *same* objects (equal, hashable,
immutable) by setting the slots through their descriptors.  Only the front end's
plain-block fast path uses them; everything else constructs normally.
"""

from __future__ import annotations

from cncc.ir.commands import PROGRAMMED, Linear, Motion, Rapid
from cncc.ir.frame import Frame, Vec6
from cncc.source import Span

_new = object.__new__
_sp_id, _sp_start, _sp_end = (getattr(Span, n).__set__ for n in ("source_id", "start", "end"))
_l_set = tuple(getattr(Linear, n).__set__ for n in ("span", "frame", "start", "end", "feed_mm_min", "motion", "origin"))
_r_set = tuple(getattr(Rapid, n).__set__ for n in ("span", "frame", "start", "end", "motion", "origin"))


def new_span(source_id: int, start: int, end: int) -> Span:
    o = _new(Span)
    _sp_id(o, source_id)
    _sp_start(o, start)
    _sp_end(o, end)
    return o


def new_linear(span: Span, frame: Frame, start: Vec6, end: Vec6, feed_mm_min: float, motion: Motion) -> Linear:
    o = _new(Linear)
    a, b, c, d, e, f, g = _l_set
    a(o, span)
    b(o, frame)
    c(o, start)
    d(o, end)
    e(o, feed_mm_min)
    f(o, motion)
    g(o, PROGRAMMED)
    return o


def new_rapid(span: Span, frame: Frame, start: Vec6, end: Vec6, motion: Motion) -> Rapid:
    o = _new(Rapid)
    a, b, c, d, e, f = _r_set
    a(o, span)
    b(o, frame)
    c(o, start)
    d(o, end)
    e(o, motion)
    f(o, PROGRAMMED)
    return o
