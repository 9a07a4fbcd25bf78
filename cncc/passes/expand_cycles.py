"""``expand-cycles``: canned cycles to rapids, feeds, dwells and spindle events.

Consumes :class:`cncc.ir.Cycle` commands (everything else passes through) and yields,
per hole, the moves the controller makes, in the cycle's own frame:

* positioning: a rapid in the plane at the current height (under a transform even when
  it is zero-length in program coordinates: see ``_Path.position``), then its own rapid
  to R;
* the cycle's in-feed, bottom action and retract (table in ``docs/cycles.md``);
* every move has the exact-stop path mode and ``origin`` set to the cycle code.

Tapping moves are bracketed by ``SpindleSync(pitch_mm)`` and
``SpindleSync(0.0)``: in between, the feed axis follows the spindle
(feed = rpm x pitch, overrides locked at 100 %).  Spindle reversals, stops, orients
and restarts are :class:`Spindle` commands; the G88 manual retract is a :class:`Wait`.
Other zero-length moves are left out (a G99 hole starts at R already).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from typing import ClassVar

from cncc.ir import (
    Command,
    Cycle,
    CycleKind,
    CycleKindBase,
    Origin,
    OriginKind,
    Rapid,
    SpindleState,
)
from cncc.ir.batch import Item
from cncc.passes import Pass, PassContext, linuxcnc_cycles, register, series8_cycles
from cncc.passes.cycle_path import CyclePath as _Path
from cncc.passes.cycle_path import Sequence

MANUAL_RETRACT = "operator: retract the tool by hand, then cycle start (G88)"


@register
@dataclass(frozen=True, kw_only=True)
class ExpandCycles(Pass):
    """Lower every canned cycle to primitive moves (except the kinds in ``keep``)."""

    name: ClassVar[str] = "expand-cycles"
    keep: frozenset[str] = frozenset()  # cycle kinds left whole (the G-code backend writes them)

    def run(self, cmds: Iterable[Command], ctx: PassContext) -> Iterator[Command]:
        for c in cmds:
            if isinstance(c, Cycle) and c.kind.value not in self.keep:
                yield from expand(c)
            else:
                yield c

    def run_items(self, items: Iterable[Item], ctx: PassContext) -> Iterator[Item]:
        """Batches of moves (:mod:`cncc.ir.batch`) hold no cycles: they pass through."""
        for c in items:
            if isinstance(c, Cycle) and c.kind.value not in self.keep:
                yield from expand(c)
            else:
                yield c


def expand(c: Cycle) -> list[Command]:
    """The primitive commands of one cycle command."""
    path = _Path(c)
    sequence = SEQUENCES[c.kind]
    for hole in c.holes:
        path.hole = hole
        path.frame = c.frame
        over = path.at(path.pos[c.axis])
        if c.zero_moves and over == path.pos:  # rs274 prints the move even when it has no length
            path.out.append(Rapid(c.span, c.frame, over, over, path.motion, Origin(OriginKind.CYCLE, c.code)))
        else:
            path.position(over)
        path.frame = path.levels_frame
        sequence(path)
    return path.out


def peck_depths(r_mm: float, bottom_mm: float, peck_mm: float) -> list[float]:
    """Bottoms of the successive pecks from R; the last one is the hole bottom."""
    depth = abs(bottom_mm - r_mm)
    down = -1.0 if bottom_mm < r_mm else 1.0
    if peck_mm <= 0:
        return [bottom_mm]
    n = max(1, math.ceil(depth / peck_mm - 1e-9))
    return [r_mm + down * k * peck_mm for k in range(1, n)] + [bottom_mm]


# ---- one hole of each kind (the tool is above the hole at the positioning height) -----------------
def _drill(p: _Path) -> None:
    c = p.c
    p.rapid(p.at(c.r_mm))
    p.feed(p.at(c.bottom_mm))
    if c.kind is CycleKind.DRILL_DWELL:
        p.dwell()
    p.rapid(p.at(c.retract_mm))


def _peck_high_speed(p: _Path) -> None:
    c = p.c
    p.rapid(p.at(c.r_mm))
    depths = peck_depths(c.r_mm, c.bottom_mm, c.peck_mm)
    for b in depths[:-1]:
        p.feed(p.at(b))
        p.lift(p.at(b - p.down * c.clearance_mm))
    p.feed(p.at(c.bottom_mm))
    p.rapid(p.at(c.retract_mm))


def _peck(p: _Path) -> None:
    c = p.c
    p.rapid(p.at(c.r_mm))
    depths = peck_depths(c.r_mm, c.bottom_mm, c.peck_mm)
    for k, b in enumerate(depths):
        if k:
            p.lift(p.at(c.r_mm))
            back = depths[k - 1] - p.down * c.clearance_mm
            p.rapid(p.at(back if (back - c.r_mm) * p.down > 0 else c.r_mm))
        p.feed(p.at(b))
    p.rapid(p.at(c.retract_mm))


def _tap(p: _Path) -> None:
    c = p.c
    p.rapid(p.at(c.r_mm))
    p.sync(c.tap_pitch_mm)
    depths = peck_depths(c.r_mm, c.bottom_mm, c.peck_mm)
    for k, b in enumerate(depths):
        p.feed(p.at(b))
        p.dwell()
        p.spindle(p.reverse())
        last = k == len(depths) - 1
        p.feed(p.at(c.r_mm if last or c.peck_tap_to_r else b - p.down * c.clearance_mm))
        p.dwell()
        p.spindle(p.forward)
    p.sync(0.0)
    p.rapid(p.at(c.retract_mm))


def _feed_out(p: _Path) -> None:
    c = p.c
    p.rapid(p.at(c.r_mm))
    p.feed(p.at(c.bottom_mm))
    if c.kind is CycleKind.BORE_DWELL_FEED_OUT:
        p.dwell()
    p.feed(p.at(c.r_mm))
    p.rapid(p.at(c.retract_mm))


def _stop_rapid_out(p: _Path) -> None:
    c = p.c
    p.rapid(p.at(c.r_mm))
    p.feed(p.at(c.bottom_mm))
    p.spindle(SpindleState.OFF)
    p.rapid(p.at(c.retract_mm))
    p.spindle(p.forward)


def _dwell_orient_shift_out(p: _Path) -> None:
    """At the bottom: dwell, oriented stop, shift off the wall, rapid out, shift back, restart."""
    c = p.c
    p.dwell()
    p.spindle(SpindleState.ORIENT)
    p.rapid(p.at(c.bottom_mm, shifted=True))
    p.rapid(p.at(c.retract_mm, shifted=True))
    p.rapid(p.at(c.retract_mm))
    p.spindle(p.forward)


def _fine_bore(p: _Path) -> None:
    c = p.c
    p.rapid(p.at(c.r_mm))
    p.feed(p.at(c.bottom_mm))
    _dwell_orient_shift_out(p)


def _back_bore(p: _Path) -> None:
    c = p.c
    level = p.pos[c.axis]
    p.spindle(SpindleState.ORIENT)
    p.rapid(p.at(level, shifted=True))
    p.rapid(p.at(c.r_mm, shifted=True))
    p.rapid(p.at(c.r_mm))
    p.spindle(p.forward)
    p.feed(p.at(c.bottom_mm))
    _dwell_orient_shift_out(p)


def _manual(p: _Path) -> None:
    c = p.c
    p.rapid(p.at(c.r_mm))
    p.feed(p.at(c.bottom_mm))
    p.dwell()
    p.spindle(SpindleState.OFF)
    p.wait(MANUAL_RETRACT)
    p.feed(p.at(c.r_mm))
    p.rapid(p.at(c.retract_mm))
    p.spindle(p.forward)


SEQUENCES: dict[CycleKindBase, Sequence] = {
    CycleKind.DRILL: _drill,
    CycleKind.DRILL_DWELL: _drill,
    CycleKind.PECK_HIGH_SPEED: _peck_high_speed,
    CycleKind.PECK: _peck,
    CycleKind.TAP: _tap,
    CycleKind.TAP_LEFT: _tap,
    CycleKind.FINE_BORE: _fine_bore,
    CycleKind.BORE_FEED_OUT: _feed_out,
    CycleKind.BORE_DWELL_FEED_OUT: _feed_out,
    CycleKind.BORE_STOP_RAPID_OUT: _stop_rapid_out,
    CycleKind.BACK_BORE: _back_bore,
    CycleKind.BORE_MANUAL: _manual,
}
SEQUENCES.update(linuxcnc_cycles.SEQUENCES)  # the LinuxCNC kinds (their own module's table)
SEQUENCES.update(series8_cycles.SEQUENCES)  # the SERIES 8 kinds
