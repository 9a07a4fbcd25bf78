"""Per-axis pulse parameters derived from the machine model, and the position → step map.

Consumes a :class:`~cncc.ir.machine.MachineModel` and the trajectory's axis names;
produces one :class:`AxisPulseSpec` per trajectory axis.

The motor step count at commanded position ``p_mm`` is ::

    N(p) = floor(r * g(p) + 1/2),   r = steps_per_mm * CMR / CMD,   g(p) = p + pitch(p)

so a step happens when ``r * g(p(t))`` crosses a half-integer, the step count is
always computed from the absolute position (the gear remainder is carried, never
accumulated), and ``N`` of the commanded end of a command is where the motor stands.
``pitch`` is the pitch-error correction, linear between table points, held constant
beyond the table of a linear axis and periodic over 360° on a rotary axis.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from cncc.ir.machine import Axis, AxisKind, BacklashMode, StepOutput

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]

ROTARY_PERIOD_DEG = 360.0


class PitchMap:
    """Pitch-error correction ``c(p)`` (mm) and the monotone map ``g(p) = p + c(p)``.

    ``table_mm`` holds ``(position relative to home, correction)`` pairs.  The home
    position has correction 0 unless the table gives a value for it.
    """

    def __init__(self, table_mm: tuple[tuple[float, float], ...], home_mm: float, rotary: bool) -> None:
        pts: dict[float, float] = {0.0: 0.0}
        for x, c in table_mm:
            key = float(x) % ROTARY_PERIOD_DEG if rotary else float(x)
            pts[key] = float(c)
        xs = np.array(sorted(pts), dtype=np.float64)
        cs = np.array([pts[x] for x in xs.tolist()], dtype=np.float64)
        if rotary:  # close the period: the point after the last is the first, 360° on
            xs = np.append(xs, xs[0] + ROTARY_PERIOD_DEG)
            cs = np.append(cs, cs[0])
        self.home_mm = home_mm
        self.rotary = rotary
        self.x_mm = xs
        self.c_mm = cs
        self.g_mm = xs + cs
        slopes = np.diff(cs) / np.diff(xs) if xs.size > 1 else np.zeros(0)
        self.max_slope = float(slopes.max()) if slopes.size else 0.0
        self.monotone = bool(np.all(np.diff(self.g_mm) > 0)) if xs.size > 1 else True

    def offset_mm(self, p_mm: FloatArray) -> FloatArray:
        u = p_mm - self.home_mm
        if self.rotary:
            return np.interp(u, self.x_mm[:-1], self.c_mm[:-1], period=ROTARY_PERIOD_DEG)
        return np.interp(u, self.x_mm, self.c_mm)

    def forward(self, p_mm: FloatArray) -> FloatArray:
        return p_mm + self.offset_mm(p_mm)

    def inverse(self, q_mm: FloatArray) -> FloatArray:
        u = q_mm - self.home_mm
        if self.rotary:
            g0 = self.g_mm[0]
            k = np.floor((u - g0) / ROTARY_PERIOD_DEG)
            u0 = u - k * ROTARY_PERIOD_DEG
            x: FloatArray = np.interp(u0, self.g_mm, self.x_mm) + k * ROTARY_PERIOD_DEG
            return x + self.home_mm
        inside = np.interp(u, self.g_mm, self.x_mm)
        below = u - self.c_mm[0]
        above = u - self.c_mm[-1]
        x = np.where(u < self.g_mm[0], below, np.where(u > self.g_mm[-1], above, inside))
        return self.home_mm + x


@dataclass(frozen=True, slots=True)
class AxisPulseSpec:
    """What the pulse generator needs to know about one axis (all derived, immutable)."""

    name: str
    rotary: bool
    steps_num: float  # steps_per_mm * CMR: r = steps_num / steps_den
    steps_den: float  # CMD
    direction_invert: bool
    backlash_steps: int
    backlash_mode: BacklashMode
    backlash_a_rate_hz: float  # mode A: constant step rate of the compensation
    backlash_rate_hz: float  # mode B: top step rate
    backlash_start_rate_hz: float  # mode B: start step rate
    backlash_accel_hz_s: float  # mode B: step-rate change per second
    reversal_delay_s: float
    pitch: PitchMap | None
    max_step_rate_hz: float
    pulse_width_ns: int
    dir_setup_ns: int
    soft_min_mm: float | None
    soft_max_mm: float | None

    @property
    def steps_per_mm(self) -> float:
        return self.steps_num / self.steps_den

    @property
    def min_spacing_ns(self) -> int:
        """Minimum time between two step edges: pulse high plus as long low."""
        return 2 * self.pulse_width_ns

    def motor_position(self, p_mm: FloatArray) -> FloatArray:
        """``r * g(p)``: the motor position in (fractional) steps."""
        q = self.pitch.forward(p_mm) if self.pitch is not None else p_mm
        return q * self.steps_num / self.steps_den

    def motor_steps(self, p_mm: FloatArray) -> IntArray:
        """``N(p)``: the step count the motor stands at for commanded position ``p_mm``."""
        return np.floor(self.motor_position(p_mm) + 0.5).astype(np.int64)

    def commanded_steps(self, p_mm: FloatArray) -> IntArray:
        """Step count without pitch compensation (``floor(r p + 1/2)``)."""
        return np.floor(p_mm * self.steps_num / self.steps_den + 0.5).astype(np.int64)

    def pitch_steps(self, p_mm: FloatArray) -> IntArray:
        """Steps added by pitch compensation at ``p_mm``: ``motor_steps - commanded_steps``."""
        return self.motor_steps(p_mm) - self.commanded_steps(p_mm)

    def boundary_mm(self, s_new: IntArray, direction: npt.NDArray[np.int8] | IntArray) -> FloatArray:
        """Commanded position at which the motor steps to ``s_new`` moving in ``direction``."""
        q = (s_new - 0.5 * direction) * self.steps_den / self.steps_num
        return self.pitch.inverse(q) if self.pitch is not None else q

    def rate_factor(self) -> float:
        """Upper bound of ``dN/dp`` in steps per mm (pitch slope included)."""
        slope = max(0.0, self.pitch.max_slope) if self.pitch is not None else 0.0
        return self.steps_per_mm * (1.0 + slope)


def axis_spec(axis: Axis) -> tuple[AxisPulseSpec, bool]:
    """The pulse spec of ``axis``; the flag is False when its pitch table was rejected."""
    so: StepOutput = axis.step
    rotary = axis.kind is AxisKind.ROTARY
    num = float(so.steps_per_mm) * float(so.gear_cmr)
    den = float(so.gear_cmd)
    r = num / den
    pitch: PitchMap | None = None
    ok = True
    if so.pitch_table_mm:
        pm = PitchMap(so.pitch_table_mm, axis.home_mm, rotary)
        if pm.monotone:
            pitch = pm
        else:
            ok = False
    per_s = r / 60.0  # mm/min -> steps/s
    spec = AxisPulseSpec(
        name=axis.name,
        rotary=rotary,
        steps_num=num,
        steps_den=den,
        direction_invert=so.direction_invert,
        backlash_steps=math.floor(abs(so.backlash_mm) * r + 0.5),
        backlash_mode=so.backlash_mode if so.backlash_mm else BacklashMode.NONE,
        backlash_a_rate_hz=max(so.backlash_a_speed_mm_min * per_s, 1.0),
        backlash_rate_hz=max(so.backlash_speed_mm_min * per_s, 1.0),
        backlash_start_rate_hz=max(min(so.backlash_start_speed_mm_min, so.backlash_speed_mm_min) * per_s, 1.0),
        backlash_accel_hz_s=max(so.backlash_accel_mm_s2 * r, 1.0),
        reversal_delay_s=max(0.0, so.reversal_delay_s),
        pitch=pitch,
        max_step_rate_hz=so.max_step_rate_hz,
        pulse_width_ns=int(so.pulse_width_ns),
        dir_setup_ns=int(so.dir_setup_ns),
        soft_min_mm=axis.soft_min_mm,
        soft_max_mm=axis.soft_max_mm,
    )
    return spec, ok


def backlash_offsets_s(spec: AxisPulseSpec) -> tuple[FloatArray, float]:
    """Times (from the reversal) of the backlash compensation pulses of ``spec``, and the move's duration.

    Pulse ``k`` (0-based) happens when the compensation move reaches ``(k + 1/2)``
    steps.  Mode A moves at a constant rate; mode B ramps from the start rate to the
    top rate and back down with ``backlash_accel_hz_s``.
    """
    b = spec.backlash_steps
    if b <= 0 or spec.backlash_mode is BacklashMode.NONE:
        return np.zeros(0), 0.0
    x = np.arange(b, dtype=np.float64) + 0.5
    if spec.backlash_mode is BacklashMode.A:
        return x / spec.backlash_a_rate_hz, b / spec.backlash_a_rate_hz
    vs, vm, a = spec.backlash_start_rate_hz, spec.backlash_rate_hz, spec.backlash_accel_hz_s
    half = b / 2.0
    x_acc = min((vm * vm - vs * vs) / (2 * a), half)
    v_peak = math.sqrt(vs * vs + 2 * a * x_acc)
    t_acc = (v_peak - vs) / a
    t_total = 2 * t_acc + (b - 2 * x_acc) / v_peak

    def accel_time(d: FloatArray) -> FloatArray:
        return (np.sqrt(vs * vs + 2 * a * d) - vs) / a

    t = np.where(x <= x_acc, accel_time(np.minimum(x, x_acc)), t_acc + (x - x_acc) / v_peak)
    tail = x > b - x_acc
    return np.where(tail, t_total - accel_time(np.maximum(b - x, 0.0)), t), t_total
