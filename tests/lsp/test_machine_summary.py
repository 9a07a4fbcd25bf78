"""Without a work offsets table the soft-limit errors become one warning (issue 20)."""

from __future__ import annotations

from cncc import diagnostics as dg
from cncc.diagnostics import Diagnostic, Severity
from cncc.lsp.machine_check import LIMITS_CAPPED, without_offsets
from cncc.source import Span


def soft(at: int) -> Diagnostic:
    return Diagnostic(dg.SOFT_LIMIT, Severity.ERROR, Span(0, at, at + 5), f"Z reaches 5.000 at {at}")


def test_one_warning_on_the_first_crossing_and_the_other_findings_kept() -> None:
    step = Diagnostic(dg.STEP_RATE, Severity.ERROR, Span(0, 7, 9), "X would step at 30 kHz")
    got = without_offsets([soft(40), soft(10), step, soft(10)], None)
    assert [d.code for d in got] == ["W0775", "E0701"]
    assert got[0].span.start == 10 and "2 move(s)" in got[0].message and "at 10" in got[0].message
    assert "no work offsets table" in got[0].message


def test_a_capped_list_says_more_than_and_drops_the_cap_note() -> None:
    cap = Diagnostic(dg.ANALYSIS_STOPPED, Severity.NOTE, Span(0, 0, 0), f"7 {LIMITS_CAPPED} (the first 3 are)")
    got = without_offsets([soft(1), soft(2), soft(3), cap], "off.toml")
    assert [d.code for d in got] == ["W0775"]
    assert "more than 3 moves" in got[0].message and "'off.toml' cannot be read" in got[0].message
