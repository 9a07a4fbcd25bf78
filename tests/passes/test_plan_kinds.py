"""Issue 25: -O1 and -O2 with verify accept valid generated programs of every path kind, and no
numpy RuntimeWarning escapes the planner."""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

import pytest

from cncc.cli import main

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench"))
from pathgen import KINDS  # noqa: E402


@pytest.mark.parametrize("level", [1, 2])
@pytest.mark.parametrize("machine", ["generic-mill", "szgh-990mdb"])
@pytest.mark.parametrize("kind", sorted(KINDS))
def test_o1_and_o2_verify_every_path_kind(kind: str, machine: str, level: int, tmp_path: Path,
                                          capsys: pytest.CaptureFixture[str]) -> None:
    # -O1 on the SZGH stops at every G00 the way the manual's stop goes (a step down from the take-off
    # speed to rest, a step up from rest to it): E0617 on the mixed part before verify allowed it
    src = tmp_path / "part.nc"
    src.write_text(KINDS[kind](120), encoding="ascii")
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        rc = main([str(src), "-m", machine, f"-O{level}", "--emit=timing", "--report-format=json",
                   "-o", str(tmp_path / "t.json")])
    err = capsys.readouterr().err
    assert "E061" not in err and "RuntimeWarning" not in err
    assert rc == 0, err


def test_o3_keeps_every_axis_within_its_limits(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # -O3 judged before it is kept (issue 26): an optimised window, else its start, else
    # -O2's S-curve, whichever keeps the per-axis jerk and acceleration within the limits
    import numpy as np

    from cncc.ir.trajectory import Trajectory  # noqa: F401  (the planner's output type)
    from cncc.machines import load_machine
    from cncc.passes.plan import _rows_within
    from cncc.passes.planning.emit import Rows
    from cncc.passes.planning.limits import axis_limits

    limits = axis_limits(load_machine("generic-mill"))
    z = np.zeros((1, 6))
    ok = Rows(np.zeros(1), np.ones(1), z, z, z, z, np.zeros(1, np.int64), np.zeros(1, np.int8))
    assert _rows_within(ok, limits)
    jerky = np.zeros((1, 6))
    jerky[0, 0] = 1.01 * limits.jmax_mm_s3[0]  # injected: 1 % over the X jerk limit
    assert not _rows_within(Rows(np.zeros(1), np.full(1, 1e-3), z, z, z, jerky, ok.cmd, ok.limit), limits)
    src = tmp_path / "walk.nc"
    src.write_text(KINDS["random walk"](30), encoding="ascii")
    rc = main([str(src), "-O3", "--emit=timing", "--report-format=json", "-o", str(tmp_path / "t.json")])
    err = capsys.readouterr().err
    assert "E061" not in err
    assert rc == 0, err
