"""The compiler pipeline of an analysis: front end and path passes, as the driver builds them.

``compile_commands(...)`` streams the document's commands like ``driver.front_end``
followed by ``driver.path_passes``, with two differences for the editor:

* the macro executor gets the server's variable trace (``MacroOptions.trace``);
* in program coordinates (the first phase) the frame passes -- polar, scaling,
  mirror, rotation, cutter compensation -- are started only at the first command
  whose frame asks for one of them.  Before it, all they do to a command is to
  start each motion where the previous one ended (a cycle's expanded moves, a
  change of work offset); the ``relink`` pass does just that.  The commands and the
  diagnostics are the same (``tests/lsp/test_pipeline.py`` compares both pipelines
  on a corpus); on a plain CAM program this saves about half of the first phase,
  which is what the editor waits for.

Both lists of passes come from the pipeline builder (:mod:`cncc.pipeline.builder`), with
the driver's configuration for the same options (:func:`cncc.driver.pipeline_config`).
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Iterator
from typing import TYPE_CHECKING

from cncc.diagnostics import DiagnosticSink
from cncc.dialects import Dialect
from cncc.ir import Command, Frame
from cncc.ir.frame import CompSide
from cncc.ir.machine import MachineModel
from cncc.source import SourceMap

if TYPE_CHECKING:
    from cncc.driver import Options
    from cncc.frontend import InterpOptions
    from cncc.lsp.analysis import Request
    from cncc.lsp.incremental import Memory
    from cncc.lsp.trace import VariableTrace


def compile_options(req: Request, dialect: Dialect) -> Options:
    """The driver's options for one document: its tables, and its folder and the workspace
    root as places to look for called programs."""
    from cncc import driver

    settings = req.settings
    folders = [os.path.dirname(req.path)] if req.path else []
    if settings.root and settings.root not in folders:
        folders.append(settings.root)
    return driver.Options(inputs=[req.path] if req.path else [], dialect=dialect.name,
                          offsets_file=settings.path(settings.offsets), tools_file=settings.path(settings.tools),
                          repair_arcs=req.repair_arcs, include_dirs=folders,
                          dialect_options=dict(settings.dialect_options))


def interp_options(opts: Options, machine: MachineModel, sink: DiagnosticSink) -> InterpOptions:
    """The interpreter's tables (work offsets, tool lengths and radii, reference points), as the driver makes them."""
    from cncc import driver

    iopts: InterpOptions = driver.interp_options(opts, machine, sink)
    return iopts


def compile_commands(req: Request, dialect: Dialect, machine: MachineModel, sources: SourceMap,
                     sink: DiagnosticSink, machine_coords: bool,
                     trace: VariableTrace | None = None, memory: Memory | None = None) -> Iterator[Command]:
    """The document's commands after the path passes; in machine coordinates for the planner
    when ``machine_coords``.  With ``memory`` (program coordinates only), a straight-line
    program keeps interpreter checkpoints there for :mod:`cncc.lsp.incremental`."""
    from cncc import driver
    from cncc.frontend import lower

    src = sources.add(req.path or req.uri, req.text)
    opts = compile_options(req, dialect)
    iopts = interp_options(opts, machine, sink)
    macro = driver.macro_options(opts, sink, sources)
    macro.trace = trace
    if memory is not None and not machine_coords:
        from cncc.lsp.incremental import eligible, keep_checkpoints

        if eligible(req.text, dialect):
            return _split(keep_checkpoints(src, dialect, sink, iopts, memory), dialect, machine, opts, sink, memory)
        memory.light = False
    if trace is not None and dialect.macro_flavour == "linuxcnc":
        from cncc.lsp.linuxcnc_trace import lower_traced

        cmds = lower_traced(src, dialect, sink, iopts, macro, trace)
    else:
        cmds = lower(src, dialect, sink, iopts, macro)
    if machine_coords:
        opts.emit = "timing"  # a backend that reads machine coordinates: offsets and tool lengths applied
        return driver.path_passes(cmds, dialect, machine, opts, sink)
    return _split(cmds, dialect, machine, opts, sink)


def transforms(frame: Frame) -> bool:
    """Whether a frame pass of the program-coordinate pipeline changes commands of this frame."""
    return (frame.polar is not None or frame.scaling is not None or frame.mirror is not None
            or frame.rotation is not None or frame.comp_side is not CompSide.OFF)


def _split(cmds: Iterable[Command], dialect: Dialect, machine: MachineModel, opts: Options,
           sink: DiagnosticSink, memory: Memory | None = None) -> Iterator[Command]:
    """Commands through the light pipeline until a frame needs the frame passes, then the
    rest (from that command on) through the driver's whole pipeline."""
    from cncc import driver

    it = iter(cmds)
    first: list[Command] = []

    def plain() -> Iterator[Command]:
        checked: set[int] = set()  # frames already seen to be plain (frames are shared records)
        for c in it:
            f = c.frame
            if id(f) not in checked:
                if transforms(f):
                    first.append(c)
                    return
                checked.add(id(f))
            yield c

    yield from light_passes(plain(), dialect, machine, opts, sink, memory)
    if first:
        if memory is not None:
            memory.light = False
        yield from driver.path_passes(_chain(first, it), dialect, machine, opts, sink)


def _chain(head: list[Command], rest: Iterator[Command]) -> Iterator[Command]:
    yield from head
    yield from rest


def light_passes(cmds: Iterable[Command], dialect: Dialect, machine: MachineModel, opts: Options,
                 sink: DiagnosticSink, memory: Memory | None = None) -> Iterator[Command]:
    """``driver.path_passes`` with ``relink`` in place of the frame passes (same cycle expansion
    and arc check; :func:`cncc.pipeline.builder.light_passes`); ``memory``: where the relink
    starts and what it keeps up to date."""
    from cncc import driver
    from cncc.dialects.errors import controller_sink
    from cncc.passes import PassContext
    from cncc.pipeline import builder
    from cncc.pipeline.manager import PassManager

    ctx = PassContext(sink=controller_sink(sink, dialect.raw.get("errors")), dialect=dialect, machine=machine)
    passes = builder.light_passes(driver.pipeline_config(opts), dialect, memory)
    return PassManager().run(passes, cmds, ctx)
