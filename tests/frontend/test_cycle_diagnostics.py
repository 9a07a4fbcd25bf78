"""Bad canned-cycle input is a diagnostic at the offending block, not a wrong path."""

from __future__ import annotations

import pytest

from cncc.api import compile_text
from tests.helpers import calls

START = "F100. S500 M03;\nG00 X0. Y0. Z10.;\n"  # lines 1-2; the cycle block is line 3


def diagnose(text: str, **options: object) -> tuple[dict[str, int], list[str]]:
    """{code: line} of the diagnostics, and the canon trace lines."""
    r = compile_text(START + text, dialect_options=options) if options else compile_text(START + text)
    full = START + text
    found = {d.code: full.count("\n", 0, d.span.start) + 1 for d in r.sink}
    return found, r.output.splitlines()


def feeds(lines: list[str]) -> list[list[float]]:
    return [a for _, a in calls(lines, "STRAIGHT_FEED")]


@pytest.mark.parametrize(("block", "code"), [
    ("G81 X5. Z-10.;", "E0401"),  # no R
    ("G81 X5. R-5.;", "E0402"),  # no Z
    ("G81 X5. Z-10. R-20.;", "E0403"),  # R below the bottom
    ("G81 X5. Z-10. R-10.;", "E0403"),  # zero depth
    ("G87 X5. Z-40. R-30. Q5.;", "E0403"),  # back bore: R must be below the top
    ("G83 X5. Z-10. R-5.;", "E0404"),  # no Q
    ("G73 X5. Z-10. R-5. Q0;", "E0404"),  # Q = 0
    ("G81 X5. Z-10. R-5. K10000;", "E0406"),
    ("G81 X5. Z-10. R-5. K2.5;", "E0406"),
    ("G81 X5. Z-10. R-5. K-1;", "E0406"),
])
def test_bad_cycle_block(block: str, code: str) -> None:
    found, lines = diagnose(block + "\nG80;\n")
    assert found.get(code) == 3, found
    assert feeds(lines) == []  # no path from a bad block


def test_negative_q_warns_and_uses_abs() -> None:
    found, lines = diagnose("G83 X5. Z-10. R-5. Q-3.;\nG80;\n", cycle_g83_clearance_mm=0.5)
    assert found.get("W0405") == 3
    assert [f[2] for f in feeds(lines)] == [-8.0, -10.0]


def test_plane_change_with_cycle_active() -> None:
    found, lines = diagnose("G99 G81 X5. Z-10. R-5.;\nG18;\nX15.;\nG80;\n")
    assert found.get("E0407") == 4
    assert [f[0] for f in feeds(lines)] == [5.0, 15.0]  # the plane stayed XY: hole 2 still drills along Z


def test_plane_change_with_cancel_in_the_same_block_is_fine() -> None:
    found, _ = diagnose("G81 X5. Z-10. R-5.;\nG80 G18;\n")
    assert "E0407" not in found


def test_pattern_without_cycle() -> None:
    found, lines = diagnose("G134 X0 Y0 I10. J0 K4;\n")
    assert found.get("E0408") == 3
    assert feeds(lines) == []


@pytest.mark.parametrize("pattern", ["G134 X0 Y0 J0 K4;", "G134 X0 Y0 I10. K0;", "G134 X0 Y0 I-10. K4;",
                                     "G135 X0 Y0 I10. J0;", "G136 X0 Y0 I10. J0 K3;",
                                     "G137.1 X0 Y0 I10. J10. P0 K2;", "G137.1 X0 Y0 I10. J10. P2.5 K2;"])
def test_pattern_bad_words(pattern: str) -> None:
    found, lines = diagnose("G81 Z-10. R-5. K0;\n" + pattern + "\nG80;\n")
    assert found.get("E0409") == 4
    assert feeds(lines) == []


def test_tapping_without_spindle_speed() -> None:
    r = compile_text("F100.;\nG00 Z10.;\nG84 X5. Z-10. R-5.;\nG80;\n")
    assert "E0412" in [d.code for d in r.sink]


def test_tapping_with_the_wrong_spindle_direction_warns() -> None:
    found, _ = diagnose("M04;\nG84 X5. Z-10. R-5.;\nG80;\n")
    assert found.get("W0414") == 4


def test_shift_direction_out_of_range() -> None:
    found, lines = diagnose("G76 X5. Z-10. R-5. Q2.;\nG80;\n", cycle_shift_direction=7)
    assert found.get("E0413") == 3
    assert feeds(lines) == []


def test_r_in_a_cycle_block_without_axes_is_not_stored() -> None:
    found, lines = diagnose("G99 G81 X5. Z-10. R-5.;\nG81 R-2.;\nX15.;\nG80;\n")
    assert found.get("W0416") == 4
    assert calls(lines, "STRAIGHT_TRAVERSE")[-1][1][:3] == [15.0, 0.0, -5.0]  # still the old R


def test_long_dwell_warns() -> None:
    found, _ = diagnose("G82 X5. Z-10. R-5. P300.;\nG80;\n")
    assert found.get("W0417") == 3


def test_repeats_in_g90_warn() -> None:
    found, lines = diagnose("G81 X5. Z-10. R-5. K2;\nG80;\n")
    assert found.get("W0411") == 3
    assert len(feeds(lines)) == 2
