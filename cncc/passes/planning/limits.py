"""Per-axis limits of a machine as numpy arrays in the IR axis order (X Y Z A B C).

Consumes a :class:`MachineModel`; produces :class:`AxisLimits` with SI-per-second
units (mm/s, mm/s^2, mm/s^3).  An IR axis the machine lacks gets the limits of the
machine's first axis and ``present[i] = False`` (the planner reports moves on it).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cncc.ir.frame import AXES
from cncc.ir.machine import Axis, MachineModel
from cncc.ir.trajectory import FloatArray


@dataclass(frozen=True)
class AxisLimits:
    """Arrays of shape ``(6,)``; velocities already include the step-rate limit."""

    present: np.ndarray  # bool
    vmax_mm_s: FloatArray  # feed moves: axis max velocity and step-rate limit
    rapid_mm_s: FloatArray  # G00 rate (capped by the step rate)
    amax_mm_s2: FloatArray
    jmax_mm_s3: FloatArray
    start_mm_s: FloatArray  # SZGH take-off speed (0: none)
    step_mm_s: FloatArray  # SZGH per-axis speed step at corners (0: none)
    reversal_mm_s: FloatArray  # SZGH speed at an axis reversal (0: none)
    step_rate_mm_s: FloatArray  # step output rate (max rate and pulse spacing) / steps per mm


def axis_limits(machine: MachineModel) -> AxisLimits:
    by_name = {a.name: a for a in machine.axes}
    first = machine.axes[0]
    axes: list[Axis] = [by_name.get(n, first) for n in AXES]
    present = np.array([n in by_name for n in AXES])

    def arr(get: str, scale: float = 1.0) -> FloatArray:
        return np.array([float(getattr(a, get)) * scale for a in axes])

    step_rate = np.array([output_rate_hz(a) / _steps_per_mm(a) for a in axes])
    return AxisLimits(
        present=present,
        vmax_mm_s=np.minimum(arr("max_velocity_mm_min", 1 / 60), step_rate),
        rapid_mm_s=np.minimum(arr("rapid_mm_min", 1 / 60), step_rate),
        amax_mm_s2=arr("max_accel_mm_s2"),
        jmax_mm_s3=arr("max_jerk_mm_s3"),
        start_mm_s=arr("start_speed_mm_min", 1 / 60),
        step_mm_s=arr("max_speed_step_mm_min", 1 / 60),
        reversal_mm_s=arr("reversal_speed_mm_min", 1 / 60),
        step_rate_mm_s=step_rate,
    )


def output_rate_hz(axis: Axis) -> float:
    """Highest step rate the axis' output can emit: its maximum rate and its minimum pulse
    spacing (pulse high plus as long low, ``2 * pulse_width_ns``, with 2 ns for the
    rounding of step times to whole nanoseconds)."""
    rate = axis.step.max_step_rate_hz
    if axis.step.pulse_width_ns > 0:
        rate = min(rate, 1e9 / (2 * axis.step.pulse_width_ns + 2))
    return rate


def _steps_per_mm(axis: Axis) -> float:
    """Output pulses per mm: steps per mm times the electronic gear CMR/CMD."""
    return axis.step.steps_per_mm * axis.step.gear_cmr / max(axis.step.gear_cmd, 1)


def path_limit(per_axis: FloatArray, u: FloatArray) -> FloatArray:
    """Largest path rate whose components ``|u_i| * rate`` stay within ``per_axis``.

    ``u`` has shape ``(n, 6)``; the result ``(n,)`` (inf where ``u`` is zero).
    """
    au = np.abs(u)
    with np.errstate(divide="ignore"):
        ratio = np.where(au > 1e-12, per_axis[None, :] / np.maximum(au, 1e-300), np.inf)
    out: FloatArray = ratio.min(axis=1)
    return out
