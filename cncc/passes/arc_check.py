"""``arc-check``: start and end radius of every arc must agree within tolerance.

The tolerances follow LinuxCNC's rule: the difference between the start and end
radius may be at most ``abs_tol_mm`` (default 0.01 mm x sqrt(2) x 2) or
``rel_tol`` (default 0.1 %) of the start radius, whichever is larger.  LinuxCNC has
its own absolute tolerance for arcs programmed in inches (``abs_tol_inch_mm``) and
rejects a difference above ``max_abs_factor`` (100) absolute tolerances whatever the
radius.  With
``repair=True`` the centre is moved onto the perpendicular bisector of the chord,
keeping the start radius (or the mean radius when the chord is longer), and a
warning says how far it moved; otherwise the arc is an error.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from typing import ClassVar

from cncc import diagnostics as dg
from cncc.dialects import Dialect
from cncc.ir import Arc, Command, Units, Vec6
from cncc.ir.batch import ARC, Item, MoveBatch
from cncc.ir.frame import MM_PER_INCH
from cncc.passes import Pass, PassContext, register


@register
@dataclass(frozen=True, kw_only=True)
class ArcCheck(Pass):
    """Radius mismatch check (and optional repair) for arcs."""

    name: ClassVar[str] = "arc-check"
    abs_tol_mm: float = 0.01 * math.sqrt(2.0) * 2.0
    rel_tol: float = 0.001
    repair: bool = False
    abs_tol_inch_mm: float = 0.0  # > 0: the absolute tolerance of arcs programmed in inches (mm)
    max_abs_factor: float = 0.0  # > 0: a difference above this many absolute tolerances is an error anyway

    @classmethod
    def for_dialect(cls, dialect: Dialect, repair: bool = False) -> ArcCheck:
        """The check with the dialect's tolerances (``arc_radius_tolerance_mm``/``_rel``/``_inch``,
        ``arc_radius_error_factor``); the absolute one is never below the default, or below
        ``arc_radius_tolerance_floor_mm`` where the dialect gives one (LinuxCNC's INI file may lower it)."""
        floor = float(dialect.option("arc_radius_tolerance_floor_mm", cls.abs_tol_mm))
        return cls(abs_tol_mm=max(float(dialect.option("arc_radius_tolerance_mm", cls.abs_tol_mm)), floor),
                   rel_tol=float(dialect.option("arc_radius_tolerance_rel", cls.rel_tol)), repair=repair,
                   abs_tol_inch_mm=float(dialect.option("arc_radius_tolerance_inch", 0.0)) * MM_PER_INCH,
                   max_abs_factor=float(dialect.option("arc_radius_error_factor", 0.0)))

    def run(self, cmds: Iterable[Command], ctx: PassContext) -> Iterator[Command]:
        for c in cmds:
            if isinstance(c, Arc):
                fixed = self._check(c, ctx)
                if fixed is None:
                    continue
                yield fixed
            else:
                yield c

    def run_items(self, items: Iterable[Item], ctx: PassContext) -> Iterator[Item]:
        """A batch whose arcs all pass clearly (a margin above the rounding of the vectorised radii)
        passes whole; any other goes command by command."""
        for x in items:
            if isinstance(x, MoveBatch):
                if self._clearly_fine(x):
                    yield x
                else:
                    yield from self.run(x.commands(), ctx)
            else:
                yield from self.run((x,), ctx)

    def _clearly_fine(self, b: MoveBatch) -> bool:
        import numpy as np

        arcs = np.flatnonzero(b.kind == ARC)
        if len(arcs) == 0:
            return True
        i, j = b.plane.first, b.plane.second
        start, end, center = b.starts()[arcs], b.end[arcs], b.center[arcs]
        r0 = np.hypot(start[:, i] - center[:, i], start[:, j] - center[:, j])
        r1 = np.hypot(end[:, i] - center[:, i], end[:, j] - center[:, j])
        diff = np.abs(r1 - r0)
        tol = self.abs_tol_inch_mm if self.abs_tol_inch_mm > 0 and b.frame.units is Units.INCH else self.abs_tol_mm
        margin = 1e-9 + 1e-12 * np.maximum(r0, r1)  # math.hypot and np.hypot may differ in the last bits
        fine = diff + margin < np.maximum(tol, self.rel_tol * r0) + 1e-9
        if self.max_abs_factor > 0:
            fine &= diff + margin < self.max_abs_factor * tol
        return bool(fine.all())

    def _check(self, c: Arc, ctx: PassContext) -> Arc | None:
        p = c.plane
        i, j = p.first, p.second
        r0 = math.hypot(c.start[i] - c.center[i], c.start[j] - c.center[j])
        r1 = math.hypot(c.end[i] - c.center[i], c.end[j] - c.center[j])
        diff = abs(r1 - r0)
        tol = self.abs_tol_inch_mm if self.abs_tol_inch_mm > 0 and c.frame.units is Units.INCH else self.abs_tol_mm
        capped = self.max_abs_factor > 0 and diff > self.max_abs_factor * tol
        if diff <= max(tol, self.rel_tol * r0) + 1e-9 and not capped:
            return c
        if not self.repair:
            ctx.sink.emit(dg.ARC_RADIUS, c.span,
                          f"arc radius at the end ({r1:.4f} mm) differs from the start ({r0:.4f} mm) by {diff:.4f} mm")
            return None
        center = _repaired_center(c, r0)
        moved = math.hypot(center[i] - c.center[i], center[j] - c.center[j])
        ctx.sink.emit(dg.ARC_REPAIRED, c.span,
                      f"arc radii differed by {diff:.4f} mm; centre moved by {moved:.4f} mm to "
                      f"({center[i]:.4f}, {center[j]:.4f})")
        return Arc(c.span, c.frame, c.start, c.end, center, c.turns, c.plane, c.feed_mm_min, c.motion, c.origin)


def _repaired_center(c: Arc, radius: float) -> Vec6:
    """Centre on the chord's bisector, on the same side as the programmed one."""
    p = c.plane
    i, j = p.first, p.second
    x0, y0, x1, y1 = c.start[i], c.start[j], c.end[i], c.end[j]
    dx, dy = x1 - x0, y1 - y0
    chord = math.hypot(dx, dy)
    mx, my = (x0 + x1) / 2, (y0 + y1) / 2
    if chord < 1e-12:
        return c.center
    half = chord / 2
    h = math.sqrt(max(radius * radius - half * half, 0.0))
    nx, ny = -dy / chord, dx / chord
    side = 1.0 if (c.center[i] - mx) * nx + (c.center[j] - my) * ny >= 0 else -1.0
    out = list(c.center)
    out[i], out[j] = mx + side * h * nx, my + side * h * ny
    return (out[0], out[1], out[2], out[3], out[4], out[5])
