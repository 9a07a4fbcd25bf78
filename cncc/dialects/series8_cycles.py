"""The cycle kinds only the SERIES 8 dialect has (its tables' ``cycle`` names; spec series8.md 4.14).

They are not core IR: the core enum :class:`cncc.ir.CycleKind` holds the kinds every dialect
may use.  The SERIES 8 front end (``cncc/frontend/series8/``) makes ``Cycle`` commands of these
kinds and ``cncc/passes/series8_cycles.py`` expands them; both import this module (the data
layer under both), and so the IR text reader knows them (docs/ir.md).
"""

from __future__ import annotations

from cncc.ir import CycleKindBase


class Series8CycleKind(CycleKindBase):
    """SERIES 8's own cycles (docs/dialects-notes.md; sequences in cncc/passes/series8_cycles.py)."""

    PECK_FIRST = "peck_first"  # G83: first stroke to the level I, then pecks of J, back to R after each
    BORE_DWELL_STOP_OUT = "bore_dwell_stop_out"  # G86: dwell, spindle stop, feed out to R
    BORE_DWELL_STOP_RAPID_OUT = "bore_dwell_stop_rapid_out"  # G86 read as its title says (rapid out)
    CASE_BORE = "case_bore"  # G87: rapid to R, feed to Z and stay at depth
    BORE_ORIENT_OUT = "bore_orient_out"  # G88: dwell, orient, shift I J, feed out, shift back
    BORE_ORIENT_RAPID_OUT = "bore_orient_rapid_out"  # G88 read as its title says (rapid out)
    BACK_BORE_RETURN = "back_bore_return"  # G89: back bore that feeds back down to R before leaving
