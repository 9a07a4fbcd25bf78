"""Which G68 rotations and G51.1 mirrors a translation keeps as codes instead of applying them.

Consumes the front end's IR commands (frames still carry their rotation and mirror
records); produces the set of :class:`~cncc.ir.frame.Rotation` and
:class:`~cncc.ir.frame.Mirror` records the target runs itself.  The driver tells the
``rotation`` and ``mirror`` passes to leave those records alone, and the emitter
writes ``G68 X Y R`` / ``G51.1 X Y`` (SZGH ``G11``) when a command's frame gains one
and ``G69`` / ``G50.1`` (``G12``) when it loses it, with the positions untransformed.

A record is kept only when the target moves exactly as cncc's pass would:

* the target has the on and off codes (``rotate_on``/``rotate_off``,
  ``mirror_on``/``mirror_off``; every front end reads the mirror codes alike: the
  named axes replace the mirror in force);
* every command carrying the record: no cutter compensation, polar mode, scaling and
  no other of the two transforms; for a rotation its plane selected; no G53 or
  reference-return legs (they bypass the transform in the source but are written as
  ordinary moves); absolute distances (in G91 the pass maps the increment from the
  actual start, which the G90 output cannot say); the same offsets, tool length and
  units throughout (a fold that changes under the transform would move its centre);
* no cutter compensation on the motion before it nor on the few after it
  (compensation is computed by cncc on the coordinates it sees);
* a centre the output writes exactly at its resolution;
* no transform applied by cncc right after it whose first move is incremental (cncc
  maps that increment from where the kept transform really left the tool, which the
  untransformed coordinates do not say).

The decision is by record value: a value is kept only if every run of it qualifies.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from cncc.backends.gcode.target import Target
from cncc.ir import Arc, Command, CompSide, Cycle, Frame, Linear, Rapid, Units
from cncc.ir.frame import Mirror, Rotation

StepMm = Callable[[Units], float]  # output resolution in mm for a frame's units
COMP_AFTER = 3  # motions after a transform whose compensation would see its coordinates
Record = Rotation | Mirror


def _record(f: Frame, kind: type) -> Record | None:
    return f.rotation if kind is Rotation else f.mirror


def _frame_ok(f: Frame, r: Record) -> bool:
    if f.comp_side is not CompSide.OFF or f.polar is not None or f.scaling is not None or f.machine_coords:
        return False
    if isinstance(r, Rotation):
        return f.mirror is None and f.plane is r.plane
    return f.rotation is None


def _centre(r: Record) -> tuple[float, ...]:
    if isinstance(r, Rotation):
        return r.center_mm
    return tuple(c for c, on in zip(r.center_mm, r.axes, strict=True) if on)


def _written_exactly(value_mm: float, step_mm: float) -> bool:
    counts = value_mm / step_mm
    return abs(counts - round(counts)) * step_mm < 1e-9


def _state(f: Frame) -> tuple[object, ...]:
    return (f.total_offset_mm, f.tool_length_mm, f.tool_length_axis, f.units)


def kept_transforms(cmds: Sequence[Command], target: Target, step_mm: StepMm) -> frozenset[Record]:
    """The rotation and mirror records the target can run itself for this program."""
    motions = [c for c in cmds if isinstance(c, Rapid | Linear | Arc | Cycle)]
    kept: set[Record] = set()
    for kind, on, off in ((Rotation, "rotate_on", "rotate_off"), (Mirror, "mirror_on", "mirror_off")):
        if target.has(on) and target.has(off):
            kept |= _kept(cmds, motions, kind, step_mm)
    for k in range(1, len(motions)):  # an increment mapped by cncc starts where a kept transform left
        f, before = motions[k].frame, motions[k - 1].frame
        if f.incremental and any(r is not None and r not in kept for r in (f.rotation, f.mirror)):
            kept.difference_update((before.rotation, before.mirror))
    return frozenset(kept)


def _kept(cmds: Sequence[Command], motions: Sequence[Command], kind: type, step_mm: StepMm) -> set[Record]:
    bad: set[Record] = set()
    seen: dict[Record, tuple[object, ...]] = {}
    for c in cmds:
        r = _record(c.frame, kind)
        if r is None:
            continue
        state = _state(c.frame)
        first = seen.setdefault(r, state)
        step = step_mm(c.frame.units)
        motion = isinstance(c, Rapid | Linear | Arc | Cycle)
        if (first != state or not _frame_ok(c.frame, r) or (motion and c.frame.incremental)
                or not all(_written_exactly(v, step) for v in _centre(r))
                or (isinstance(c, Rapid | Linear | Arc) and (c.origin == "G53" or c.origin.endswith(" ref")))):
            bad.add(r)
    for k, m in enumerate(motions):  # compensation next to a transform
        r = _record(m.frame, kind)
        prev = _record(motions[k - 1].frame, kind) if k else None
        if r == prev:
            continue
        window = motions[max(k - 1, 0):k + COMP_AFTER]
        if any(w.frame.comp_side is not CompSide.OFF for w in window):
            bad.update(x for x in (r, prev) if x is not None)
    return {r for r in seen if r not in bad}
