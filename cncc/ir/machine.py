"""Machine model types (the data lives in ``cncc/machines/*.toml``).

Units are in the field names.  Linear axes are in mm, rotary axes in degrees (the
``_mm`` names then read as degrees).
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field


class RapidMode(enum.Enum):
    INTERPOLATED = "interpolated"  # straight line, all axes finish together
    INDEPENDENT = "independent"  # each axis at its own rate (dog-leg)


class AxisKind(enum.Enum):
    LINEAR = "linear"
    ROTARY = "rotary"


class BacklashMode(enum.Enum):
    NONE = "none"
    A = "A"  # SZGH mode A: extra pulses sent at once on reversal
    B = "B"  # SZGH mode B: extra pulses spread at the reversal speed


@dataclass(frozen=True, slots=True)
class MCode:
    """An M code the machine (not the control) implements, e.g. ``M10`` clamp, 0.8 s."""

    meaning: str = ""
    seconds: float = 0.0


@dataclass(frozen=True, slots=True)
class StepOutput:
    """Step/dir output of one axis."""

    steps_per_mm: float = 1000.0
    gear_cmr: int = 1  # electronic gear numerator (SZGH CMR)
    gear_cmd: int = 1  # electronic gear denominator (SZGH CMD)
    direction_invert: bool = False
    backlash_mm: float = 0.0
    backlash_mode: BacklashMode = BacklashMode.NONE
    reversal_delay_s: float = 0.0  # SZGH Axis P68: pause inserted when the axis reverses
    backlash_a_speed_mm_min: float = 1_000.0  # mode A: constant compensation speed (SZGH: < 1000)
    backlash_speed_mm_min: float = 3_000.0  # mode B: top speed (SZGH Speed P48)
    backlash_start_speed_mm_min: float = 500.0  # mode B: start speed (SZGH Speed P48-1)
    backlash_accel_mm_s2: float = 1_000.0  # mode B: accel (SZGH P48-2, 60000 mm/min/s)
    pitch_table_mm: tuple[tuple[float, float], ...] = ()  # (position, correction)
    max_step_rate_hz: float = 1_000_000.0
    pulse_width_ns: int = 2_000  # step high time; minimum spacing is twice this
    dir_setup_ns: int = 5_000


@dataclass(frozen=True, slots=True)
class Axis:
    name: str
    kind: AxisKind = AxisKind.LINEAR
    max_velocity_mm_min: float = 10_000.0
    max_accel_mm_s2: float = 1_000.0
    max_jerk_mm_s3: float = 50_000.0
    rapid_mm_min: float = 10_000.0
    start_speed_mm_min: float = 0.0
    max_speed_step_mm_min: float = 0.0  # SZGH: per-axis speed jump allowed at corners
    reversal_speed_mm_min: float = 0.0
    soft_min_mm: float | None = None
    soft_max_mm: float | None = None
    home_mm: float = 0.0
    step: StepOutput = field(default_factory=StepOutput)


class CornerRule(enum.Enum):
    JUNCTION_DEVIATION = "junction-deviation"
    EXACT_STOP = "exact-stop"
    SPEED_STEP = "speed-step"  # SZGH: per-axis max speed step at corners
    BLEND = "blend"


@dataclass(frozen=True, slots=True)
class MachineModel:
    name: str
    axes: tuple[Axis, ...]
    rapid_mode: RapidMode = RapidMode.INTERPOLATED
    max_feed_mm_min: float = 10_000.0
    default_feed_mm_min: float = 1_000.0
    corner_rule: CornerRule = CornerRule.JUNCTION_DEVIATION
    junction_deviation_mm: float = 0.01
    blend_tolerance_mm: float = 0.01
    square_corner_velocity_mm_s: float = 5.0
    interpolation_period_s: float = 0.001
    rapid_ends_in_stop: bool = False
    ramp: str = "s-curve"  # "linear", "s-curve"
    tool_change_s: float = 5.0
    spindle_ramp_s: float = 1.0
    optional_stop_s: float = 0.0
    start_speed_mm_min: float = 0.0  # path take-off speed, no ramp below it (SZGH Speed P11)
    max_speed_step_mm_min: float = 0.0  # path speed step done instantly (SZGH Speed P12)
    mst_stops_motion: bool = False  # M/S/T blocks (coolant, S, T, aux M) stop the path (SZGH)
    arc_tolerance_mm: float = 0.001  # chord sagitta allowed when arcs become chords
    # G28 reference and the G30 P2..P4 positions, machine coordinates (mm, deg)
    reference_positions_mm: tuple[tuple[float, ...], ...] = ((0.0, 0.0, 0.0, 0.0, 0.0, 0.0),) * 4
    notes: str = ""
    # the machine builder's own M codes: "M10" -> MCode (meaning, seconds it takes)
    m_codes: tuple[tuple[str, MCode], ...] = ()

    def m_code(self, name: str) -> MCode | None:
        """The machine's own M code ``name`` ("M10"), or None."""
        for key, code in self.m_codes:
            if key == name:
                return code
        return None

    def axis(self, name: str) -> Axis | None:
        for a in self.axes:
            if a.name == name:
                return a
        return None
