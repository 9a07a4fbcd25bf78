"""Trajectory: the planner's output, one row per phase of constant jerk.

Every phase ``k`` covers ``[t0_s[k], t0_s[k] + duration_s[k])`` and within it each
axis ``i`` moves as a cubic polynomial of the local time ``tau``::

    p_i(tau) = p0_mm[k, i] + v0[k, i] tau + a0[k, i] tau^2 / 2 + j[k, i] tau^3 / 6

Phases are contiguous in time and in position.  Arcs are represented by chords
that the planner chose within its tolerance, and independent-axis motions by
splitting time at every axis' phase boundary, so the representation is exact for
everything downstream: pulses and timing read only this.

Array shapes (``n`` phases, ``m`` axes):

* ``t0_s``, ``duration_s``: ``(n,)`` float64, seconds
* ``p0_mm``, ``v0_mm_s``, ``a0_mm_s2``, ``j_mm_s3``: ``(n, m)`` float64
  (degrees for rotary axes)
* ``cmd_index``: ``(n,)`` int64, index of the IR command responsible
* ``limit``: ``(n,)`` int8, what limited the phase (:class:`Limit` value)

numpy is imported here only; nothing on the CLI or LSP start-up path imports this
module.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from cncc.ir.frame import AXES

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]


class Limit(enum.IntEnum):
    """The constraint that bounded a phase (for timing reports)."""

    NONE = 0
    FEED = 1  # programmed feed
    ACCEL = 2
    JERK = 3
    CORNER = 4
    AXIS_VELOCITY = 5
    STEP_RATE = 6
    RAPID = 7
    CENTRIPETAL = 8


@dataclass(frozen=True, slots=True)
class Trajectory:
    t0_s: FloatArray
    duration_s: FloatArray
    p0_mm: FloatArray
    v0_mm_s: FloatArray
    a0_mm_s2: FloatArray
    j_mm_s3: FloatArray
    cmd_index: IntArray
    limit: npt.NDArray[np.int8]
    axes: tuple[str, ...] = AXES

    def __post_init__(self) -> None:
        n = self.t0_s.shape[0]
        m = len(self.axes)
        for name in ("duration_s", "cmd_index", "limit"):
            if getattr(self, name).shape != (n,):
                raise ValueError(f"Trajectory.{name} must have shape ({n},)")
        for name in ("p0_mm", "v0_mm_s", "a0_mm_s2", "j_mm_s3"):
            if getattr(self, name).shape != (n, m):
                raise ValueError(f"Trajectory.{name} must have shape ({n}, {m})")

    @property
    def phase_count(self) -> int:
        return int(self.t0_s.shape[0])

    @property
    def duration_total_s(self) -> float:
        if self.phase_count == 0:
            return 0.0
        return float(self.t0_s[-1] + self.duration_s[-1])

    def end_state(self, k: int) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Position, velocity, acceleration at the end of phase ``k``."""
        t = self.duration_s[k]
        v0, a0, j = self.v0_mm_s[k], self.a0_mm_s2[k], self.j_mm_s3[k]
        p = self.p0_mm[k] + v0 * t + a0 * t * t / 2 + j * t**3 / 6
        return p, v0 + a0 * t + j * t * t / 2, a0 + j * t

    def sample(self, t_s: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        """Position, velocity, acceleration, jerk at times ``t_s`` (shape ``(q,)``) -> ``(q, m)``."""
        k = np.clip(np.searchsorted(self.t0_s, t_s, side="right") - 1, 0, max(self.phase_count - 1, 0))
        tau = (t_s - self.t0_s[k])[:, None]
        v0, a0, j = self.v0_mm_s[k], self.a0_mm_s2[k], self.j_mm_s3[k]
        p = self.p0_mm[k] + v0 * tau + a0 * tau**2 / 2 + j * tau**3 / 6
        v = v0 + a0 * tau + j * tau**2 / 2
        a = a0 + j * tau
        return p, v, a, j

    def phase_at(self, t_s: FloatArray) -> IntArray:
        """Index of the phase that covers each time of ``t_s`` (clipped to the first/last phase)."""
        out: IntArray = np.clip(np.searchsorted(self.t0_s, t_s, side="right") - 1, 0,
                                max(self.phase_count - 1, 0)).astype(np.int64)
        return out

    def phase_info(self, t_s: FloatArray) -> tuple[IntArray, npt.NDArray[np.int8]]:
        """``cmd_index`` and ``limit`` of the phase at each time of ``t_s`` (shape ``(q,)`` each)."""
        if self.phase_count == 0:
            return np.zeros(np.shape(t_s), np.int64), np.zeros(np.shape(t_s), np.int8)
        k = self.phase_at(t_s)
        return self.cmd_index[k], self.limit[k]

    @staticmethod
    def empty(axes: tuple[str, ...] = AXES) -> Trajectory:
        m = len(axes)
        z = np.zeros(0)
        zm = np.zeros((0, m))
        return Trajectory(z, z.copy(), zm, zm.copy(), zm.copy(), zm.copy(),
                          np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int8), axes)
