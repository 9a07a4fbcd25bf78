"""Typed mode commands: the modal changes and markers with no motion of their own.

Each is a frozen, slotted dataclass with ``span`` and ``frame`` like every command,
and typed fields instead of the former ``SetMode(name: str, value: Any)``.  The
frame the command carries is the frame *after* the change (units, plane, offsets,
compensation ...), so consumers that only need the new state read ``frame``; the
fields say what the change was where the frame cannot (a tool-table write, a
synchronisation pitch, a call boundary ...).

:func:`set_mode` (and the deprecated alias :func:`SetMode`) builds the typed command
from a legacy ``(name, value)`` pair; converted code constructs the classes directly.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

from cncc.ir.frame import CompSide, Frame, Mirror, Plane, Rotation, Scaling, Units, Vec6
from cncc.ir.pathmode import PathMode
from cncc.source import Span

Held6 = tuple[bool, bool, bool, bool, bool, bool]


class FeedMode(enum.Enum):
    """G94 / G95 / G93."""

    PER_MIN = "per_min"
    PER_REV = "per_rev"
    INVERSE_TIME = "inverse_time"


class ToolData(enum.Enum):
    """The tool table a G10 data input writes (SYNTEC/Fanuc G10 L10-L13)."""

    LENGTH = "length"
    LENGTH_WEAR = "length_wear"
    RADIUS = "radius"
    RADIUS_WEAR = "radius_wear"


@dataclass(frozen=True, slots=True)
class SetUnits:
    """G20/G21: the program's length units (``frame.units`` after it)."""

    span: Span
    frame: Frame
    units: Units


@dataclass(frozen=True, slots=True)
class SetPlane:
    """G17/G18/G19."""

    span: Span
    frame: Frame
    plane: Plane


@dataclass(frozen=True, slots=True)
class SetFeedMode:
    span: Span
    frame: Frame
    mode: FeedMode


@dataclass(frozen=True, slots=True)
class SetPathMode:
    """G61/G61.1/G64 with LinuxCNC's P tolerance and Q naive-CAM tolerance (None: not reported);
    ``for_cycle``: the exact path a LinuxCNC canned cycle sets around itself, and the mode restored."""

    span: Span
    frame: Frame
    mode: PathMode
    tolerance_mm: float = 0.0
    naive_cam_mm: float | None = None
    for_cycle: bool = False


@dataclass(frozen=True, slots=True)
class SetCutterComp:
    span: Span
    frame: Frame
    side: CompSide


@dataclass(frozen=True, slots=True)
class SetToolLength:
    """G43/G44/G49/G43.1: the signed length offset now in force."""

    span: Span
    frame: Frame
    length_mm: float


@dataclass(frozen=True, slots=True)
class SetWorkSystem:
    """G54 ... G59.x (or a change of the active system's offset): ``index`` as in ``Frame.work_index``."""

    span: Span
    frame: Frame
    index: int


@dataclass(frozen=True, slots=True)
class SetG92Offset:
    span: Span
    frame: Frame
    offset_mm: Vec6


@dataclass(frozen=True, slots=True)
class PresetG92:
    """A G92 preset naming ``axes`` (indices into AXES): translation writes them again."""

    span: Span
    frame: Frame
    axes: tuple[int, ...]


@dataclass(frozen=True, slots=True)
class SetLocalOffset:
    """G52."""

    span: Span
    frame: Frame
    offset_mm: Vec6


@dataclass(frozen=True, slots=True)
class SetXyRotation:
    """LinuxCNC's rotation of the active work system (G10 L2 R), reported by the canon trace."""

    span: Span
    frame: Frame
    angle_deg: float


@dataclass(frozen=True, slots=True)
class SetPolar:
    """Polar coordinates on about ``origin_mm`` (plane coordinates), or off (None)."""

    span: Span
    frame: Frame
    origin_mm: tuple[float, float] | None


@dataclass(frozen=True, slots=True)
class SetScaling:
    span: Span
    frame: Frame
    scaling: Scaling | None


@dataclass(frozen=True, slots=True)
class SetMirror:
    span: Span
    frame: Frame
    mirror: Mirror | None


@dataclass(frozen=True, slots=True)
class SetRotation:
    span: Span
    frame: Frame
    rotation: Rotation | None


@dataclass(frozen=True, slots=True)
class WriteToolTable:
    """G10 L1/L10/L11: a tool-table entry written (lathe fields zero on a mill)."""

    span: Span
    frame: Frame
    tool: int
    length_mm: float
    diameter_mm: float
    x_mm: float = 0.0
    front_angle_deg: float = 0.0
    back_angle_deg: float = 0.0
    orientation: int = 0


@dataclass(frozen=True, slots=True)
class WriteWorkTable:
    """G10 L2/L20: work system ``index`` changed from ``old_mm`` to ``new_mm`` (translation writes it)."""

    span: Span
    frame: Frame
    index: int
    old_mm: Vec6
    new_mm: Vec6


@dataclass(frozen=True, slots=True)
class WriteToolData:
    """SYNTEC/Fanuc G10 data input: entry ``entry`` of ``table`` now holds ``value_mm``."""

    span: Span
    frame: Frame
    table: ToolData
    entry: int
    value_mm: float


@dataclass(frozen=True, slots=True)
class SetCssReference:
    """SERIES 8 lathe G92 R: the radius ``radius_mm`` is at the tool's X ``x_mm``."""

    span: Span
    frame: Frame
    radius_mm: float
    x_mm: float


@dataclass(frozen=True, slots=True)
class SetSpindleMode:
    """LinuxCNC's SET_SPINDLE_MODE: constant speed (0) or CSS with this top speed."""

    span: Span
    frame: Frame
    css_max_rpm: float = 0.0


@dataclass(frozen=True, slots=True)
class SpindleSync:
    """The feed axis follows the spindle at ``pitch_mm`` per revolution until a SpindleSync of 0."""

    span: Span
    frame: Frame
    pitch_mm: float


@dataclass(frozen=True, slots=True)
class RigidTap:
    """LinuxCNC's RIGID_TAP to ``end``: the canon trace writes one call for the ``folded`` commands after it."""

    span: Span
    frame: Frame
    end: Vec6
    folded: int


@dataclass(frozen=True, slots=True)
class NurbsFeed:
    """LinuxCNC's NURBS_FEED (G5.x): ``points`` control points of ``order``; ``folded`` moves follow."""

    span: Span
    frame: Frame
    points: int
    order: int
    folded: int


@dataclass(frozen=True, slots=True)
class Probe:
    """LinuxCNC's G38.x probe toward ``end``: ``op`` is the probe op (``probe_toward`` ...); the canon trace
    writes one STRAIGHT_PROBE for the ``folded`` moves after it (the probe move and the interpreter's back-off)."""

    span: Span
    frame: Frame
    end: Vec6
    op: str
    folded: int


@dataclass(frozen=True, slots=True)
class SetToolNumber:
    """LinuxCNC's M61 Q: the tool in the spindle is declared to be ``tool``, without a tool change."""

    span: Span
    frame: Frame
    tool: int


@dataclass(frozen=True, slots=True)
class SetOverrides:
    """Feed and speed overrides enabled (LinuxCNC's tapping cycles switch them off and on)."""

    span: Span
    frame: Frame
    enabled: bool


@dataclass(frozen=True, slots=True)
class SetFeedOverride:
    """The feed override alone enabled or disabled (LinuxCNC G76 around each synchronised pass)."""

    span: Span
    frame: Frame
    enabled: bool


@dataclass(frozen=True, slots=True)
class HoldAxes:
    """The machine moved these axes outside the program (``Frame.held_axes`` after it)."""

    span: Span
    frame: Frame
    axes: Held6


@dataclass(frozen=True, slots=True)
class CallBoundary:
    """Where one run of a called program begins (``begin``) or ends: ``key`` names the program body."""

    span: Span
    frame: Frame
    begin: bool
    key: str
    name: str


@dataclass(frozen=True, slots=True)
class SetOutput:
    """SZGH OUT: output ``signal`` switched on or off."""

    span: Span
    frame: Frame
    signal: str
    on: bool


@dataclass(frozen=True, slots=True)
class SetSmoothing:
    """A smoothing / high-speed mode code with its words (no modelled effect)."""

    span: Span
    frame: Frame
    code: str
    words: tuple[tuple[str, float], ...] = ()


@dataclass(frozen=True, slots=True)
class InterpreterReport:
    """Where LinuxCNC's interpreter reports a mode change in its trace (``COMMENT("interpreter: ...")``):
    ``key`` names the text in the dialect's ``[canon.comments]``; only the canon backend writes it."""

    span: Span
    frame: Frame
    key: str


ModeCommand = (
    SetUnits
    | SetPlane
    | SetFeedMode
    | SetPathMode
    | SetCutterComp
    | SetToolLength
    | SetWorkSystem
    | SetG92Offset
    | PresetG92
    | SetLocalOffset
    | SetXyRotation
    | SetPolar
    | SetScaling
    | SetMirror
    | SetRotation
    | WriteToolTable
    | WriteWorkTable
    | WriteToolData
    | SetCssReference
    | SetSpindleMode
    | SpindleSync
    | RigidTap
    | NurbsFeed
    | Probe
    | SetToolNumber
    | SetOverrides
    | SetFeedOverride
    | HoldAxes
    | CallBoundary
    | SetOutput
    | SetSmoothing
    | InterpreterReport
)
"""Every mode command (a part of :data:`cncc.ir.Command`)."""

MODE_TYPES = (
    SetUnits, SetPlane, SetFeedMode, SetPathMode, SetCutterComp, SetToolLength, SetWorkSystem, SetG92Offset,
    PresetG92, SetLocalOffset, SetXyRotation, SetPolar, SetScaling, SetMirror, SetRotation, WriteToolTable,
    WriteWorkTable, WriteToolData, SetCssReference, SetSpindleMode, SpindleSync, RigidTap, NurbsFeed,
    Probe, SetToolNumber, SetOverrides, SetFeedOverride, HoldAxes, CallBoundary, SetOutput, SetSmoothing,
    InterpreterReport,
)
"""The mode command classes, for ``isinstance``."""
