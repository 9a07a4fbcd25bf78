"""The emitter's view of the target's frame: what the output has set, and what is folded.

Consumes the frames of IR commands (program coordinates of the source); keeps the
offsets the *output* program has established on the target (work system, G52, G92,
tool length) and yields the blocks that bring the target's frame to the command's
frame where the target has codes for it.  Whatever the target cannot set is folded
into the written coordinates: :meth:`TargetFrame.fold` is the 6-vector added to a
command's program coordinates so that the target puts the tool at the same machine
position.

The work offsets are assumed to be the same tables on both controls (``--offsets``):
switching to a work system writes its code; a changed value of the same system
(G10 in the source) is folded.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from cncc.ir import ZERO6, Frame, Vec6

ZERO: Vec6 = ZERO6


def add(a: Vec6, b: Vec6) -> Vec6:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2], a[3] + b[3], a[4] + b[4], a[5] + b[5])


def sub(a: Vec6, b: Vec6) -> Vec6:
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2], a[3] - b[3], a[4] - b[4], a[5] - b[5])


def tool_vector(length_mm: float, axis: int) -> Vec6:
    v = [0.0] * 6
    v[axis] = length_mm
    return (v[0], v[1], v[2], v[3], v[4], v[5])


def base_offset(f: Frame) -> Vec6:
    """Where the frame's program origin is, tool length included (machine = program + this)."""
    return add(f.total_offset_mm, tool_vector(f.tool_length_mm, f.tool_length_axis))


@dataclass(slots=True)
class TargetFrame:
    """The offsets the output program has set on the target so far."""

    work_index: int = 1
    work_mm: Vec6 | None = None  # None until the first frame is seen (the table value of G54)
    local_mm: Vec6 = ZERO
    g92_mm: Vec6 = ZERO
    g92_in_local_mm: Vec6 = ZERO  # the part of the source's G92 offset the target holds in its local offset (G52)
    tool_mm: float = 0.0
    tool_index: int = 0
    tool_axis: int = 2
    work_tables: dict[int, Vec6] = field(default_factory=dict)

    def offset(self, machine_coords: bool = False) -> Vec6:
        tool = tool_vector(self.tool_mm, self.tool_axis)
        if machine_coords:
            return tool
        work = self.work_mm or ZERO
        return add(add(add(work, self.local_mm), self.g92_mm), tool)

    def fold(self, f: Frame, g53: bool) -> Vec6:
        """Added to ``f``'s program coordinates gives the target's program coordinates."""
        return sub(base_offset(f), self.offset(machine_coords=g53 and f.machine_coords))

    def adopt_work(self, f: Frame) -> None:
        """The target switched to ``f``'s work system: its table value (first seen) is in force."""
        self.work_index = f.work_index
        self.work_mm = self.work_tables.setdefault(f.work_index, f.work_offset_mm)
