"""IR commands: the closed set of things a machine does.

Every command is a frozen, slotted dataclass carrying its source ``span`` and the
``frame`` it was programmed in.  Positions are 6-vectors (X Y Z A B C) in
millimetres and degrees, in the coordinates of the command's frame: programmed
coordinates after the front end resolved absolute/incremental words, units and the
decimal-point rule.  Passes lower frames step by step until every command is in
machine coordinates with the identity frame.

Dispatch on commands with ``match``/``case`` over :data:`Command`.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field

from cncc.ir.css import Css
from cncc.ir.frame import Frame, Plane, Vec6
from cncc.ir.modes import ModeCommand
from cncc.ir.pathmode import PathMode as PathMode  # re-exported: motions name it
from cncc.source import Span


class OriginKind(enum.Enum):
    """Why a move exists, where that changes how passes and backends treat it."""

    PROGRAM = "program"  # an ordinary programmed move
    MACHINE = "machine"  # G53: in machine coordinates, transforms leave it alone
    CYCLE = "cycle"  # a move of a canned cycle (``code`` the cycle code)
    CURVE = "curve"  # a piece of a NURBS / spline (G5.x)
    SYNC = "sync"  # spindle-synchronised (G33, G33.1)
    HOME = "home"  # a reference-return leg in program terms (G28/G30 to the intermediate point, G29)
    REFERENCE = "reference"  # the leg to the reference position: no transform applies to it
    CODE = "code"  # made by a code of its own that is none of these (SERIES 8 G06 oscillation)
    RETURN_START = "return_start"  # SZGH G26/G261-G265: back to the program's start point
    RETURN_SAVED = "return_saved"  # SZGH G61x: back to the point saved by G25
    PROBE = "probe"  # LinuxCNC G38.x: the probe move (``code`` the probe code)
    PROBE_BACKOFF = "probe_backoff"  # the stand-alone interpreter's back-off after a G38.x probe move


@dataclass(frozen=True, slots=True)
class Origin:
    """The origin of a move: its kind and the code as programmed that made it ("" for ordinary moves)."""

    kind: OriginKind = OriginKind.PROGRAM
    code: str = ""

    @property
    def programmed(self) -> bool:
        """An ordinary programmed move (no code of its own made it)."""
        return self.kind is OriginKind.PROGRAM

    @property
    def in_machine_terms(self) -> bool:
        """G53 and reference legs: in machine terms, no programmable transform applies."""
        return self.kind is OriginKind.MACHINE or self.kind is OriginKind.REFERENCE


PROGRAMMED = Origin()
MACHINE_ORIGIN = Origin(OriginKind.MACHINE, "G53")


@dataclass(frozen=True, slots=True)
class Motion:
    """Path-mode data shared by all motions of a block (interned by the front end)."""

    mode: PathMode = PathMode.CONTINUOUS
    blend_tolerance_mm: float | None = None  # None: the machine default
    inverse_time: bool = False
    per_rev: bool = False  # G95: feed is per spindle revolution
    css: Css | None = None  # G95 under G96: the spindle speed follows the radius (feed_mm_min is at the start)


DEFAULT_MOTION = Motion()


@dataclass(frozen=True, slots=True)
class Rapid:
    span: Span
    frame: Frame
    start: Vec6
    end: Vec6
    motion: Motion = DEFAULT_MOTION
    origin: Origin = PROGRAMMED  # why the move exists (G53, a reference return, a cycle ...)


@dataclass(frozen=True, slots=True)
class Linear:
    span: Span
    frame: Frame
    start: Vec6
    end: Vec6
    feed_mm_min: float  # path feed in mm/min (per-rev feeds resolved by `motion.per_rev`)
    motion: Motion = DEFAULT_MOTION
    origin: Origin = PROGRAMMED


@dataclass(frozen=True, slots=True)
class Arc:
    """Circular or helical move in ``plane``.

    ``center`` holds the full 6-vector whose in-plane components are the centre;
    ``turns`` is signed like LinuxCNC's rotation: +1 one counter-clockwise turn (or
    part of it), -1 clockwise; |turns| > 1 adds full circles.
    """

    span: Span
    frame: Frame
    start: Vec6
    end: Vec6
    center: Vec6
    turns: int
    plane: Plane
    feed_mm_min: float
    motion: Motion = DEFAULT_MOTION
    origin: Origin = PROGRAMMED


def with_ends(c: Rapid | Linear | Arc, frame: Frame, start: Vec6, end: Vec6,
              center: Vec6 | None = None) -> Rapid | Linear | Arc:
    """The same motion (its kind, feed, path mode and origin; an arc's turns and plane) in ``frame``
    from ``start`` to ``end``; an arc turns about ``center``, else about its own centre."""
    if isinstance(c, Rapid):
        return Rapid(c.span, frame, start, end, c.motion, c.origin)
    if isinstance(c, Linear):
        return Linear(c.span, frame, start, end, c.feed_mm_min, c.motion, c.origin)
    return Arc(c.span, frame, start, end, c.center if center is None else center, c.turns, c.plane, c.feed_mm_min,
               c.motion, c.origin)


@dataclass(frozen=True, slots=True)
class Dwell:
    span: Span
    frame: Frame
    seconds: float


class SpindleState(enum.Enum):
    CW = "cw"
    CCW = "ccw"
    OFF = "off"
    ORIENT = "orient"


@dataclass(frozen=True, slots=True)
class Spindle:
    span: Span
    frame: Frame
    state: SpindleState
    rpm: float


@dataclass(frozen=True, slots=True)
class SpindleSpeed:
    """S word: spindle speed set (rpm, or surface speed with ``css``)."""

    span: Span
    frame: Frame
    rpm: float
    css: bool = False


@dataclass(frozen=True, slots=True)
class FeedRate:
    """F word programmed: the new feed rate (mm/min, or mm/rev when per-rev)."""

    span: Span
    frame: Frame
    feed: float
    per_rev: bool = False


class CoolantState(enum.Enum):
    MIST = "mist"
    FLOOD = "flood"
    OFF = "off"


@dataclass(frozen=True, slots=True)
class Coolant:
    span: Span
    frame: Frame
    state: CoolantState


@dataclass(frozen=True, slots=True)
class SelectTool:
    span: Span
    frame: Frame
    tool: int


@dataclass(frozen=True, slots=True)
class ToolChange:
    span: Span
    frame: Frame
    tool: int


class StopKind(enum.Enum):
    PROGRAM_STOP = "M00"
    OPTIONAL_STOP = "M01"
    PROGRAM_END = "M02"
    END_REWIND = "M30"


@dataclass(frozen=True, slots=True)
class Stop:
    span: Span
    frame: Frame
    kind: StopKind


@dataclass(frozen=True, slots=True)
class Comment:
    span: Span
    frame: Frame
    text: str


@dataclass(frozen=True, slots=True)
class Message:
    """An operator message (MSG, #3006 ...), optionally a pause."""

    span: Span
    frame: Frame
    text: str
    pause: bool = False


@dataclass(frozen=True, slots=True)
class Aux:
    """An auxiliary M function with no modelled effect (e.g. M19 orient, user M codes)."""

    span: Span
    frame: Frame
    code: int  # M number in tenths
    args: tuple[tuple[str, float], ...] = field(default=())


@dataclass(frozen=True, slots=True)
class Wait:
    """Wait for an input or an operator (SZGH WAT, MSG pause); time from the machine."""

    span: Span
    frame: Frame
    what: str
    seconds: float = 0.0


class CycleKindBase(enum.Enum):
    """A canned cycle kind (no members of its own): the core kinds are :class:`CycleKind`; a
    dialect layer with cycles of its own defines an enum deriving from this one
    (``cncc/dialects/series8_cycles.py``).  The values are the ``cycle`` names of the dialect tables."""


def cycle_kind(name: str) -> CycleKindBase | None:
    """The cycle kind a dialect table names, among the kind enums defined (imported) so far."""
    for kinds in CycleKindBase.__subclasses__():
        try:
            return kinds(name)
        except ValueError:
            continue
    return None


class CycleKind(CycleKindBase):
    """The canned cycle kinds every dialect may use (the Fanuc family's and LinuxCNC's)."""

    DRILL = "drill"  # G81
    DRILL_DWELL = "drill_dwell"  # G82
    PECK = "peck"  # G83: full retract to R after each peck
    PECK_HIGH_SPEED = "peck_high_speed"  # G73: small retract after each peck
    TAP = "tap"  # G84: right-hand tap
    TAP_LEFT = "tap_left"  # G74: left-hand tap
    FINE_BORE = "fine_bore"  # G76: oriented stop and shift before the retract
    BORE_FEED_OUT = "bore_feed_out"  # G85
    BORE_STOP_RAPID_OUT = "bore_stop_rapid_out"  # G86
    BACK_BORE = "back_bore"  # G87: cut upward from R to the bottom
    BORE_MANUAL = "bore_manual"  # G88: operator retracts by hand
    BORE_DWELL_FEED_OUT = "bore_dwell_feed_out"  # G89
    # LinuxCNC 2.9's own sequences (rs274's interp_cycles; cncc/passes/linuxcnc_cycles.py)
    TAP_RS274 = "tap_rs274"  # G84: overrides off, feed in, reverse, dwell, feed out to the clear level
    TAP_LEFT_RS274 = "tap_left_rs274"  # G74: the same with the spindle turning counter-clockwise
    BORE_FEED_OUT_RS274 = "bore_feed_out_rs274"  # G85: feed in, feed out to R, rapid to the clear level
    BORE_DWELL_STOP_RS274 = "bore_dwell_stop_rs274"  # G86: feed in, dwell, stop, rapid out, restart
    BORE_MANUAL_RS274 = "bore_manual_rs274"  # G88: feed in, dwell, stop, program stop, restart (tool stays)
    BORE_DWELL_FEED_OUT_RS274 = "bore_dwell_feed_out_rs274"  # G89: feed in, dwell, feed out to the clear level


@dataclass(frozen=True, slots=True)
class Cycle:
    """One block's canned cycle (all its holes), kept whole until ``expand-cycles``.

    Levels are positions on the drilling axis (``frame.plane.normal``: Z in G17, Y in
    G18, X in G19) in the frame's program coordinates; ``holes`` are the positions the
    tool is put at before each hole (their drilling-axis component is unused).  The
    front end has already resolved G90/G91, K/L repeats, hole patterns, the return
    level of G98/G99 and the machine parameters (peck clearance, shift direction), so
    the expansion needs nothing but this record.
    """

    span: Span
    frame: Frame
    kind: CycleKindBase
    code: str  # as programmed ("G81"), so translation can keep the cycle
    start: Vec6  # tool position before the first hole
    holes: tuple[Vec6, ...]
    initial_mm: float  # initial level (G98 return)
    r_mm: float  # R level
    bottom_mm: float  # Z: the hole bottom (for a back bore, the top of the bore)
    retract_mm: float  # level every hole ends at (G98: initial, G99: R, G87: initial)
    feed_mm_min: float
    return_initial: bool = True  # G98 (True) or G99 (False) as programmed
    peck_mm: float = 0.0  # Q: depth per peck, 0 without pecks
    first_depth_mm: float | None = None  # SERIES 8 G83 I: level of the first stroke (None: R + peck)
    clearance_mm: float = 0.0  # d: G73 retract, G83 clearance, peck-tap back-off
    peck_tap_to_r: bool = True  # peck tapping returns to R (True) or backs off by d
    shift_mm: Vec6 = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)  # G76/G87 shift away from the wall
    dwell_s: float = 0.0
    spindle: SpindleState = SpindleState.CW  # direction when the cycle starts
    spindle_rpm: float = 0.0
    tap_pitch_mm: float = 0.0  # tapping: feed = rpm x pitch, spindle-synchronised
    repeat: int = 1  # K (SYNTEC) / L (SZGH) as programmed
    pattern: str = ""  # the hole-pattern code (G134 ...) that produced the holes
    pattern_words: tuple[tuple[str, float], ...] = ()  # its words as read (mm, deg, counts; origin by axis letter)
    motion: Motion = DEFAULT_MOTION
    lift_pause_s: float = 0.0  # G73/G83: dwell before each peck lift (SZGH User P8)
    zero_moves: bool = False  # LinuxCNC: the move over each hole and a dwell are made even with no length or time
    lift_at_feed: bool = False  # G73/G83: peck lifts at feed instead of rapid (User P8 < 0)

    @property
    def plane(self) -> Plane:
        return self.frame.plane

    @property
    def axis(self) -> int:
        """Index of the drilling axis in the 6-vectors."""
        return self.frame.plane.normal


Command = (
    Rapid
    | Linear
    | Arc
    | Dwell
    | Spindle
    | SpindleSpeed
    | FeedRate
    | Coolant
    | SelectTool
    | ToolChange
    | Stop
    | Comment
    | Message
    | ModeCommand
    | Aux
    | Wait
    | Cycle
)
"""The closed union of IR commands.  Later issues add cycles, probes, NURBS."""

MOTION_TYPES = (Rapid, Linear, Arc)
