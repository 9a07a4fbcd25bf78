"""The records the pulse generator streams to the writers.

A program's pulses arrive as a sequence of :class:`StepChunk`, one per time window.
Within a chunk each axis has its own time-sorted arrays (:class:`AxisSteps`).
Guarantees a writer may rely on:

* per axis, step times strictly increase across the whole stream;
* no later chunk has an event (step edge or direction edge) before
  ``chunk.horizon_ns``, so events before it can be written out for good;
* the direction line changes at ``dir_t_ns`` to ``dir_level`` (electrical level,
  after ``direction_invert``), at least ``dir_setup_ns`` before the next step and
  not before the previous step's pulse has ended.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from cncc.backends.pulses.spec import AxisPulseSpec

I64 = npt.NDArray[np.int64]


@dataclass(frozen=True, slots=True)
class PulseLayout:
    """Stream-wide facts: the axes, their electrical conventions, the time base."""

    specs: tuple[AxisPulseSpec, ...]
    mode: str  # "exact" or "interp"

    @property
    def axes(self) -> tuple[str, ...]:
        return tuple(s.name for s in self.specs)

    def initial_dir_level(self, i: int) -> int:
        """Electrical level of axis ``i``'s direction line before the first change."""
        return 0 if self.specs[i].direction_invert else 1

    @property
    def max_dir_setup_ns(self) -> int:
        return max((s.dir_setup_ns for s in self.specs), default=0)


@dataclass(frozen=True, slots=True)
class AxisSteps:
    """The steps of one axis in one chunk; arrays of shape ``(c,)`` and ``(d,)``.

    ``direction`` is the motor direction (+1/-1, before inversion); ``phase`` the
    trajectory phase responsible; ``backlash`` marks backlash-compensation pulses.
    """

    t_ns: I64
    direction: npt.NDArray[np.int8]
    phase: npt.NDArray[np.int32]
    backlash: npt.NDArray[np.bool_]
    dir_t_ns: I64
    dir_level: npt.NDArray[np.uint8]

    @property
    def count(self) -> int:
        return int(self.t_ns.shape[0])

    @property
    def net_steps(self) -> int:
        return int(self.direction.sum(dtype=np.int64))

    @staticmethod
    def empty() -> AxisSteps:
        return AxisSteps(
            np.zeros(0, np.int64), np.zeros(0, np.int8), np.zeros(0, np.int32),
            np.zeros(0, np.bool_), np.zeros(0, np.int64), np.zeros(0, np.uint8),
        )


@dataclass(frozen=True, slots=True)
class StepChunk:
    """The steps of every axis in one window ``[t_start_ns, t_end_ns)`` (machine time).

    Up to the end of this window, ``pause_ns`` is the reversal delay (SZGH Axis P68)
    inserted into the time line so far, ``event_ns`` the pauses of commands without
    motion (dwells, tool changes, ...): the trajectory has neither, so
    ``t_end_ns`` is the trajectory time plus both.
    """

    layout: PulseLayout
    index: int
    t_start_ns: int
    t_end_ns: int
    horizon_ns: int
    axes: tuple[AxisSteps, ...]
    pause_ns: int = 0
    event_ns: int = 0

    @property
    def step_count(self) -> int:
        return sum(a.count for a in self.axes)
