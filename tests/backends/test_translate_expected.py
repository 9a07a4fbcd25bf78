"""Hand-checked translations: a G83 drilling job, a compensated contour, a macro bolt
circle and an inch program, in every target (``tests/translate/expected``).

Each expected file was read against the source program and the target's rules (see
``docs/translation.md``, "Worked examples"); ``UPDATE_GOLDEN=1`` rewrites them, and a
human reads the diff.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from cncc.dialects import available
from tests.backends.test_translate_roundtrip import DATA, translate

PROGRAMS = ["drill_g83", "comp_contour", "bolt_circle_macro", "inch"]
EXPECTED = DATA / "expected"
CASES = [(p, t) for p in PROGRAMS for t in available() if (EXPECTED / f"{p}.{t}.nc").exists()
         or os.environ.get("UPDATE_GOLDEN")]


def test_every_program_has_expected_output_for_syntec_szgh_fanuc_and_grbl() -> None:
    for p in PROGRAMS:
        for t in ("syntec", "szgh", "fanuc", "grbl"):
            if t in available():
                assert (EXPECTED / f"{p}.{t}.nc").exists(), f"{p}.{t}.nc"


@pytest.mark.parametrize(("program", "target"), CASES, ids=[f"{p}-{t}" for p, t in CASES])
def test_translation_matches_the_checked_output(program: str, target: str) -> None:
    got = translate((DATA / "corpus" / "syntec" / f"{program}.nc").read_text(), "syntec", target)
    path: Path = EXPECTED / f"{program}.{target}.nc"
    if os.environ.get("UPDATE_GOLDEN"):
        path.write_text(got)
    assert got == path.read_text()
