"""Frames: the immutable coordinate context a command was programmed in.

A frame records everything needed to turn the command's programmed coordinates into
machine coordinates: units, plane, work/local/G92 offsets, the programmable
transforms (polar, scaling, mirror, rotation) and the compensation state.  Frames
are shared: consecutive commands programmed under the same modes point to the same
frame object, and a new frame is built only when something changes.

All lengths are millimetres and all angles degrees, whatever the program's units;
``units`` only says how the program wrote them (for emitters and the canon trace).
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass, field

AXES: tuple[str, ...] = ("X", "Y", "Z", "A", "B", "C")
"""Axis order of every 6-vector in the IR."""

Vec6 = tuple[float, float, float, float, float, float]
ZERO6: Vec6 = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
MM_PER_INCH = 25.4


class Units(enum.Enum):
    MM = "mm"
    INCH = "inch"

    @property
    def mm_per_unit(self) -> float:
        return 1.0 if self is Units.MM else MM_PER_INCH


class Plane(enum.Enum):
    """Active plane: the two in-plane axes and the normal axis (indices into AXES)."""

    XY = (0, 1, 2)
    ZX = (2, 0, 1)
    YZ = (1, 2, 0)

    first: int  # plain attributes, set once per member: read per move by cutter comp and the backends
    second: int
    normal: int

    def __init__(self, first: int, second: int, normal: int) -> None:
        self.first, self.second, self.normal = first, second, normal


class CompSide(enum.Enum):
    OFF = "off"
    LEFT = "left"
    RIGHT = "right"


@dataclass(frozen=True, slots=True)
class Scaling:
    center_mm: tuple[float, float, float]
    factors: tuple[float, float, float]


@dataclass(frozen=True, slots=True)
class Mirror:
    """Programmable mirror: axes flagged True are mirrored about ``center_mm``."""

    center_mm: tuple[float, float, float]
    axes: tuple[bool, bool, bool]


@dataclass(frozen=True, slots=True)
class Rotation:
    """Rotation in the active plane about ``center_mm`` (plane coordinates).

    ``work``: the work system's own rotation (LinuxCNC G10 L2 R, centre ``-g92``: the machine
    point is ``R (p + g92) + g5x``): positions are the program's, the canon trace keeps them,
    and :func:`add_offsets` includes it.
    """

    plane: Plane
    center_mm: tuple[float, float]
    angle_deg: float
    work: bool = False


@dataclass(frozen=True, slots=True)
class Polar:
    """Polar coordinate mode: radius and angle words about ``origin_mm``."""

    plane: Plane
    origin_mm: tuple[float, float]


@dataclass(frozen=True, slots=True)
class Frame:
    units: Units = Units.MM
    plane: Plane = Plane.XY
    work_index: int = 1  # 1 = G54, 2 = G55, ... 6 = G59, 7.. = G59.1..
    work_offset_mm: Vec6 = ZERO6
    local_offset_mm: Vec6 = ZERO6  # G52
    g92_offset_mm: Vec6 = ZERO6
    machine_coords: bool = False  # G53: coordinates are machine coordinates
    polar: Polar | None = None
    scaling: Scaling | None = None
    mirror: Mirror | None = None
    rotation: Rotation | None = None
    tool_length_mm: float = 0.0  # signed, added to Z (G43 +, G44 -)
    tool_length_index: int = 0  # H number (0: none)
    tool_length_axis: int = 2  # axis the length offset acts on (2 = Z; SZGH type B: the plane normal)
    comp_side: CompSide = CompSide.OFF
    comp_radius_mm: float = 0.0
    comp_index: int = 0  # D number
    incremental: bool = False  # G91 when programmed: transforms rotate/scale the increment (see docs/frames.md)
    # Axes (X Y Z A B C) whose machine position is not the program's: none named absolutely yet
    # since the start, a transform cancel (the tool stays at the transformed point) or an event
    # that moves the machine outside the program (tool change, reference return, G53).  A move
    # carries them from where the tool really is by the programmed increment (zero when the
    # block does not name them); a translation writes their next absolute word.  docs/frames.md.
    held_axes: tuple[bool, bool, bool, bool, bool, bool] = (False, False, False, False, False, False)
    after_cancel: bool = False  # a transform was cancelled and X Y Z have not all been named absolutely since
    # Program origin in machine coordinates (work + local + G92), computed once per frame
    # because passes ask for it on every command.
    total_offset_mm: Vec6 = field(init=False, repr=False, compare=False, default=ZERO6)

    def __post_init__(self) -> None:
        if self.machine_coords:
            return
        w, loc, g = self.work_offset_mm, self.local_offset_mm, self.g92_offset_mm
        object.__setattr__(self, "total_offset_mm", (
            w[0] + loc[0] + g[0],
            w[1] + loc[1] + g[1],
            w[2] + loc[2] + g[2],
            w[3] + loc[3] + g[3],
            w[4] + loc[4] + g[4],
            w[5] + loc[5] + g[5],
        ))

    @property
    def is_identity(self) -> bool:
        return self == IDENTITY_FRAME or (
            self.total_offset_mm == ZERO6
            and self.polar is None
            and self.scaling is None
            and self.mirror is None
            and self.rotation is None
            and self.tool_length_mm == 0.0
            and self.comp_side is CompSide.OFF
        )


IDENTITY_FRAME = Frame()
NOT_HELD: tuple[bool, bool, bool, bool, bool, bool] = (False, False, False, False, False, False)
LINEAR_HELD: tuple[bool, bool, bool, bool, bool, bool] = (True, True, True, False, False, False)
ALL_HELD: tuple[bool, bool, bool, bool, bool, bool] = (True, True, True, True, True, True)


def add_offsets(p: Vec6, frame: Frame) -> Vec6:
    """Program coordinates of ``frame`` -> the same point plus the frame's total offset (turned
    first by a work-system rotation, :attr:`Rotation.work`)."""
    o = frame.total_offset_mm
    r = frame.rotation
    if r is not None and r.work:
        c = r.center_mm
        x, y = _turn(p[0] - c[0], p[1] - c[1], r.angle_deg)
        return (x + c[0] + o[0], y + c[1] + o[1], p[2] + o[2], p[3] + o[3], p[4] + o[4], p[5] + o[5])
    return (p[0] + o[0], p[1] + o[1], p[2] + o[2], p[3] + o[3], p[4] + o[4], p[5] + o[5])


def sub_offsets(b: Vec6, frame: Frame) -> Vec6:
    """The inverse of :func:`add_offsets`."""
    o = frame.total_offset_mm
    r = frame.rotation
    if r is not None and r.work:
        c = r.center_mm
        x, y = _turn(b[0] - o[0] - c[0], b[1] - o[1] - c[1], -r.angle_deg)
        return (x + c[0], y + c[1], b[2] - o[2], b[3] - o[3], b[4] - o[4], b[5] - o[5])
    return (b[0] - o[0], b[1] - o[1], b[2] - o[2], b[3] - o[3], b[4] - o[4], b[5] - o[5])


def _turn(x: float, y: float, angle_deg: float) -> tuple[float, float]:
    a = math.radians(angle_deg)
    c, s = math.cos(a), math.sin(a)
    return c * x - s * y, s * x + c * y
