"""The core handler table is composed by one module (frontend/handler_tables.py) in a
fixed order: whichever front-end module a process imports first, the table holds the
same handlers, and its block hooks run in the same order."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
_PROBE = """
import json, sys
import {first}
from cncc.frontend.handler_tables import core_table
t = core_table()
print(json.dumps({{"hooks": [h.__module__ + "." + h.__qualname__ for h in t.block_hooks],
                   "handlers": sorted(t.handlers), "motions": sorted(t.motions),
                   "wrapped_plane": t.handlers["plane_xy"].__qualname__}}))
"""


def _table_after_importing(first: str) -> dict[str, object]:
    p = subprocess.run([sys.executable, "-c", _PROBE.format(first=first)], cwd=ROOT, capture_output=True,
                       text=True, timeout=120, env={"PYTHONPATH": str(ROOT), "PATH": ""})
    assert p.returncode == 0, p.stderr
    out: dict[str, object] = json.loads(p.stdout)
    return out


@pytest.mark.parametrize("first", ["cncc.frontend.transforms", "cncc.frontend.rs274_curves",
                                   "cncc.frontend.holes", "cncc.frontend.series8.front"])
def test_the_core_table_does_not_depend_on_the_first_import(first: str) -> None:
    assert _table_after_importing(first) == _table_after_importing("cncc.frontend.interp")


def test_the_core_table_holds_every_registering_module() -> None:
    t = _table_after_importing("cncc.frontend.interp")
    hooks = t["hooks"]
    assert hooks == ["cncc.frontend.rs274._absolute_centres", "cncc.frontend.rs274._inverse_time_feed",
                     "cncc.frontend.transforms._lone_words"]
    handlers = t["handlers"]
    assert isinstance(handlers, list)
    # one op of each registering module: ops, cycles, holes, mcodes, rs274, rs274_curves,
    # rs274_sync, saved_points, transforms
    for op in ("rapid", "cycle", "pattern", "aux", "exact_path_mode", "nurbs_begin", "spindle_sync_rs274",
               "save_point", "polar_on"):
        assert op in handlers
    assert t["wrapped_plane"] == "_guard_plane.<locals>.guarded"  # cycles.py's guard is on the shared plane op
