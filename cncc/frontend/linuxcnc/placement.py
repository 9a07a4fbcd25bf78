"""Where LinuxCNC's interpreter places program XY on the machine under a work-system rotation.

A leaf of the front end (geometry only): :mod:`cncc.frontend.linuxcnc.rotation` says when
rs274 re-expresses the position; G10 L20 and G28/G30 use :class:`Placement` and
:func:`home_position` directly.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from cncc.ir import Frame, Vec6


@dataclass(frozen=True, slots=True)
class Placement:
    """Where rs274's interpreter places program XY for G53, G28/G30 and G10 L20:
    ``R(theta) (p + g92) + g5x``."""

    g5x: tuple[float, float]
    g92: tuple[float, float]
    theta_deg: float

    @staticmethod
    def of_frame(f: Frame, theta_deg: float) -> Placement:
        g5x = (f.work_offset_mm[0] + f.local_offset_mm[0], f.work_offset_mm[1] + f.local_offset_mm[1])
        return Placement(g5x, (f.g92_offset_mm[0], f.g92_offset_mm[1]), theta_deg)

    def machine(self, x: float, y: float) -> tuple[float, float]:
        c, s = math.cos(math.radians(self.theta_deg)), math.sin(math.radians(self.theta_deg))
        u, v = x + self.g92[0], y + self.g92[1]
        return c * u - s * v + self.g5x[0], s * u + c * v + self.g5x[1]

    def program(self, mx: float, my: float) -> tuple[float, float]:
        c, s = math.cos(math.radians(self.theta_deg)), math.sin(math.radians(self.theta_deg))
        u, v = mx - self.g5x[0], my - self.g5x[1]
        return c * u + s * v - self.g92[0], -s * u + c * v - self.g92[1]


def home_position(f: Frame, theta_deg: float, machine: Vec6) -> Vec6:
    """The program coordinates of a machine position (G28/G30's home) in frame ``f`` rotated by ``theta_deg``."""
    off = f.total_offset_mm
    p = [machine[i] - off[i] - (f.tool_length_mm if i == 2 else 0.0) for i in range(6)]
    if theta_deg:
        p[0], p[1] = Placement.of_frame(f, theta_deg).program(machine[0], machine[1])
    return (p[0], p[1], p[2], p[3], p[4], p[5])
