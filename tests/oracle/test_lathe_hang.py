"""LinuxCNC 2.9.0's endless G71 loop (docs/dialects-notes.md, lathe cycles; tests/oracle/allow.toml).

rs274 2.9.0 never finishes these programs (found by generating profiles with arcs); cncc writes the moves rs274
writes before it hangs and then stops with E0480.  Each costs the harness's rs274 time-out, so they are slow tests.
"""

from __future__ import annotations

import pytest

from tests.oracle.harness import TIMED_OUT, compare, rs274_path
from tests.oracle.verdicts import allowances

pytestmark = [pytest.mark.slow, pytest.mark.skipif(rs274_path() is None, reason="LinuxCNC's rs274 is not installed")]

HANGS = {
    "arcs_down_and_up": ("G21 G18 F100\no100 sub\nG1 X2 Z0\nG2 X0 Z-2 R2\nG3 X3 Z-5 R3\nG2 X1 Z-7 R2\no100 endsub\n"
                         "G0 X3 Z2\nG71 Q100 D0.5 I0.5\nM2\n"),
    "pockets_only": ("G21 G18 F100\no100 sub\nG1 X2 Z0\nG1 X3\nG3 X2 Z-1 R1\nG2 X0 Z-3 R2\no100 endsub\n"
                     "G0 X3 Z2\nG71.2 Q100 D0.2 I0.5\nM2\n"),
    "face_then_arc": ("G21 G18 F100\no100 sub\nG1 X0 Z0\nG1 X1\nG3 X3 Z-2 R2\no100 endsub\n"
                      "G0 X4 Z1\nG71 Q100 D1 I0.5\nM2\n"),
}


@pytest.mark.parametrize("name", sorted(HANGS))
def test_rs274_hangs_and_cncc_stops(name: str) -> None:
    text = HANGS[name]
    v = compare(text)
    assert v.oracle is not None and v.oracle.error == TIMED_OUT, v.reason
    assert v.cncc is not None and v.cncc.codes == ("E0480",)
    assert any(a.covers("lathe_roughing", text, v.reason) for a in allowances()), v.reason
