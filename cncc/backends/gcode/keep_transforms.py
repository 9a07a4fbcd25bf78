"""Which G68 rotations a translation keeps as codes (G68/G69) instead of applying them.

Consumes the front end's IR commands (frames still carry their rotation records);
produces the set of :class:`~cncc.ir.frame.Rotation` records the target runs itself.
The driver tells the ``rotation`` pass to leave those records alone, and the emitter
writes ``G68 X Y R`` when a command's frame gains one and ``G69`` when it loses it,
with the positions untransformed.

A record is kept only when the target moves exactly as cncc's pass would:

* the target has ``rotate_on`` and ``rotate_off`` codes;
* every command carrying the record: no cutter compensation, polar mode, scaling or
  mirror; the record's plane selected; no G53 or reference-return legs (they bypass
  the rotation in the source but are written as ordinary moves); absolute distances
  (in G91 the pass turns the increment about the actual start, which the G90 output
  cannot say); the same offsets, tool length and units throughout (a fold that
  changes under the rotation would move its centre);
* no cutter compensation on the motion before the rotation nor on the few after it
  (compensation is computed by cncc on the coordinates it sees);
* a centre the output writes exactly at its resolution;
* no rotation applied by cncc right after it whose first move is incremental (cncc
  turns that increment from where the kept rotation really left the tool, which the
  untransformed coordinates do not say).

The decision is by record value: a value is kept only if every run of it qualifies.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from cncc.backends.gcode.target import Target
from cncc.ir import Arc, Command, CompSide, Cycle, Frame, Linear, Rapid, Units
from cncc.ir.frame import Rotation

StepMm = Callable[[Units], float]  # output resolution in mm for a frame's units
COMP_AFTER = 3  # motions after a rotation whose compensation would see its coordinates


def _frame_ok(f: Frame, r: Rotation) -> bool:
    return (f.comp_side is CompSide.OFF and f.polar is None and f.scaling is None and f.mirror is None
            and f.plane is r.plane and not f.machine_coords)


def _written_exactly(value_mm: float, step_mm: float) -> bool:
    counts = value_mm / step_mm
    return abs(counts - round(counts)) * step_mm < 1e-9


def _state(f: Frame) -> tuple[object, ...]:
    return (f.total_offset_mm, f.tool_length_mm, f.tool_length_axis, f.units)


def kept_rotations(cmds: Sequence[Command], target: Target, step_mm: StepMm) -> frozenset[Rotation]:
    """The rotation records the target can run itself for this program."""
    if not (target.has("rotate_on") and target.has("rotate_off")):
        return frozenset()
    bad: set[Rotation] = set()
    seen: dict[Rotation, tuple[object, ...]] = {}
    motions = [c for c in cmds if isinstance(c, Rapid | Linear | Arc | Cycle)]
    for c in cmds:
        r = c.frame.rotation
        if r is None:
            continue
        state = _state(c.frame)
        first = seen.setdefault(r, state)
        step = step_mm(c.frame.units)
        motion = isinstance(c, Rapid | Linear | Arc | Cycle)
        if (first != state or not _frame_ok(c.frame, r) or (motion and c.frame.incremental)
                or not all(_written_exactly(v, step) for v in r.center_mm)
                or (isinstance(c, Rapid | Linear | Arc) and (c.origin == "G53" or c.origin.endswith(" ref")))):
            bad.add(r)
    for k, m in enumerate(motions):  # compensation next to a rotation
        r = m.frame.rotation
        prev = motions[k - 1].frame.rotation if k else None
        if r == prev:
            continue
        window = motions[max(k - 1, 0):k + COMP_AFTER]
        if any(w.frame.comp_side is not CompSide.OFF for w in window):
            bad.update(x for x in (r, prev) if x is not None)
    kept = {r for r in seen if r not in bad}
    for k in range(1, len(motions)):  # an increment turned by cncc starts where a kept rotation left
        r, prev = motions[k].frame.rotation, motions[k - 1].frame.rotation
        if r is not None and r not in kept and motions[k].frame.incremental and prev in kept:
            kept.discard(prev)
    return frozenset(kept)
