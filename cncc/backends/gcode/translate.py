"""Before the passes: what a translation keeps for the target, and the notes that say so.

Consumes the front end's IR commands (frames still carry polar, scaling, mirror,
rotation and compensation records; cycles are whole); produces the same stream, with

* the canned cycles the target cannot run exactly as the source did expanded
  (``expand`` is injected by the driver: a backend does not import passes), with a
  note N0806 naming the reason; hole patterns noted (N0807) — they are always
  written as their list of holes;
* a note for every programmable transform cncc applies itself (N0801-N0805): the
  output carries the transformed coordinates.  Rotations, mirrors and scalings the target runs itself
  (:mod:`cncc.backends.gcode.keep_transforms`) get no note.

Under ``-Werror`` the notes are errors: the target does not do what the source asked
it to, cncc did.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator

from cncc import diagnostics as dg
from cncc.backends.gcode.cycles import keep_problem
from cncc.backends.gcode.target import Target
from cncc.diagnostics import DiagnosticSink, Severity
from cncc.ir import Command, CompSide, Cycle, CycleKind
from cncc.ir.batch import Item

Expand = Callable[[Cycle], Iterable[Command]]

_TRANSFORMS = (
    ("rotation", dg.XL_ROTATION, "coordinate rotation is applied by cncc: the output has rotated coordinates"),
    ("scaling", dg.XL_SCALING, "scaling is applied by cncc: the output has scaled coordinates"),
    ("mirror", dg.XL_MIRROR, "the mirror is applied by cncc: the output has mirrored coordinates"),
    ("polar", dg.XL_POLAR, "polar coordinates are converted by cncc: the output has Cartesian coordinates"),
)


def note(sink: DiagnosticSink, code: str, span: object, message: str) -> None:
    """Emit a translation note; -Werror makes it an error."""
    severity = Severity.ERROR if sink.werror and dg.CODES[code].severity is Severity.NOTE else None
    sink.emit(code, span, message, severity=severity)  # type: ignore[arg-type]


def kept_cycle_kinds(target: Target) -> frozenset[str]:
    """Cycle kinds the target has codes for (each cycle is still checked by :func:`keep_problem`)."""
    return frozenset(target.cycles)


def prepare(cmds: Iterable[Item], target: Target, expand: Expand, sink: DiagnosticSink,
            kept: frozenset[object] = frozenset()) -> Iterator[Item]:
    """Expand the cycles the target cannot keep and note the transforms cncc applies (batches of
    moves, :mod:`cncc.ir.batch`, pass through: they hold no cycles).

    ``kept``: the rotation, mirror and scaling records the target runs itself (no N0801-N0803).
    """
    seen: set[str] = set()
    for c in cmds:
        f = c.frame
        for attr, code, message in _TRANSFORMS:
            if attr in ("rotation", "mirror", "scaling") and getattr(f, attr) in kept:
                continue
            if getattr(f, attr) is not None and code not in seen:
                seen.add(code)
                note(sink, code, c.span, f"{target.name} output: {message}")
        if f.comp_side is not CompSide.OFF and dg.XL_COMP not in seen:
            seen.add(dg.XL_COMP)
            note(sink, dg.XL_COMP, c.span, f"{target.name} output: cutter compensation is applied by cncc; "
                                           "the output is the tool-centre path for this tool radius")
        if isinstance(c, Cycle):
            yield from _cycle(c, target, expand, sink, seen)
        else:
            yield c


def _cycle(c: Cycle, target: Target, expand: Expand, sink: DiagnosticSink, seen: set[str]) -> Iterable[Command]:
    problem = keep_problem(c, target)
    if not problem:  # a kept pattern the target cannot write as one gets N0807 from the emitter
        return (c,)
    key = f"{dg.XL_CYCLE_EXPANDED}:{c.kind.value}"
    if key not in seen:
        seen.add(key)
        note(sink, dg.XL_CYCLE_EXPANDED, c.span, f"{c.code} is written as moves: {problem}")
        if c.kind in (CycleKind.TAP, CycleKind.TAP_LEFT):
            sink.emit(dg.XL_TAP_UNSYNCED, c.span, f"{c.code} becomes feed moves and spindle reversals; "
                                                  f"{target.name} does not synchronise them with the spindle")
    return expand(c)
