"""The planning stage of the machine-coordinate backends: commands to a :class:`cncc.ir.Trajectory`.

:func:`plan_trajectory` runs the builder's plan stage (:func:`cncc.pipeline.builder.plan_passes`:
blend, plan at one ``-O`` level, verify) over a command list; the timing report runs it once per
column, the pulse backend once, the language server for its inlay hints.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from cncc.diagnostics import DiagnosticSink
from cncc.ir import Command
from cncc.ir.machine import MachineModel

if TYPE_CHECKING:
    from cncc.pipeline.manager import PassManager


def plan_trajectory(cmds: list[Command], machine: MachineModel, level: int, sink: DiagnosticSink,
                    verify: bool = True, soft_limits: bool = False, quiet: bool = False,
                    manager: PassManager | None = None, spec: str = "") -> tuple[Any, str]:
    """(Trajectory, how it was made): the planning stage of the pipeline -- blend, plan at
    ``level`` (-O0: the nominal estimate), verify (``verify``, -O1..-O3; its violations
    become diagnostics) -- as :func:`cncc.pipeline.builder.plan_passes` makes it.

    ``cmds`` are in machine coordinates (``to-machine`` ran in ``path_passes``); blend keeps
    their order and count, so ``Trajectory.cmd_index`` still indexes ``cmds``.  Soft limits
    are checked only when the work offsets are known (``soft_limits``: ``--offsets`` given):
    with the default zero offsets, program coordinates are no machine positions.
    ``manager``: the compilation's pass manager; ``spec``: its ``-p`` text.
    """
    from cncc.passes import PassContext
    from cncc.pipeline import PipelineConfig
    from cncc.pipeline.builder import plan_passes
    from cncc.pipeline.manager import PassManager

    pm = manager if manager is not None else PassManager()
    passes = plan_passes(PipelineConfig(machine_coords=True, spec=spec), level, verify=verify,
                         soft_limits=soft_limits, quiet=quiet)
    ctx = PassContext(sink=sink, machine=machine)
    for _ in pm.run(passes, cmds, ctx, stage="plan", label=f"-O{level} on {machine.name}"):
        pass
    if ctx.trajectory is None:  # a -p plan stage without plan: the nominal estimate, for the report
        from cncc.backends.nominal import nominal_trajectory

        return nominal_trajectory(cmds, machine), "nominal: length / feed (no plan pass in -p)"
    return ctx.trajectory, ctx.plan_how
