"""Timing reports (``--emit=timing``): where the cycle time goes.

Consumes the IR commands the planner saw and one :class:`Run` (a planned
:class:`~cncc.ir.trajectory.Trajectory` for a machine and level) per column; the
driver plans them (this package never imports the planner).  Produces a terminal
table (:mod:`.text`), JSON with a schema (:mod:`.jsonout`, ``schema.json``), an
offline HTML page with SVG plots (:mod:`.html`), or the program annotated with the
elapsed time of each block (:mod:`.annotate`).

Times add up exactly: see :mod:`.model`.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Sequence
from typing import Any

from cncc import diagnostics as dg
from cncc.backends.timing.columns import ColumnSpec, default_columns, parse_compare
from cncc.backends.timing.model import Run, TimingReport
from cncc.diagnostics import DiagnosticSink
from cncc.dialects import Dialect
from cncc.ir import Command
from cncc.ir.batch import Item
from cncc.ir.machine import MachineModel
from cncc.source import NO_SPAN, SourceFile, SourceMap

__all__ = ["FORMATS", "ColumnSpec", "Run", "TimingReport", "annotated_commands", "default_columns", "event_pauses",
           "parse_compare", "streamable", "streamed_timing_report", "timing_report"]

FORMATS = ("text", "json", "html")


def timing_report(cmds: Sequence[Command], runs: Sequence[Run], src: SourceFile, sources: SourceMap,
                  dialect: Dialect, fmt: str, sink: DiagnosticSink, *, annotate: bool = False,
                  color: bool = False, top_n: int = 10, width: int | None = None) -> Iterator[str]:
    """Render the report of ``runs`` (the first is the primary column) in ``fmt``.

    With ``annotate`` the output is instead the program ``src`` with each block's
    elapsed time (primary column) as a comment in the dialect's comment syntax.
    """
    from cncc.backends.timing.aggregate import build_report

    if fmt not in FORMATS:
        sink.emit(dg.BAD_OPTION, NO_SPAN, f"unknown --report-format={fmt} (choose from {', '.join(FORMATS)})")
        return iter(())
    if not runs:
        return iter(())
    rep = build_report(cmds, runs, sources, src.name, dialect.name, top_n, sink)
    if annotate:
        from cncc.backends.timing.annotate import annotate_time

        return iter((annotate_time(rep, src, dialect),))
    if fmt == "json":
        from cncc.backends.timing.jsonout import iter_json

        return iter_json(rep)
    if fmt == "html":
        from cncc.backends.timing.html import render_html

        return iter((render_html(rep, cmds),))
    from cncc.backends.timing.text import render_text

    return iter((render_text(rep, color, width),))


def streamable(opts: Any, machine: MachineModel) -> bool:
    """True when the report of ``opts`` (a :class:`cncc.driver.Options`) can be made while the
    commands stream (:mod:`.streamed`): one nominal -O0 column on ``machine`` without reversal
    pauses, as text or JSON, with the default plan stage and no pass instruments, and no caller
    that keeps the trajectory (``keep_trajectory``: cncc.api)."""
    return (opts.opt_level == 0 and not opts.compare and not opts.annotate_time and not opts.keep_trajectory
            and opts.report_format in ("text", "json") and not opts.passes and not opts.verify_each
            and not opts.print_after and not opts.time_passes
            and not any(a.step.reversal_delay_s > 0 for a in machine.axes))


def streamed_timing_report(items: Iterable[Item], machine: MachineModel, src: SourceFile, sources: SourceMap,
                           dialect: Dialect, fmt: str, sink: DiagnosticSink, *, color: bool = False,
                           width: int | None = None) -> Iterator[str]:
    """:func:`timing_report` of the -O0 column, made from ``items`` as they stream (:func:`streamable`)."""
    from cncc.backends.timing.streamed import streamed_report

    rep = streamed_report(items, machine, sources, src.name, dialect.name, sink=sink)
    if fmt == "json":
        from cncc.backends.timing.jsonout import iter_json

        return iter_json(rep)
    from cncc.backends.timing.text import render_text

    return iter((render_text(rep, color, width),))


def event_pauses(cmds: Sequence[Command], cmd_index: object, machine: MachineModel) -> list[tuple[int, int]]:
    """``(command index, ns)`` of the timed events (dwells, tool changes, spindle ramps, stops, waits)
    a report column over a trajectory with ``cmd_index`` counts: the pauses of the pulse time line."""
    from cncc.backends.timing.aggregate import event_pauses as pauses

    return pauses(cmds, cmd_index, machine)


def annotated_commands(cmds: Sequence[Command], runs: Sequence[Run], sources: SourceMap, file: str,
                       dialect: Dialect) -> Iterator[Command]:
    """``-E --annotate-time``: ``cmds`` with a comment giving the elapsed time after each executed block."""
    from cncc.backends.timing.aggregate import build_report
    from cncc.backends.timing.annotate import annotate_commands

    if not runs:
        return iter(cmds)
    return annotate_commands(cmds, build_report(cmds, runs[:1], sources, file, dialect.name))
