"""How a motion ends (a part of every motion's :class:`~cncc.ir.commands.Motion`)."""

from __future__ import annotations

import enum


class PathMode(enum.Enum):
    """How a motion ends: blend into the next or stop exactly (G61/G09)."""

    CONTINUOUS = "continuous"  # G64: blend within the tolerance
    EXACT_STOP = "exact-stop"  # G61/G09: decelerate to zero at the end
    EXACT_PATH = "exact-path"  # G61.1-like: stay on the path, no stop required
