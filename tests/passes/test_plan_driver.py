"""The driver runs blend, plan and verify for --emit=timing and --emit=pulses."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from cncc import diagnostics as dg
from cncc.api import compile_text
from cncc.ir.trajectory import Trajectory

PROGRAM = "G90 G01 X10. Y5. F1200\nG01 X20.\nG01 Y15.\n"


def _codes(text: str, **opts: Any) -> set[str]:
    r = compile_text(text, emit="timing", **opts)
    return {d.code for d in r.sink}


@pytest.mark.parametrize("level", [0, 1, 2, 3])
def test_tiny_feed_is_a_diagnostic_at_every_level(level: int) -> None:
    codes = _codes("G01 X1. F0.000000000000000000001\n", opt_level=level)
    assert level == 0 or dg.FEED_TOO_SMALL in codes
    assert not {c for c in codes if c.startswith("E061")}  # the plan itself verifies


def test_verify_runs_after_plan(monkeypatch: pytest.MonkeyPatch) -> None:
    import cncc.passes.plan as plan_module

    real = plan_module.plan_commands

    def too_fast(*args: Any, **kwargs: Any) -> Trajectory:
        t = real(*args, **kwargs)
        return Trajectory(t.t0_s, t.duration_s, t.p0_mm, t.v0_mm_s * 100, t.a0_mm_s2, t.j_mm_s3, t.cmd_index, t.limit)

    assert not {c for c in _codes(PROGRAM) if c.startswith("E061")}
    monkeypatch.setattr(plan_module, "plan_commands", too_fast)
    assert dg.VERIFY_VELOCITY in _codes(PROGRAM)
    assert dg.VERIFY_VELOCITY in {d.code for d in compile_text(PROGRAM, emit="pulses", pulse_format="csv").sink}
    assert dg.VERIFY_VELOCITY not in _codes(PROGRAM, verify=False)  # -fno-verify


def test_planner_sees_machine_coordinates(monkeypatch: pytest.MonkeyPatch) -> None:
    import cncc.passes.plan as plan_module

    seen: list[Any] = []
    real = plan_module.plan_commands

    def spy(cmds: Any, *args: Any, **kwargs: Any) -> Trajectory:
        seen.extend(cmds)
        return real(cmds, *args, **kwargs)

    monkeypatch.setattr(plan_module, "plan_commands", spy)
    _codes("G92 X100. Y100.\nG01 X110. Y100. F1200\n")  # G92: the tool is at machine 0 0
    ends = [c.end for c in seen if hasattr(c, "feed_mm_min")]
    assert ends and np.allclose(ends[-1][:2], (10.0, 0.0))
