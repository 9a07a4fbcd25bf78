"""``--emit=pulses``: machine-coordinate commands to step/dir pulses.

:func:`pulse_backend` checks the pulse options, plans at ``-O<level>`` (:func:`cncc.emit.plan.plan_trajectory`),
adds the timing report's event pauses and the reversal pauses, and writes the pulses
(:mod:`cncc.backends.pulses`): as text to stdout, or streamed into ``-o FILE``.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink
from cncc.emit.plan import plan_trajectory
from cncc.ir import Command
from cncc.ir.machine import MachineModel
from cncc.options import Options
from cncc.outfile import write_stream
from cncc.source import NO_SPAN

if TYPE_CHECKING:
    from cncc.pipeline.manager import PassManager

PULSE_BINARY_FORMATS = ("npz",)


def writes_own_output(opts: Options) -> bool:
    """True when the backend streams straight into ``opts.output`` (pulses to a file)."""
    return opts.emit == "pulses" and opts.output not in (None, "-")


def pulse_option_problem(opts: Options, formats: tuple[str, ...], modes: tuple[str, ...]) -> str:
    """What is wrong with the --emit=pulses options ('' when nothing)."""
    to_stdout = opts.output in (None, "-")
    if opts.pulse_format not in formats:
        return f"unknown --pulse-format={opts.pulse_format} (choose from {', '.join(formats)})"
    if opts.pulse_mode not in modes:
        return f"unknown --pulse-mode={opts.pulse_mode} (choose from {', '.join(modes)})"
    if opts.pulse_format in PULSE_BINARY_FORMATS and to_stdout:
        return f"--pulse-format={opts.pulse_format} is binary: name the output file with -o FILE"
    if not to_stdout and len(opts.inputs) > 1:
        return "--emit=pulses -o FILE takes one input program"
    return ""


def pulse_backend(cmds: Iterator[Command], machine: MachineModel, opts: Options, sink: DiagnosticSink,
                  manager: PassManager | None = None) -> Iterator[str]:
    """--emit=pulses: plan at -O<level>, then step/dir pulses; text to stdout, or streamed into -o FILE."""
    import io

    from cncc.backends.pulses import FORMATS, MODES, generate_pulses, reversal_pauses, write_pulses
    from cncc.backends.pulses import progress as pulse_progress
    from cncc.backends.timing import event_pauses

    fmt, to_stdout = opts.pulse_format, opts.output in (None, "-")
    problem = pulse_option_problem(opts, FORMATS, MODES)
    cmd_list = list(cmds)
    if problem:
        sink.emit(dg.BAD_OPTION, NO_SPAN, problem)
        return iter(())
    traj, _ = plan_trajectory(cmd_list, machine, opts.opt_level, sink, verify=opts.verify,
                              soft_limits=opts.offsets_file is not None, quiet=opts.quiet, manager=manager,
                              spec=opts.passes)
    pauses = event_pauses(cmd_list, traj.cmd_index, machine)  # the timing report's event times
    reversals = reversal_pauses(traj, machine, mode=opts.pulse_mode)
    chunks = pulse_progress.track(
        generate_pulses(traj, machine, mode=opts.pulse_mode, spans=[c.span for c in cmd_list], sink=sink,
                        pauses=pauses, reversals=reversals),
        round(traj.duration_total_s * 1e9) + sum(ns for _, ns in pauses) + reversals.total_ns,
        pulse_progress.estimated_steps(traj, machine), quiet=opts.quiet)
    if to_stdout:
        buf = io.StringIO()
        write_pulses(chunks, fmt, buf)
        return iter((buf.getvalue(),))
    write_stream(opts.output or "-", opts.inputs, sink, lambda fh: write_pulses(chunks, fmt, fh))
    return iter(())
