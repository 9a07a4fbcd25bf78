"""Numbers a controller refuses: exponent notation and values too large to be real.

Consumes one physical line (and the dialect's comment syntax); produces the spans of
the numbers no controller reads, so the parser can report them and skip the block
instead of reading ``X1e400`` as ``X1`` (the ``e400`` as another word) or a 400-digit
``X`` as infinity:

* **exponent notation** ``1e3``, ``2.5E-4``, ``1e+5``: a digit or point followed by a
  lower-case ``e`` and digits, or by ``E`` and a signed exponent.  ``1E5`` with an
  upper-case ``E`` and no sign is the word ``E5`` in dialects that have an E address
  (``G01X1.E5``, compact CAM output); in the others it is exponent notation too.
* **overflow**: 13 or more integer digits (leading zeros aside), i.e. 10^12 mm or more,
  which no controller's word format holds and which would reach the planner as
  infinity or as numbers whose squares overflow.

Comments, quoted strings and ``<names>`` are masked first, so ``(1e5 parts)`` is text.
"""

from __future__ import annotations

import functools
import re
from collections.abc import Iterator

_CANDIDATE = re.compile(r"[\d.][eE]|\d{13}")
_OVERFLOW = re.compile(r"(?<![\d.])0*[1-9]\d{12,}")


@functools.cache
def _exponent_re(e_is_address: bool) -> re.Pattern[str]:
    upper = r"E[+-]\d" if e_is_address else r"E[+-]?\d"
    return re.compile(rf"(?<![\d.])(?:\d+\.?\d*|\.\d+)(?:e[+-]?\d|{upper})\d*")


@functools.cache
def _mask_re(comments: tuple[str, ...], block_end: str) -> re.Pattern[str]:
    parts = [r'"[^"]*"?', r"<[^>]*>?"]
    if "paren" in comments:
        parts.append(r"\([^)]*\)?")
    if "slash" in comments:
        parts.append(r"//.*")
    if "semi" in comments and block_end != ";":
        parts.append(r";.*")
    return re.compile("|".join(parts))


def refused_numbers(line: str, comments: tuple[str, ...], block_end: str,
                    e_is_address: bool) -> Iterator[tuple[int, int, str]]:
    """(start, end, kind) of each refused number in ``line``; kind is "exponent" or "overflow"."""
    if _CANDIDATE.search(line) is None:  # the common case: one search, nothing to do
        return
    masked = _mask_re(comments, block_end).sub(lambda m: " " * len(m.group(0)), line)
    for m in _exponent_re(e_is_address).finditer(masked):
        yield m.start(), m.end(), "exponent"
    for m in _OVERFLOW.finditer(masked):
        yield m.start(), m.end(), "overflow"


__all__ = ["refused_numbers"]
