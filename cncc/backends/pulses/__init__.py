"""Step/dir pulses from the planner's Trajectory (``--emit=pulses``).

Consumes an :class:`~cncc.ir.trajectory.Trajectory` and a
:class:`~cncc.ir.machine.MachineModel`; produces, per axis, the integer-nanosecond
time and direction of every step, streamed in chunks, and writes them as VCD, CSV,
NPZ or a compressed (interval, count, add) step queue.  See ``docs/pulses.md``.

Usage (what the driver does for ``--emit=pulses --pulse-format=vcd``)::

    from cncc.backends.pulses import generate_pulses, write_pulses

    chunks = generate_pulses(traj, machine, mode="exact", spans=spans, sink=sink,
                             pauses=event_pauses(cmds, traj.cmd_index, machine),
                             reversals=reversal_pauses(traj, machine, mode="exact"))
    write_pulses(chunks, "vcd", "out.vcd")      # or a binary/text stream

* ``mode``: ``"exact"`` (each step when the position crosses its boundary) or
  ``"interp"`` (SZGH 2 ms interpolation: pulses counted per ``period_s`` and spread
  evenly).
* ``spans``: ``spans[k]`` is the span of IR command ``k`` (the trajectory's
  ``cmd_index``), used to place diagnostics E07xx in ``sink``.
* ``pauses``: ``(command index, ns)`` of the commands without motion that take time
  (dwells, tool changes, spindle ramps, stops, waits; the driver takes them from
  ``cncc.backends.timing.event_pauses``); the time line stops for them.
* ``reversals``: the reversal pauses (SZGH Axis P68) from :func:`reversal_pauses`, which
  the driver also hands to the timing report.
* ``fmt``: one of :data:`FORMATS` — ``vcd``, ``csv``, ``npz``, ``queue``.

numpy is imported by this package's modules only.
"""

from cncc.backends.pulses.chunk import AxisSteps, PulseLayout, StepChunk
from cncc.backends.pulses.generate import MODES, generate_pulses, reversal_pauses
from cncc.backends.pulses.pauses import ReversalPauses
from cncc.backends.pulses.queue import DEFAULT_MAX_ERROR_NS, read_queue
from cncc.backends.pulses.spec import AxisPulseSpec
from cncc.backends.pulses.write import FORMATS, WriteStats, write_pulses

__all__ = [
    "DEFAULT_MAX_ERROR_NS",
    "FORMATS",
    "MODES",
    "AxisPulseSpec",
    "AxisSteps",
    "PulseLayout",
    "ReversalPauses",
    "StepChunk",
    "WriteStats",
    "generate_pulses",
    "read_queue",
    "reversal_pauses",
    "write_pulses",
]
