"""Small hand-written SVG helpers for the HTML report: a plot frame with axes and ticks.

No plotting library: the page must open offline and the module must import fast.
Coordinates given to :class:`Frame` are data units; it maps them to pixels.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from html import escape

LIMIT_COLORS = {
    "none": "#6d6d1f", "feed": "#1f77b4", "accel": "#ff7f0e", "jerk": "#d62728", "corner": "#9467bd",
    "axis_velocity": "#8c564b", "step_rate": "#e377c2", "rapid": "#7f7f7f", "centripetal": "#2ca02c",
}
CATEGORY_COLORS = {
    "rapid": "#9e9e9e", "feed": "#1f77b4", "arc": "#6baed6", "dwell": "#d9a400", "tool_change": "#00a6a6",
    "spindle": "#9edae5", "wait": "#7b4173", "reversal": "#637939",
}
"""Event colours differ from every limit colour: both share the legend of the speed plot."""
TOOL_COLORS = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#17becf", "#ff7f0e")
"""Feed moves, one colour per tool (in the order the tools appear); no yellow (unreadable on white)."""
RAPID_COLOR = "#6f6f6f"
HOLE_COLOR = "#111111"
SELECTED_COLOR = "#ff9800"
SPEED_COLORS = ("#440154", "#46327e", "#365c8d", "#277f8e", "#1fa187", "#4ac16d", "#a0da39", "#fde725")
"""Slow to fast (viridis)."""


def nice_ticks(lo: float, hi: float, count: int = 6) -> list[float]:
    """Round tick values covering ``[lo, hi]``."""
    if not math.isfinite(lo) or not math.isfinite(hi) or hi <= lo:
        return [lo]
    raw = (hi - lo) / max(count - 1, 1)
    mag = 10 ** math.floor(math.log10(raw))
    step = next(m * mag for m in (1, 2, 2.5, 5, 10) if m * mag >= raw)
    first = math.ceil(lo / step - 1e-9) * step
    ticks = []
    k = 0
    while first + k * step <= hi + step * 1e-9:
        ticks.append(first + k * step)
        k += 1
    return ticks


def fmt_num(v: float) -> str:
    return f"{v:.6g}" if abs(v) < 1e6 else f"{v:.3e}"


@dataclass(slots=True)
class Frame:
    """A plot area of ``width`` x ``height`` pixels showing ``[x0, x1] x [y0, y1]``."""

    width: int
    height: int
    x0: float
    x1: float
    y0: float
    y1: float
    left: int = 64
    right: int = 16
    top: int = 16
    bottom: int = 40

    def __post_init__(self) -> None:
        if self.x1 <= self.x0:
            self.x1 = self.x0 + 1.0
        if self.y1 <= self.y0:
            self.y1 = self.y0 + 1.0

    def px(self, x: float) -> float:
        w = self.width - self.left - self.right
        return self.left + (x - self.x0) / (self.x1 - self.x0) * w

    def py(self, y: float) -> float:
        h = self.height - self.top - self.bottom
        return self.top + (1.0 - (y - self.y0) / (self.y1 - self.y0)) * h

    def axes(self, xlabel: str, ylabel: str, yticks: bool = True) -> str:
        out = [f'<rect x="{self.left}" y="{self.top}" width="{self.width - self.left - self.right}" '
               f'height="{self.height - self.top - self.bottom}" fill="#fff" stroke="#999"/>']
        yb = self.height - self.bottom
        for t in nice_ticks(self.x0, self.x1):
            x = self.px(t)
            out.append(f'<line x1="{x:.1f}" y1="{self.top}" x2="{x:.1f}" y2="{yb}" stroke="#eee"/>'
                       f'<text x="{x:.1f}" y="{yb + 14}" text-anchor="middle">{fmt_num(t)}</text>')
        for t in nice_ticks(self.y0, self.y1) if yticks else []:
            y = self.py(t)
            out.append(f'<line x1="{self.left}" y1="{y:.1f}" x2="{self.width - self.right}" y2="{y:.1f}" '
                       f'stroke="#eee"/><text x="{self.left - 4}" y="{y + 4:.1f}" '
                       f'text-anchor="end">{fmt_num(t)}</text>')
        out.append(f'<text x="{(self.left + self.width - self.right) / 2:.1f}" y="{self.height - 6}" '
                   f'text-anchor="middle">{escape(xlabel)}</text>')
        out.append(f'<text transform="translate(14 {(self.top + yb) / 2:.1f}) rotate(-90)" '
                   f'text-anchor="middle">{escape(ylabel)}</text>')
        return "".join(out)


def svg(width: int, height: int, body: str, label: str) -> str:
    return (f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
            f'viewBox="0 0 {width} {height}" role="img" aria-label="{escape(label)}" '
            f'font-family="sans-serif" font-size="11">{body}</svg>')


def legend(items: list[tuple[str, str]], x: float, y: float, dy: float = 14) -> str:
    out = []
    for k, (name, color) in enumerate(items):
        yy = y + k * dy
        out.append(f'<rect x="{x:.1f}" y="{yy - 8:.1f}" width="10" height="10" fill="{color}"/>'
                   f'<text x="{x + 14:.1f}" y="{yy + 1:.1f}">{escape(name)}</text>')
    return "".join(out)
