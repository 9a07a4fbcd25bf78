"""The hand-written programs of tests/oracle/cases.py against LinuxCNC 2.9's rs274."""

from __future__ import annotations

import pytest

from tests.oracle.cases import CASES
from tests.oracle.harness import compare, rs274_path

pytestmark = pytest.mark.skipif(rs274_path() is None, reason="LinuxCNC's rs274 is not installed "
                                "(run scripts/ensure-rs274.sh; it needs apt-get and dpkg)")

# Classes of issue 24 not fixed yet: cncc disagrees with rs274 on these (docs/dialects-notes.md).
OPEN_CASES = frozenset({"dollar_spindle", "m70_m72", "g7_diameter",
                        "probe_g38_2", "polar_words", "tool_not_in_table"})


@pytest.mark.parametrize("name", sorted(CASES))
def test_case_agrees_with_rs274(name: str) -> None:
    case = CASES[name]
    text, table, files = (case, "", {}) if isinstance(case, str) else (*case, {}) if len(case) == 2 else case
    v = compare(text, table, files)
    if name in OPEN_CASES and not v.agree:
        pytest.xfail(v.reason)
    assert v.agree, f"{name}: {v.reason}"
