"""``--emit=timing``: the cycle-time report (:mod:`cncc.backends.timing`) from machine-coordinate commands.

:func:`timing_backend` streams the ``-O0`` report from the batches when it can
(:func:`cncc.backends.timing.streamable`), else lists the commands and plans one :class:`Run` per
report column (:func:`timing_runs`: ``--compare``, else ``-O<level>`` beside the nominal estimate).
:func:`reversal_events` gives each run the reversal pauses ``--emit=pulses`` would insert.
"""

from __future__ import annotations

import shutil
import sys
from collections.abc import Iterator
from typing import TYPE_CHECKING, Any

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink
from cncc.dialects import Dialect
from cncc.emit.plan import plan_trajectory
from cncc.ir import Command
from cncc.ir.batch import Item
from cncc.ir.machine import MachineModel
from cncc.options import Options
from cncc.resolve import resolve_machine
from cncc.source import NO_SPAN, SourceFile, SourceMap

if TYPE_CHECKING:
    from cncc.pipeline.manager import PassManager


def timing_backend(items: Iterator[Item], cmds: Iterator[Command], src: SourceFile, sources: SourceMap,
                   dialect: Dialect, machine: MachineModel, opts: Options, sink: DiagnosticSink,
                   keep_runs: list[Any] | None = None, manager: PassManager | None = None) -> Iterator[str]:
    """The report of ``src`` (text, JSON or HTML: ``opts.report_format``); ``items`` and ``cmds`` are the
    same stream (batches of moves, and commands), only one of them is read.  The planned runs are
    added to ``keep_runs`` when given (:mod:`cncc.api` reads them)."""
    from cncc.backends.timing import streamable, streamed_timing_report, timing_report
    from cncc.backends.timing.progress import track_source

    color = opts.output in (None, "-") and sys.stdout.isatty()
    width = shutil.get_terminal_size().columns if color else None  # the text report fits the terminal
    if streamable(opts, machine):  # -O0 from the batches, without a command list (timing/streamed.py)
        return streamed_timing_report(track_source(items, len(src.text), src.source_id), machine, src, sources,
                                      dialect, opts.report_format, sink, color=color, width=width)
    cmd_list = list(track_source(cmds, len(src.text), src.source_id))
    runs = timing_runs(cmd_list, machine, opts, sink, manager)
    if keep_runs is not None:
        keep_runs.extend(runs)
    return timing_report(cmd_list, runs, src, sources, dialect, opts.report_format, sink,
                         annotate=opts.annotate_time, color=color, width=width)


def timing_runs(cmds: list[Command], machine: MachineModel, opts: Options, sink: DiagnosticSink,
                manager: PassManager | None = None) -> list[Any]:
    """One planned Run per report column (``--compare``, else -O<level> and the nominal estimate)."""
    from cncc.backends.timing import Run, default_columns, parse_compare

    specs = parse_compare(opts.compare, opts.opt_level) if opts.compare else default_columns(opts.opt_level)
    if isinstance(specs, str):
        sink.emit(dg.BAD_OPTION, NO_SPAN, specs)
        return []
    runs = []
    for spec in specs:
        model = machine if spec.machine is None else resolve_machine(spec.machine, sink)
        if model is None:
            return []
        traj, how = plan_trajectory(cmds, model, spec.level, sink, verify=opts.verify,
                                    soft_limits=opts.offsets_file is not None, quiet=opts.quiet, manager=manager,
                                    spec=opts.passes)
        runs.append(Run(spec.label, model, spec.level, traj, how, nominal=spec.level == 0,
                        reversals=reversal_events(traj, model, opts)))
    return runs


def reversal_events(traj: Any, machine: MachineModel, opts: Options) -> tuple[tuple[int, int, str], ...]:
    """(command, ns, what) of the reversal pauses --emit=pulses inserts for ``traj`` on ``machine``."""
    if not any(a.step.reversal_delay_s > 0 for a in machine.axes):
        return ()
    from cncc.backends.pulses import MODES, reversal_pauses

    mode = opts.pulse_mode if opts.pulse_mode in MODES else "exact"
    return tuple(reversal_pauses(traj, machine, mode=mode).by_command(traj.cmd_index))
