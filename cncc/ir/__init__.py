"""The intermediate representation: commands with spans and frames, programs,
machine model types, and (in :mod:`cncc.ir.trajectory`, which needs numpy) the
planner's Trajectory.

This package imports nothing from the stages above it.
"""

from cncc.ir.commands import (
    MOTION_TYPES,
    Arc,
    Aux,
    Command,
    Comment,
    Coolant,
    CoolantState,
    Dwell,
    FeedRate,
    Linear,
    Message,
    Motion,
    PathMode,
    Rapid,
    SelectTool,
    SetMode,
    Spindle,
    SpindleSpeed,
    SpindleState,
    Stop,
    StopKind,
    ToolChange,
    Wait,
)
from cncc.ir.frame import AXES, IDENTITY_FRAME, ZERO6, CompSide, Frame, Plane, Units, Vec6
from cncc.ir.program import Program

__all__ = [
    "AXES",
    "IDENTITY_FRAME",
    "MOTION_TYPES",
    "ZERO6",
    "Arc",
    "Aux",
    "Command",
    "Comment",
    "CompSide",
    "Coolant",
    "CoolantState",
    "Dwell",
    "FeedRate",
    "Frame",
    "Linear",
    "Message",
    "Motion",
    "PathMode",
    "Plane",
    "Program",
    "Rapid",
    "SelectTool",
    "SetMode",
    "Spindle",
    "SpindleSpeed",
    "SpindleState",
    "Stop",
    "StopKind",
    "ToolChange",
    "Units",
    "Vec6",
    "Wait",
]
