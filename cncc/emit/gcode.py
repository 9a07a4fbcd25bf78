"""``--emit=gcode``: translation to the ``-t`` dialect (:mod:`cncc.backends.gcode`, docs/translation.md).

* :func:`output_dialect` -- the dialect written: ``-t`` with its ``--target-option``s, else the input's.
* :func:`translation_prepare` -- before the path passes: the cycles the target cannot keep are
  expanded, and the rotation, mirror and scaling records the target runs itself are chosen (the
  path passes then leave those alone).
* :func:`gcode_backend` -- the emitter over the path stage's items (``-E --annotate-time``: over the
  commands, with the planned times as comments).
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from typing import TYPE_CHECKING, Any

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink
from cncc.dialects import Dialect, DialectError
from cncc.ir import Command, Units
from cncc.ir.batch import Item
from cncc.ir.machine import MachineModel
from cncc.options import Options
from cncc.resolve import resolve_dialect
from cncc.source import NO_SPAN, SourceFile, SourceMap

if TYPE_CHECKING:
    from cncc.pipeline.manager import PassManager

TRANSFORM_CODES = (("rotate_on", "rotate_off"), ("mirror_on", "mirror_off"), ("scale_on", "scale_off"))


def gcode_backend(items: Iterator[Item], cmds: Iterator[Command], src: SourceFile, sources: SourceMap,
                  dialect: Dialect, machine: MachineModel, opts: Options, sink: DiagnosticSink,
                  manager: PassManager | None = None) -> Iterator[str]:
    """The translated program's text; ``items`` and ``cmds`` are the same stream (batches of moves, and
    commands), only one of them is read."""
    from cncc.backends.gcode import EmitOptions, emit_gcode
    from cncc.passes.expand_cycles import expand

    target = output_dialect(dialect, opts, sink)
    if target is None:
        return iter(())
    eopts = EmitOptions(decimals_mm=opts.decimals_mm, decimals_inch=opts.decimals_inch,
                        line_numbers=opts.line_numbers, units=opts.units,
                        same_dialect=target.name == dialect.name, expand_cycle=expand,
                        keep_subprograms=opts.keep_subprograms and not opts.expand, from_program_start=True)
    if opts.expand and opts.annotate_time:  # -E --annotate-time
        from cncc.backends.timing import annotated_commands
        from cncc.emit.timing import timing_runs

        cmd_list = list(cmds)
        runs = timing_runs(cmd_list, machine, opts, sink, manager)
        return emit_gcode(iter(annotated_commands(cmd_list, runs, sources, src.name, dialect)), target, eopts, sink)
    return emit_gcode(items, target, eopts, sink)


def output_dialect(dialect: Dialect, opts: Options, sink: DiagnosticSink) -> Dialect | None:
    """The dialect --emit=gcode writes: -t, else the input dialect."""
    if not opts.target or opts.target == dialect.name:
        if not opts.target_options:
            return dialect
        try:
            return dialect.with_options(opts.target_options)
        except DialectError as exc:
            sink.emit(dg.BAD_OPTION, NO_SPAN, str(exc))
            return None
    return resolve_dialect(Options(dialect=opts.target, dialect_options=opts.target_options), sink)


def translation_prepare(cmds: Iterable[Item], dialect: Dialect, opts: Options,
                        sink: DiagnosticSink) -> tuple[Iterable[Item], frozenset[str], frozenset[Any]]:
    """Cycles the target cannot keep expanded now (before the transforms), notes for what cncc applies;
    the kept cycle kinds and the rotation, mirror and scaling records the target runs itself."""
    from cncc.backends.gcode import make_target
    from cncc.backends.gcode.keep_transforms import kept_transforms
    from cncc.backends.gcode.translate import kept_cycle_kinds, prepare
    from cncc.passes.expand_cycles import expand

    target = output_dialect(dialect, opts, sink)
    if target is None:
        return cmds, frozenset(), frozenset()
    tgt = make_target(target)
    if not any(tgt.has(on) and tgt.has(off) for on, off in TRANSFORM_CODES):  # nothing to keep: stream
        return prepare(cmds, tgt, expand, sink, frozenset()), kept_cycle_kinds(tgt), frozenset()
    from cncc.ir.batch import expand as expand_batches

    items = list(cmds)  # the keep decision looks at a whole transform before its first move
    if not any(x.frame.rotation is not None or x.frame.mirror is not None or x.frame.scaling is not None
               for x in items):
        return prepare(items, tgt, expand, sink, frozenset()), kept_cycle_kinds(tgt), frozenset()
    listed = list(expand_batches(items))

    def step_mm(units: Units) -> float:
        unit = Units.INCH if opts.units == "inch" else Units.MM if opts.units == "mm" else units
        default = tgt.decimals_inch if unit is Units.INCH else tgt.decimals_mm
        chosen = opts.decimals_inch if unit is Units.INCH else opts.decimals_mm
        return 10.0 ** -(default if chosen is None else chosen) * unit.mm_per_unit

    kept = kept_transforms(listed, tgt, step_mm)
    return prepare(listed, tgt, expand, sink, kept), kept_cycle_kinds(tgt), kept
