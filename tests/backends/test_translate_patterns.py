"""Hole patterns (G134-G137.1) kept as pattern blocks when the target has the same codes.

The manual's pattern examples (G91, integer angles in 0.001 deg) and the corpus program
are translated SYNTEC -> SYNTEC: the output keeps each pattern as one block and compiles
to the source's motion.  Patterns the target would compute differently (another hole
order, an origin the output cannot write exactly) and targets without the codes get
the holes one by one with note N0807.
"""

from __future__ import annotations

import re

import pytest

from cncc.api import compile_text
from tests.backends.test_translate_roundtrip import TABLES, check

MANUAL = """G90 G17 G71 G94
G00 X0 Y0 Z20.
G91 G81 Z-10.0 R5.0 K0 F200
G134 X200.0 Y100.0 I100.0 J20.0 K6
G90 G80 G00 X0 Y0
G91 G81 Z-10.0 R5.0 K0 F100
G135 X200.0 Y100.0 I100.0 J30.0 K5
G90 G80 G00 X0 Y0
G91 G81 Z-10.0 R5.0 K0 F100
G136 X300.0 Y100.0 I300.0 J10.0 P15000 K6
G90 G80 G00 X0 Y0
G91 G81 Z-10.0 R5.0 K0 F20
G137.1 X300.0 Y-100.0 I50.0 P10 J100.0 K8
G90 G80
G00 Z50.
M02
"""


MIXED = """G90 G17 G71 G94
G00 X-80. Y0. Z20.
G81 Z-20. R2. F1000. K0
G134 X0 Y0 I75. J30. K-6
G99 G83 Z-10. R1. Q3. K0
G136 X10. Y10. I30. J10. P-20. K5
G137.1 X60. Y-60. I20. J-20. P3 K3
G80
G00 Z50.
M02
"""


def _patterns(out: str) -> list[str]:
    return re.findall(r"^(G13[4-7](?:\.1)?)\b", out, flags=re.M)


def test_manual_examples_keep_their_pattern_blocks() -> None:
    out = check(MANUAL, "syntec", "syntec")
    assert _patterns(out) == ["G134", "G135", "G136", "G137.1"]
    assert "P15." in out  # P15000 (0.001 deg) is written as 15 degrees with a point


def test_mixed_patterns_keep_blocks_and_cycle_data() -> None:
    out = check(MIXED, "syntec", "syntec")
    assert _patterns(out) == ["G134", "G136", "G137.1"]
    assert "K0" in out and "G99 G83" in out
    # one line per written block: no hole lists between the pattern blocks
    assert len([ln for ln in out.splitlines() if ln.startswith(("X", "Y"))]) == 0


def _notes(text: str, target: str, **opts: object) -> tuple[str, list[str]]:
    r = compile_text(text, dialect="syntec", emit="gcode", target=target, **TABLES, **opts)  # type: ignore[arg-type]
    return r.output, [d.code for d in r.sink]


@pytest.mark.parametrize("target", ["fanuc", "szgh"])
def test_targets_without_pattern_codes_get_holes(target: str) -> None:
    out = check(MIXED, "syntec", target)
    assert not _patterns(out)
    assert "N0807" in _notes(MIXED, target)[1]


def test_other_hole_order_is_written_as_holes() -> None:
    text = MIXED.replace("G134", "(G134)").replace("G136", "(G136)")
    out, codes = _notes(text, "syntec", target_options={"g137_order": "raster"})
    assert "G137.1" not in out and "N0807" in codes
    # the rows of a raster grid all start at the first column: the fourth hole is X60. Y-80.
    assert re.search(r"^X60\. Y-80\.", out, flags=re.M)


def test_origin_the_output_cannot_write_is_written_as_holes() -> None:
    text = MIXED.replace("G134 X0 Y0", "G134 X0.0004 Y0")
    out = check(text, "syntec", "syntec")
    assert _patterns(out) == ["G136", "G137.1"]
    assert "N0807" in _notes(text, "syntec")[1]
