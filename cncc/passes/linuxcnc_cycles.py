"""The hole sequences of LinuxCNC 2.9's G74, G84, G85, G86, G88 and G89, registered into ``expand-cycles``.

As rs274's ``convert_cycle_g8x`` make them (checked against its ``-g`` trace), once the tool
is above the hole at R.  Every move is made even when it has no length (rs274 prints it):

* ``tap_rs274`` (G84; ``tap_left_rs274``, G74, the same counter-clockwise): feed and speed
  overrides off; feed to Z; spindle stop, reverse;
  dwell P (0 without P); feed out to the clear level; spindle stop, forward; overrides on;
* ``bore_feed_out_rs274`` (G85): feed to Z, feed to R, rapid to the clear level;
* ``bore_dwell_stop_rs274`` (G86): feed to Z, dwell P, spindle stop, rapid to the clear
  level, spindle on in its direction;
* ``bore_dwell_feed_out_rs274`` (G89): feed to Z, dwell P, feed out to the clear level;
* ``bore_manual_rs274`` (G88): feed to Z, dwell P, spindle stop, program stop (the
  operator retracts), spindle on; the tool is then taken to be at the clear level.
"""

from __future__ import annotations

from cncc.ir import CycleKind, CycleKindBase, Dwell, Linear, Rapid, SetOverrides, SpindleState, Stop, StopKind, Vec6
from cncc.passes.cycle_path import CyclePath as _Path
from cncc.passes.cycle_path import Sequence

SEQUENCES: dict[CycleKindBase, Sequence] = {}  # this module's kinds (expand_cycles.SEQUENCES merges them)


def _feed(p: _Path, q: Vec6) -> None:
    c = p.c
    p.out.append(Linear(c.span, c.frame, p.pos, q, c.feed_mm_min, p.motion, p.origin))
    p.pos = q


def _rapid(p: _Path, q: Vec6) -> None:
    c = p.c
    p.out.append(Rapid(c.span, c.frame, p.pos, q, p.motion, p.origin))
    p.pos = q


def _dwell(p: _Path) -> None:
    p.out.append(Dwell(p.c.span, p.c.frame, p.c.dwell_s))


def _tap(p: _Path) -> None:
    c = p.c
    p.rapid(p.at(c.r_mm))
    p.out.append(SetOverrides(c.span, c.frame, False))
    _feed(p, p.at(c.bottom_mm))
    p.spindle(SpindleState.OFF)
    p.spindle(p.reverse())
    _dwell(p)
    _feed(p, p.at(c.retract_mm))
    p.spindle(SpindleState.OFF)
    p.spindle(p.forward)
    p.out.append(SetOverrides(c.span, c.frame, True))


def _feed_out(p: _Path) -> None:
    c = p.c
    p.rapid(p.at(c.r_mm))
    _feed(p, p.at(c.bottom_mm))
    _feed(p, p.at(c.r_mm))
    _rapid(p, p.at(c.retract_mm))


def _to_bottom_and_dwell(p: _Path) -> None:
    """Rapid to R, feed to the bottom, dwell there (P, printed even when zero)."""
    c = p.c
    p.rapid(p.at(c.r_mm))
    _feed(p, p.at(c.bottom_mm))
    _dwell(p)


def _dwell_stop(p: _Path) -> None:
    c = p.c
    _to_bottom_and_dwell(p)
    p.spindle(SpindleState.OFF)
    _rapid(p, p.at(c.retract_mm))
    p.spindle(p.forward)


def _dwell_feed_out(p: _Path) -> None:
    c = p.c
    _to_bottom_and_dwell(p)
    _feed(p, p.at(c.retract_mm))


def _manual(p: _Path) -> None:
    c = p.c
    _to_bottom_and_dwell(p)
    p.spindle(SpindleState.OFF)
    p.out.append(Stop(c.span, c.frame, StopKind.PROGRAM_STOP))
    p.spindle(p.forward)
    p.pos = p.at(c.retract_mm)  # rs274 takes the tool to be at the clear level after the operator's retract


SEQUENCES.update({
    CycleKind.TAP_RS274: _tap,
    CycleKind.TAP_LEFT_RS274: _tap,
    CycleKind.BORE_FEED_OUT_RS274: _feed_out,
    CycleKind.BORE_DWELL_STOP_RS274: _dwell_stop,
    CycleKind.BORE_MANUAL_RS274: _manual,
    CycleKind.BORE_DWELL_FEED_OUT_RS274: _dwell_feed_out,
})
