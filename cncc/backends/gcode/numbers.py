"""Number words for emitted G-code: quantised to the output precision, always with a point.

Lengths are quantised to integer counts of the output resolution first
(:func:`quantize`), so that differences (arc centre offsets) are computed exactly
from the written numbers and re-parse to the written centre.
"""

from __future__ import annotations

import math

LARGEST = 1e18  # counts: far beyond any machine, small enough for exact integers


def quantize(value: float, decimals: int) -> int:
    """``value`` in counts of 10**-decimals (round half away from zero)."""
    scaled = value * 10**decimals
    if not math.isfinite(scaled):  # bad input was diagnosed upstream; never raise here
        scaled = 0.0 if math.isnan(scaled) else math.copysign(LARGEST, scaled)
    q = int(min(abs(scaled), LARGEST) + 0.5)
    return -q if scaled < 0 else q


def counts_text(counts: int, decimals: int) -> str:
    """``5500, 3`` -> ``"5.5"``; ``5000, 3`` -> ``"5."``; always a point, no ``-0``."""
    sign = "-" if counts < 0 else ""
    whole, frac = divmod(abs(counts), 10**decimals)
    digits = f"{frac:0{decimals}d}".rstrip("0") if decimals else ""
    if whole == 0 and not digits:
        return "0."
    return f"{sign}{whole}.{digits}"


def fixed(value: float, decimals: int) -> str:
    """``value`` rounded to ``decimals`` with a point (``1.5``, ``2.``, ``0.``)."""
    return counts_text(quantize(value, decimals), decimals)


def integer(value: float) -> str:
    return str(round(value))
