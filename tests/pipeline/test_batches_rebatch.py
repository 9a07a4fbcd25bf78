"""``cncc.ir.batch.rebatch`` hands on exactly the commands it was given (after ``expand``), and
makes batches of the runs it may (cutter compensation's output goes through it)."""

from __future__ import annotations

import dataclasses

from hypothesis import given, settings
from hypothesis import strategies as st

from cncc.ir import Arc, Dwell, FeedRate, Frame, Linear, Plane, Rapid
from cncc.ir.batch import REBATCH_MIN, MoveBatch, expand, rebatch
from cncc.ir.commands import MACHINE_ORIGIN
from cncc.source import Span

F1 = Frame()
F2 = dataclasses.replace(Frame(), plane=Plane.ZX)

step = st.tuples(
    st.sampled_from(["rapid", "line", "line", "line", "arc", "feed", "feed_other", "dwell", "jump", "g53", "frame",
                     "rev"]),
    st.floats(-50, 50, allow_nan=False), st.floats(-50, 50, allow_nan=False), st.sampled_from([800.0, 1200.0, -1.0]))


def commands(steps: list[tuple[str, float, float, float]]) -> list[object]:
    out: list[object] = []
    p = (0.0,) * 6
    frame = F1
    at = 0
    for what, x, y, f in steps:
        at += 3
        span = Span(1, at, at + 2)
        q = (x, y, p[2], 0.0, 0.0, 0.0)
        if what == "frame":
            frame = F2 if frame is F1 else F1
        elif what == "rapid":
            out.append(Rapid(span, frame, p, q))
        elif what == "line":
            out.append(Linear(span, frame, p, q, f))
        elif what == "arc":
            out.append(Arc(span, frame, p, q, ((p[0] + x) / 2, (p[1] + y) / 2, 0.0, 0.0, 0.0, 0.0),
                           1 if x > 0 else -3, frame.plane if y > 0 else Plane.YZ, f))
        elif what in ("feed", "feed_other", "rev"):
            out.append(FeedRate(span, frame, f if what == "feed" else 999.0, what == "rev"))
            continue
        elif what == "dwell":
            out.append(Dwell(span, frame, 0.5))
            continue
        elif what == "jump":
            p = (x, x, 1.0, 0.0, 0.0, 0.0)
            continue
        elif what == "g53":
            out.append(Rapid(span, frame, p, q, origin=MACHINE_ORIGIN))
        p = q
    return out


@settings(max_examples=300, deadline=None)
@given(st.lists(step, max_size=120), st.integers(0, 3))
def test_expand_gives_back_the_commands(steps: list[tuple[str, float, float, float]], copies: int) -> None:
    cmds = commands(steps) * 1 + commands([("line", float(k), 1.0, 800.0) for k in range(REBATCH_MIN * copies)])
    assert list(expand(rebatch(cmds))) == cmds  # type: ignore[arg-type]


def test_runs_become_batches() -> None:
    steps = [("feed", 0.0, 0.0, 800.0)] + [("line", float(k), k % 3, 800.0) for k in range(40)] + [("dwell", 0, 0, 0)]
    steps += [("rapid", float(k), 2.0, 0.0) for k in range(3)]
    cmds = commands(steps)
    items = list(rebatch(cmds))  # type: ignore[arg-type]
    assert isinstance(items[0], MoveBatch) and len(items[0]) == 40 and items[0].feed_start[0] >= 0
    assert [type(x).__name__ for x in items[1:]] == ["Dwell", "Rapid", "Rapid", "Rapid"]  # a short run stays
    assert list(expand(items)) == cmds
