"""``arc-check``: start/end radius mismatch against LinuxCNC's tolerances, and repair."""

from __future__ import annotations

import math
from typing import Any

from cncc.diagnostics import DiagnosticSink
from cncc.ir import Arc, Frame, Plane
from cncc.passes import PassContext
from cncc.passes.arc_check import ArcCheck
from cncc.source import Span


def _arc(end_x: float, radius: float = 10.0) -> Arc:
    """A CCW arc about the origin from (R, 0) to (end_x, ...) on the circle of radius R, then moved."""
    y = math.sqrt(radius * radius - (radius - 1.0) ** 2)
    return Arc(Span(0, 0, 5), Frame(), (radius, 0.0, 0.0, 0, 0, 0), (end_x, y, 0.0, 0, 0, 0),
               (0.0, 0.0, 0.0, 0, 0, 0), 1, Plane.XY, 100.0)


def _check(arc: Arc, **opts: object) -> tuple[list[Any], list[str], DiagnosticSink]:
    sink = DiagnosticSink()
    out = list(ArcCheck(**opts).run([arc], PassContext(sink=sink)))  # type: ignore[arg-type]
    return out, [d.code for d in sink], sink


def test_default_tolerance_is_linuxcncs() -> None:
    assert ArcCheck.abs_tol_mm == 0.01 * math.sqrt(2.0) * 2.0 and ArcCheck.rel_tol == 0.001


def test_mismatch_within_the_absolute_tolerance_passes() -> None:
    out, codes, _ = _check(_arc(9.0 + 0.02))  # end radius off by about 0.018 mm < 0.0283
    assert codes == [] and len(out) == 1


def test_mismatch_beyond_the_tolerance_is_an_error() -> None:
    out, codes, _ = _check(_arc(9.0 + 0.05))
    assert codes == ["E0208"] and out == []


def test_relative_tolerance_for_large_arcs() -> None:
    big = _arc(999.0 + 0.5, radius=1000.0)  # about 0.5 mm on R1000: within 0.1 %
    assert _check(big)[1] == []
    assert _check(big, rel_tol=0.0)[1] == ["E0208"]


def test_repair_moves_the_centre_and_says_where() -> None:
    arc = _arc(9.0 + 0.05)
    out, codes, sink = _check(arc, repair=True)
    assert codes == ["W0511"]
    fixed = out[0]
    r0 = math.dist(fixed.start[:2], fixed.center[:2])
    r1 = math.dist(fixed.end[:2], fixed.center[:2])
    assert abs(r0 - r1) < 1e-9 and abs(r0 - 10.0) < 1e-9  # keeps the start radius
    moved = math.dist(fixed.center[:2], arc.center[:2])
    assert f"{moved:.4f}" in sink.items[0].message and f"{fixed.center[0]:.4f}" in sink.items[0].message
    # the centre stays on the programmed side of the chord
    chord = (arc.end[0] - arc.start[0], arc.end[1] - arc.start[1])
    side = chord[0] * (fixed.center[1] - arc.start[1]) - chord[1] * (fixed.center[0] - arc.start[0])
    orig = chord[0] * (arc.center[1] - arc.start[1]) - chord[1] * (arc.center[0] - arc.start[0])
    assert side * orig > 0
