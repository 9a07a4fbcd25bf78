"""Issue 25: -O2 with verify accepts valid generated programs of every path kind, and no
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


@pytest.mark.parametrize("machine", ["generic-mill", "szgh-990mdb"])
@pytest.mark.parametrize("kind", sorted(KINDS))
def test_o2_verifies_every_path_kind(kind: str, machine: str, tmp_path: Path,
                                     capsys: pytest.CaptureFixture[str]) -> None:
    src = tmp_path / "part.nc"
    src.write_text(KINDS[kind](120), encoding="ascii")
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        rc = main([str(src), "-m", machine, "--emit=timing", "--report-format=json", "-o", str(tmp_path / "t.json")])
    err = capsys.readouterr().err
    assert "E061" not in err and "RuntimeWarning" not in err
    assert rc == 0, err
