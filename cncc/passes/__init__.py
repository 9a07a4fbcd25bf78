"""Passes over the IR: small declared objects, one per module, and their registry.

A pass has a ``name`` (also its spelling in ``-p 'name{opt=value}'``), a ``stage``
(``"path"``: the program's path, streamed before the backend; ``"plan"``: blend, plan and
verify, run per planned column of the timing and pulse backends), options as dataclass
fields, and ``run(commands, ctx) -> commands``.  Passes stream
(``Iterable[Command] -> Iterator[Command]``) unless they need the whole program.
Passes import ``cncc.ir`` (and below), never the front end or a backend.

The pipeline builder (:mod:`cncc.pipeline.builder`) is the one place that makes pass
objects: it reads :func:`registered` by name; :mod:`cncc.pipeline.manager` runs them.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar

from cncc.diagnostics import DiagnosticSink
from cncc.dialects import Dialect
from cncc.ir import Command
from cncc.ir.batch import Item, expand
from cncc.ir.machine import MachineModel

if TYPE_CHECKING:
    from cncc.ir.trajectory import Trajectory
    from cncc.passes.verify import VerifyReport


@dataclass(slots=True)
class PassContext:
    """What every pass may read: the sink, the dialect and the machine model; and what the
    planning stage leaves for the backends (``plan``: the trajectory, ``verify``: its report)."""

    sink: DiagnosticSink
    dialect: Dialect | None = None
    machine: MachineModel | None = None
    trajectory: Trajectory | None = None
    plan_level: int = 2
    plan_how: str = ""
    verify_report: VerifyReport | None = None
    batches: bool = True  # the stages after take batches (False: commands only, a pass need not re-batch)


@dataclass(frozen=True, kw_only=True)
class Pass:
    """Base class of passes."""

    name: ClassVar[str] = ""
    stage: ClassVar[str] = "path"

    def run(self, cmds: Iterable[Command], ctx: PassContext) -> Iterator[Command]:
        raise NotImplementedError

    def run_items(self, items: Iterable[Item], ctx: PassContext) -> Iterator[Item]:
        """The pass over a stream that may hold :class:`~cncc.ir.batch.MoveBatch` es (what the pass
        manager calls).  This default expands the batches into commands for :meth:`run`; a pass
        that works on batches overrides it (and makes :meth:`run` expand its result)."""
        return iter(self.run(expand(items), ctx))


_REGISTRY: dict[str, type[Pass]] = {}


def register(cls: type[Pass]) -> type[Pass]:
    """Class decorator: make a pass known to the pass manager by its name."""
    if not cls.name:
        raise ValueError(f"{cls.__name__} has no name")
    _REGISTRY[cls.name] = cls
    return cls


def registered() -> dict[str, type[Pass]]:
    return dict(_REGISTRY)


def run_pipeline(passes: Iterable[Pass], cmds: Iterable[Command], ctx: PassContext) -> Iterator[Command]:
    """Chain the passes lazily: each consumes the previous one's stream (for the unit tests of
    single passes; the compiler runs its passes through :class:`cncc.pipeline.manager.PassManager`)."""
    stream: Iterable[Command] = cmds
    for p in passes:
        stream = p.run(stream, ctx)
    return iter(stream)
