"""A progress bar over the pulse stream: percentage of machine time written, and ETA.

:func:`track` yields the chunks of :func:`~cncc.backends.pulses.generate_pulses` unchanged
and, on a terminal, draws a rich bar (rich is imported only then) whose completion is
each chunk's end time over the program's; quiet with ``quiet`` (``-q``), when the stream
is not a terminal, and for programs of fewer than :data:`MIN_STEPS` estimated steps
(about two seconds of work or less).
"""

from __future__ import annotations

import sys
from collections.abc import Iterable, Iterator
from typing import TextIO

import numpy as np

from cncc.backends.pulses.chunk import StepChunk
from cncc.ir.machine import MachineModel
from cncc.ir.trajectory import Trajectory

MIN_STEPS = 4_000_000
"""Below this many estimated steps generating and writing the pulses takes under ~2 s: no bar."""


def estimated_steps(traj: Trajectory, machine: MachineModel) -> int:
    """Steps of the program, from each phase's net travel per axis (a lower bound: a phase that
    turns back counts its net travel only)."""
    if traj.phase_count == 0:
        return 0
    rate = np.array([(a.step.steps_per_mm * a.step.gear_cmr / a.step.gear_cmd) if a is not None else 0.0
                     for a in (machine.axis(n) for n in traj.axes)])
    travel = np.abs(traj.end_positions() - traj.p0_mm)
    return int((travel * rate[None, :]).sum())


def track(chunks: Iterable[StepChunk], total_ns: int, steps: int, quiet: bool = False,
          stream: TextIO | None = None) -> Iterator[StepChunk]:
    """``chunks`` unchanged, with a bar over ``total_ns`` of machine time where one is wanted."""
    s = stream if stream is not None else sys.stderr
    isatty = getattr(s, "isatty", None)
    if quiet or steps < MIN_STEPS or total_ns <= 0 or not (isatty and isatty()):
        yield from chunks
        return
    from rich.console import Console
    from rich.progress import BarColumn, Progress, TaskProgressColumn, TextColumn, TimeRemainingColumn

    with Progress(TextColumn("{task.description}"), BarColumn(), TaskProgressColumn(), TimeRemainingColumn(),
                  console=Console(file=s), transient=True) as bar:
        task = bar.add_task(f"pulses ({steps:,} steps)", total=total_ns)
        for chunk in chunks:
            yield chunk
            bar.update(task, completed=min(chunk.t_end_ns, total_ns))
        bar.update(task, completed=total_ns)
