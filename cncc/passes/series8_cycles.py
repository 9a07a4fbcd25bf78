"""The hole sequences of the SERIES 8 cycle kinds, registered into ``expand-cycles``.

Consumes nothing by itself: :data:`cncc.passes.expand_cycles.SEQUENCES` merges its :data:`SEQUENCES`,
the per-hole moves of the kinds only SERIES 8 has (spec series8.md 4.14; levels are
absolute, every hole ends at R except G87 and G89):

* ``peck_first`` (G83): to R; feed to the level I; then, after a rapid back to R and a
  rapid down to the clearance above the last depth, feed J deeper, until Z;
* ``bore_dwell_stop_out`` / ``..._rapid_out`` (G86): feed to Z, dwell, spindle stop,
  out to R at feed (or rapid), spindle on again;
* ``case_bore`` (G87): rapid to R, feed to Z, stay there;
* ``bore_orient_out`` / ``..._rapid_out`` (G88): feed to Z, dwell, orient, shift by
  I J, out to R at feed (or rapid), back to the hole centre, spindle on;
* ``back_bore_return`` (G89): orient, shift, rapid down through the hole to R,
  centre, spindle on, feed up to Z, dwell, feed back to R, orient, shift, rapid up to
  the starting level, centre, spindle on.
"""

from __future__ import annotations

from cncc.dialects.series8_cycles import Series8CycleKind
from cncc.ir import CycleKindBase, SpindleState
from cncc.passes.cycle_path import CyclePath as _Path
from cncc.passes.cycle_path import Sequence

SEQUENCES: dict[CycleKindBase, Sequence] = {}  # this module's kinds (expand_cycles.SEQUENCES merges them)


def first_peck_depths(r_mm: float, bottom_mm: float, first_mm: float | None, peck_mm: float) -> list[float]:
    """Bottoms of the G83 strokes: the first at ``first_mm``, then ``peck_mm`` deeper each, the last at Z."""
    down = -1.0 if bottom_mm < r_mm else 1.0
    depth = first_mm if first_mm is not None else r_mm + down * peck_mm
    if (bottom_mm - depth) * down <= 0 or peck_mm <= 0:
        return [bottom_mm]
    out = [depth]
    while (bottom_mm - out[-1]) * down > 1e-9:
        nxt = out[-1] + down * peck_mm
        out.append(bottom_mm if (bottom_mm - nxt) * down < 1e-9 else nxt)
    return out


def _peck_first(p: _Path) -> None:
    c = p.c
    p.rapid(p.at(c.r_mm))
    depths = first_peck_depths(c.r_mm, c.bottom_mm, c.first_depth_mm, c.peck_mm)
    for k, b in enumerate(depths):
        if k:
            p.rapid(p.at(c.r_mm))
            p.rapid(p.at(depths[k - 1] - p.down * c.clearance_mm))
        p.feed(p.at(b))
    p.rapid(p.at(c.retract_mm))


def _stop_out(p: _Path) -> None:
    c = p.c
    p.rapid(p.at(c.r_mm))
    p.feed(p.at(c.bottom_mm))
    p.dwell()
    p.spindle(SpindleState.OFF)
    (p.rapid if c.kind is Series8CycleKind.BORE_DWELL_STOP_RAPID_OUT else p.feed)(p.at(c.r_mm))
    p.spindle(p.forward)
    p.rapid(p.at(c.retract_mm))


def _case_bore(p: _Path) -> None:
    c = p.c
    p.rapid(p.at(c.r_mm))
    p.feed(p.at(c.bottom_mm))


def _orient_out(p: _Path) -> None:
    c = p.c
    p.rapid(p.at(c.r_mm))
    p.feed(p.at(c.bottom_mm))
    p.dwell()
    p.spindle(SpindleState.ORIENT)
    p.rapid(p.at(c.bottom_mm, shifted=True))
    (p.rapid if c.kind is Series8CycleKind.BORE_ORIENT_RAPID_OUT else p.feed)(p.at(c.r_mm, shifted=True))
    p.rapid(p.at(c.r_mm))
    p.spindle(p.forward)
    p.rapid(p.at(c.retract_mm))


def _back_bore_return(p: _Path) -> None:
    c = p.c
    p.spindle(SpindleState.ORIENT)
    p.rapid(p.at(p.pos[c.axis], shifted=True))
    p.rapid(p.at(c.r_mm, shifted=True))
    p.rapid(p.at(c.r_mm))
    p.spindle(p.forward)
    p.feed(p.at(c.bottom_mm))
    p.dwell()
    p.feed(p.at(c.r_mm))
    p.spindle(SpindleState.ORIENT)
    p.rapid(p.at(c.r_mm, shifted=True))
    p.rapid(p.at(c.retract_mm, shifted=True))
    p.rapid(p.at(c.retract_mm))
    p.spindle(p.forward)


SEQUENCES.update({
    Series8CycleKind.PECK_FIRST: _peck_first,
    Series8CycleKind.BORE_DWELL_STOP_OUT: _stop_out,
    Series8CycleKind.BORE_DWELL_STOP_RAPID_OUT: _stop_out,
    Series8CycleKind.CASE_BORE: _case_bore,
    Series8CycleKind.BORE_ORIENT_OUT: _orient_out,
    Series8CycleKind.BORE_ORIENT_RAPID_OUT: _orient_out,
    Series8CycleKind.BACK_BORE_RETURN: _back_bore_return,
})
