"""blend: tolerances resolved, exact stops before commands that stop the path."""

from __future__ import annotations

from cncc.diagnostics import DiagnosticSink
from cncc.ir.commands import Coolant, CoolantState, Linear, PathMode
from cncc.ir.frame import IDENTITY_FRAME
from cncc.machines import load_machine
from cncc.passes import PassContext
from cncc.passes.blend import Blend
from cncc.source import NO_SPAN
from tests.passes._motion import dwell, line


def _run(cmds: list, machine_name: str = "generic-mill", **opts: object) -> list:  # type: ignore[type-arg]
    ctx = PassContext(DiagnosticSink(), machine=load_machine(machine_name))
    return list(Blend(**opts).run(cmds, ctx))  # type: ignore[arg-type]


def test_tolerance_and_stop_before_dwell() -> None:
    out = _run([line((0, 0), (10, 0)), line((10, 0), (10, 10)), dwell(1), line((10, 10), (0, 10))])
    modes = [c.motion.mode for c in out if isinstance(c, Linear)]
    assert modes == [PathMode.CONTINUOUS, PathMode.EXACT_STOP, PathMode.CONTINUOUS]
    assert all(c.motion.blend_tolerance_mm == 0.01 for c in out if isinstance(c, Linear))
    assert len(out) == 4


def test_mst_stops_only_on_szgh() -> None:
    cool = Coolant(NO_SPAN, IDENTITY_FRAME, CoolantState.FLOOD)
    cmds = [line((0, 0), (10, 0)), cool, line((10, 0), (10, 10))]
    generic = [c for c in _run(cmds) if isinstance(c, Linear)]
    szgh = [c for c in _run(cmds, "szgh-990mdb") if isinstance(c, Linear)]
    assert generic[0].motion.mode is PathMode.CONTINUOUS
    assert szgh[0].motion.mode is PathMode.EXACT_STOP


def test_options() -> None:
    out = _run([line((0, 0), (10, 0)), line((10, 0), (10, 10))], tolerance_mm=0.05, exact_stop=True)
    assert all(c.motion.mode is PathMode.EXACT_STOP and c.motion.blend_tolerance_mm == 0.05 for c in out)
