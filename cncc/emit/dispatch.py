"""``--emit=KIND`` to its backend: :func:`run_backend` looks the kind up in :data:`BACKENDS`.

Every backend takes one :class:`BackendCall` (the path stage's items of one input file and what
they were compiled with) and returns the output text piece by piece.  The items are read once,
lazily: as they come (batches of moves, for the backends that take them) or as commands
(:func:`cncc.ir.batch.expand`).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink
from cncc.dialects import Dialect
from cncc.ir import Command, Frame, Units
from cncc.ir.batch import Item
from cncc.ir.machine import MachineModel
from cncc.options import Options
from cncc.source import NO_SPAN, SourceFile, SourceMap

if TYPE_CHECKING:
    from cncc.pipeline.manager import PassManager

MACHINE_EMITS = ("timing", "pulses")  # backends that read machine coordinates


@dataclass(frozen=True, slots=True)
class BackendCall:
    """One backend run: ``items`` (the path stage's output for ``src``) and ``cmds``, the same
    stream as commands (lazy: a backend reads one of the two)."""

    items: Iterator[Item]
    cmds: Iterator[Command]
    src: SourceFile
    sources: SourceMap
    dialect: Dialect
    machine: MachineModel
    opts: Options
    sink: DiagnosticSink
    keep_runs: list[Any] | None
    manager: PassManager | None


def _canon(c: BackendCall) -> Iterator[str]:
    from cncc.backends.canon import emit_canon

    frame0 = Frame(units=Units.INCH if c.dialect.default_units == "inch" else Units.MM)
    return emit_canon(c.items, frame0, c.dialect.raw.get("canon"))


def _ir(c: BackendCall) -> Iterator[str]:
    from cncc.backends.irdump import dump_ir

    return dump_ir(c.cmds, c.sources)


def _gcode(c: BackendCall) -> Iterator[str]:
    from cncc.emit.gcode import gcode_backend

    return gcode_backend(c.items, c.cmds, c.src, c.sources, c.dialect, c.machine, c.opts, c.sink, c.manager)


def _timing(c: BackendCall) -> Iterator[str]:
    from cncc.emit.timing import timing_backend

    return timing_backend(c.items, c.cmds, c.src, c.sources, c.dialect, c.machine, c.opts, c.sink,
                          keep_runs=c.keep_runs, manager=c.manager)


def _pulses(c: BackendCall) -> Iterator[str]:
    from cncc.emit.pulses import pulse_backend

    return pulse_backend(c.cmds, c.machine, c.opts, c.sink, c.manager)


def _none(c: BackendCall) -> Iterator[str]:
    for _ in c.items:
        pass
    return iter(())


BACKENDS: dict[str, Callable[[BackendCall], Iterator[str]]] = {
    "canon": _canon, "ir": _ir, "gcode": _gcode, "timing": _timing, "pulses": _pulses, "none": _none,
}
EMIT_KINDS = tuple(BACKENDS)  # ("canon", "ir", "gcode", "timing", "pulses", "none"): the --emit choices


def run_backend(items: Iterator[Item], src: SourceFile, sources: SourceMap, dialect: Dialect,
                machine: MachineModel, opts: Options, sink: DiagnosticSink,
                keep_runs: list[Any] | None = None, manager: PassManager | None = None) -> Iterator[str]:
    """The output of ``--emit=opts.emit`` for the path stage's ``items`` of ``src`` (an unknown kind:
    E0204, the items drained)."""
    from cncc.ir.batch import expand as expand_batches

    call = BackendCall(items, expand_batches(items), src, sources, dialect, machine, opts, sink, keep_runs, manager)
    backend = BACKENDS.get(opts.emit)
    if backend is None:
        sink.emit(dg.NOT_SUPPORTED, NO_SPAN, f"--emit={opts.emit} is not available yet")
        for _ in call.cmds:
            pass
        return iter(())
    return backend(call)
