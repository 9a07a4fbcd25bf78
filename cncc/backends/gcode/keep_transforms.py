"""Which G68 rotations, G51.1 mirrors and G51 scalings a translation keeps as codes.

Consumes the front end's IR commands (frames still carry their rotation and mirror
records); produces the set of :class:`~cncc.ir.frame.Rotation`,
:class:`~cncc.ir.frame.Mirror` and :class:`~cncc.ir.frame.Scaling` records the target
runs itself.  The driver tells the ``rotation``, ``mirror`` and ``scaling`` passes to
leave those records alone, and the emitter writes ``G68 X Y R`` / ``G51.1 X Y`` (SZGH
``G11``) / ``G51 X Y Z P`` or ``I J K`` (SZGH ``G36 X Y Z R``) when a command's frame
gains one and ``G69`` / ``G50.1`` (``G12``) / ``G50`` (``G37``) when it loses it, with
the positions untransformed.  :func:`scale_words` is the one place that says how a
scaling is written, for the decision and the emitter alike.

A record is kept only when the target moves exactly as cncc's pass would:

* the target has the on and off codes (``rotate_on``/``rotate_off``,
  ``mirror_on``/``mirror_off``, ``scale_on``/``scale_off``; every front end reads the
  mirror codes alike: the named axes replace the mirror in force; the scaling codes
  are swapped when the target's ``g50_is_cancel`` is false);
* for a scaling, factors the target's words say exactly (``P`` uniform, ``I J K`` per
  axis, SZGH ``R`` on the named axes: one factor, the other axes unscaled; ``R`` read
  as a divisor under ``scale_r_semantics = "divide"``), no arc whose plane axes are
  scaled differently and no canned cycle under it;
* every command carrying the record: no cutter compensation, polar mode and no other
  of the three transforms; for a rotation its plane selected; no G53 or
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

from cncc.backends.gcode.numbers import fixed
from cncc.backends.gcode.target import Target
from cncc.ir import Arc, Command, CompSide, Cycle, Frame, Linear, Rapid, Units
from cncc.ir.frame import Mirror, Rotation, Scaling

StepMm = Callable[[Units], float]  # output resolution in mm for a frame's units
COMP_AFTER = 3  # motions after a transform whose compensation would see its coordinates
SCALE_DECIMALS = 6  # G51 P / I J K, G36 R: always with a point (no scale_factor_unit)
Record = Rotation | Mirror | Scaling


def _record(f: Frame, kind: type) -> Record | None:
    return f.rotation if kind is Rotation else f.mirror if kind is Mirror else f.scaling


def _frame_ok(f: Frame, r: Record) -> bool:
    if f.comp_side is not CompSide.OFF or f.polar is not None or f.machine_coords:
        return False
    others = [x for x in (f.rotation, f.mirror, f.scaling) if x is not None and x is not r]
    return not others and (not isinstance(r, Rotation) or f.plane is r.plane)


def _centre(r: Record, target: Target) -> tuple[float, ...]:
    if isinstance(r, Rotation):
        return r.center_mm
    if isinstance(r, Scaling):
        words = scale_words(target, r)
        return tuple(r.center_mm[k] for k in words[0]) if words else ()
    return tuple(c for c, on in zip(r.center_mm, r.axes, strict=True) if on)


def _swapped(target: Target) -> bool:
    names = {target.code("scale_on"), target.code("scale_off")}
    return target.option("g50_is_cancel", True) is False and names == {"G50", "G51"}


def scale_codes(target: Target) -> tuple[str, str]:
    """The target's scaling on and off codes (G51/G50 swapped when ``g50_is_cancel`` is false)."""
    on, off = target.code("scale_on"), target.code("scale_off")
    return (off, on) if _swapped(target) else (on, off)


def _factor_text(f: float) -> str | None:
    text = fixed(f, SCALE_DECIMALS)
    return text if float(text) == f else None


def scale_words(target: Target, s: Scaling) -> tuple[tuple[int, ...], list[str]] | None:
    """The axes whose centre the on code names and its factor words; None: not writable exactly."""
    cdef = target.by_op.get("scale_off" if _swapped(target) else "scale_on")  # the words its table lets it read
    kinds = cdef.words if cdef is not None else {}
    scaled = tuple(k for k in range(3) if s.factors[k] != 1.0)
    uniform = len(set(s.factors)) == 1
    if "P" in kinds and uniform:
        text = _factor_text(s.factors[0])
        return ((0, 1, 2) if scaled else (), [f"P{text}"]) if text else None
    if all(a in kinds for a in "IJK"):
        texts = [_factor_text(f) for f in s.factors]
        return (scaled, [f"{a}{t}" for a, t in zip("IJK", texts, strict=True)]) if all(texts) else None
    if "R" in kinds and len({s.factors[k] for k in scaled}) <= 1:
        f = s.factors[scaled[0]] if scaled else 1.0
        divide = target.option("scale_r_semantics", "multiply") == "divide"
        text = fixed(1.0 / f, SCALE_DECIMALS) if divide else _factor_text(f)
        if text is None or (divide and 1.0 / float(text) != f):
            return None
        return (scaled if len(scaled) < 3 else (0, 1, 2), [f"R{text}"])
    return None


def _written_exactly(value_mm: float, step_mm: float) -> bool:
    counts = value_mm / step_mm
    return abs(counts - round(counts)) * step_mm < 1e-9


def _state(f: Frame) -> tuple[object, ...]:
    return (f.total_offset_mm, f.tool_length_mm, f.tool_length_axis, f.units)


def kept_transforms(cmds: Sequence[Command], target: Target, step_mm: StepMm) -> frozenset[Record]:
    """The rotation, mirror and scaling records the target can run itself for this program."""
    motions = [c for c in cmds if isinstance(c, Rapid | Linear | Arc | Cycle)]
    kept: set[Record] = set()
    for kind, on, off in ((Rotation, "rotate_on", "rotate_off"), (Mirror, "mirror_on", "mirror_off"),
                          (Scaling, "scale_on", "scale_off")):
        if target.has(on) and target.has(off):
            kept |= _kept(cmds, motions, kind, step_mm, target)
    kept = {r for r in kept if not (isinstance(r, Rotation) and r.work)}  # G10 L2 R: cncc turns the moves
    for k in range(1, len(motions)):  # an increment mapped by cncc starts where a kept transform left
        f, before = motions[k].frame, motions[k - 1].frame
        if f.incremental and any(r is not None and r not in kept for r in (f.rotation, f.mirror, f.scaling)):
            kept.difference_update((before.rotation, before.mirror, before.scaling))
    kept.difference_update(_moved_while_held(motions))
    kept.difference_update(_scaled_before_named(cmds, target))
    return frozenset(kept)


def _scaled_before_named(cmds: Sequence[Command], target: Target) -> set[Record]:
    """Scalings the target writes with R (SZGH G36: only the axes it names are scaled) that come before
    an axis they scale has had a position (``Frame.held_axes`` since the start).

    Such a centre needs a number for that axis, which would assume where the machine started (and
    move an axis the program never moves); leaving it out would leave the axis unscaled.  So cncc
    applies the scaling itself.  (A scaling written with P or I/J/K leaves the centre out instead:
    the emitter's ``_scaling_block``.)"""
    out: set[Record] = set()
    named = [False] * 6
    for c in cmds:
        r = c.frame.scaling
        if r is not None and r not in out:
            words = scale_words(target, r)
            if words is not None and words[1][0].startswith("R") and not all(named[k] for k in words[0]):
                out.add(r)
        if isinstance(c, Rapid | Linear | Arc | Cycle):
            named = [n or not h for n, h in zip(named, c.frame.held_axes, strict=True)]
    return out


def _moved_while_held(motions: Sequence[Command]) -> set[Record]:
    """Records whose cancel is followed by a move of a held axis (``Frame.held_axes``).

    Such a move goes from where the transform left the tool by the programmed increment;
    the emitter writes untransformed absolute coordinates, which would say otherwise, so
    cncc applies the transform itself and the output carries machine-true positions.
    """
    out: set[Record] = set()
    last: tuple[Record, ...] = ()
    for m in motions:
        f = m.frame
        records = tuple(r for r in (f.rotation, f.mirror, f.scaling) if r is not None)
        if records:
            last = records
            continue
        if True not in f.held_axes:
            continue
        if isinstance(m, Cycle) or (isinstance(m, Rapid | Linear | Arc) and any(
                f.held_axes[k] and abs(m.end[k] - m.start[k]) > 1e-12 for k in range(6))):
            out.update(last)
    return out


def _scaling_bad(c: Command, r: Record, target: Target) -> bool:
    if not isinstance(r, Scaling):
        return False
    if isinstance(c, Cycle) or scale_words(target, r) is None:
        return True
    if isinstance(c, Arc):
        return r.factors[c.plane.first] != r.factors[c.plane.second]
    return False


def _kept(cmds: Sequence[Command], motions: Sequence[Command], kind: type, step_mm: StepMm,
          target: Target) -> set[Record]:
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
                or not all(_written_exactly(v, step) for v in _centre(r, target)) or _scaling_bad(c, r, target)
                or (isinstance(c, Rapid | Linear | Arc) and c.origin.in_machine_terms)):
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
