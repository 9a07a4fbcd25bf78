"""Word values: the decimal-point (least input unit) rule and unit conversion.

Under the LIU rule (SYNTEC, SZGH, Fanuc) a length written without a decimal point
is in least input units (``X5500`` = 5.5 mm), a time in milliseconds and an angle in
0.001 degree.  Dialects with ``decimal_rule = "units"`` (LinuxCNC, grbl) read every
number in the programmed unit.
"""

from __future__ import annotations

from dataclasses import dataclass

from cncc.dialects import Dialect
from cncc.frontend.syntax import Word
from cncc.ir import Units


@dataclass(frozen=True, slots=True)
class WordReader:
    """Converts word values for one dialect and one unit system."""

    liu_rule: bool
    mm_per_unit: float
    liu_length_mm: float
    liu_time_s: float
    liu_angle_deg: float
    kinds: dict[str, str]

    @staticmethod
    def for_dialect(dialect: Dialect, units: Units) -> WordReader:
        liu = dialect.liu
        if units is Units.MM:
            liu_len = liu.get("length_mm", 0.001)
        else:
            liu_len = liu.get("length_inch", 0.0001) * units.mm_per_unit
        return WordReader(
            liu_rule=dialect.decimal_rule == "liu",
            mm_per_unit=units.mm_per_unit,
            liu_length_mm=liu_len,
            liu_time_s=liu.get("time_s", 0.001),
            liu_angle_deg=liu.get("angle_deg", 0.001),
            kinds=dialect.addresses,
        )

    def length_mm(self, w: Word) -> float:
        if self.liu_rule and not w.point:
            return w.value * self.liu_length_mm
        return w.value * self.mm_per_unit

    def angle_deg(self, w: Word) -> float:
        if self.liu_rule and not w.point:
            return w.value * self.liu_angle_deg
        return w.value

    def time_s(self, w: Word) -> float:
        """A time word: seconds with a point, least time units (ms) without."""
        if self.liu_rule and not w.point:
            return w.value * self.liu_time_s
        return w.value

    def axis_value(self, w: Word) -> float:
        """X Y Z U V W in mm; A B C in degrees."""
        if w.letter in "ABC" and self.kinds.get(w.letter) == "angle":
            return self.angle_deg(w)
        return self.length_mm(w)

    def value(self, w: Word, kind: str | None = None) -> float:
        """A word by its kind (per-code kind first, then the dialect's address kind)."""
        k = kind or self.kinds.get(w.letter, "real")
        if k == "length":
            return self.length_mm(w)
        if k == "angle":
            return self.angle_deg(w)
        if k == "time":
            return self.time_s(w)
        if k == "time_ms":
            return w.value * 0.001
        return w.value
