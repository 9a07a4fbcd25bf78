"""The pass manager: runs a list of passes over a command stream, optionally instrumented.

Without instrumentation the passes are chained lazily, each consuming the previous one's
stream.  :class:`Instrumentation` adds, as LLVM's pass manager does:

* ``verify_each``: after every pass, the IR invariants of :mod:`cncc.pipeline.invariants`
  (violations are E0992 diagnostics naming the pass);
* ``print_after``: the IR after the named passes, in the ``--emit=ir`` text form (through
  ``printer``), collected in ``dumps``;
* ``time_passes``: the CPU and wall time spent inside each pass.  Passes are generators,
  so a pass's work happens while its consumer pulls from it: every stage's stream is
  wrapped, and :class:`Clock` charges the time between two switches to the stage on top
  of a stack -- a pass pulling from the pass before it hands the clock to that one until
  the item arrives -- so each row is the time spent in that stage alone.  Eager work in
  ``run()`` itself (``plan`` lists its input) is charged the same way.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field
from typing import TypeVar

from cncc.ir import Command
from cncc.ir.batch import Item, expand
from cncc.passes import Pass, PassContext
from cncc.pipeline.invariants import Checker
from cncc.source import SourceMap

T = TypeVar("T")

VERIFY_ROW = "(verify-each)"
PRINT_ROW = "(print-after)"


@dataclass(slots=True)
class Clock:
    """CPU (``process_time``) and wall time charged to the row on top of the stack.

    Reading the CPU clock is a system call (about 1.5 us here), made at every switch;
    :meth:`report` takes the measured cost of a switch (:func:`switch_cost_s`) off each
    row per switch charged to it, so a cheap pass does not look as slow as the clock."""

    rows: dict[str, list[float]] = field(default_factory=dict)  # name -> [cpu s, wall s, switches]
    stack: list[str] = field(default_factory=list)
    cpu: float = 0.0
    wall: float = 0.0

    def _charge(self) -> None:
        cpu, wall = time.process_time(), time.perf_counter()
        if self.stack:
            row = self.rows.setdefault(self.stack[-1], [0.0, 0.0, 0.0])
            row[0] += cpu - self.cpu
            row[1] += wall - self.wall
            row[2] += 1
        self.cpu, self.wall = cpu, wall

    def enter(self, row: str) -> None:
        self._charge()
        self.rows.setdefault(row, [0.0, 0.0, 0.0])
        self.stack.append(row)

    def leave(self) -> None:
        self._charge()
        self.stack.pop()

    def timed(self, items: Iterable[T], row: str) -> Iterator[T]:
        """``items``, with the time spent producing each charged to ``row``."""
        self.enter(row)
        try:
            it = iter(items)
        finally:
            self.leave()
        while True:
            self.enter(row)
            try:
                item = next(it)
            except StopIteration:
                return
            finally:
                self.leave()
            yield item

    def call(self, row: str, fn: Callable[[], T]) -> T:
        self.enter(row)
        try:
            return fn()
        finally:
            self.leave()

    def net(self) -> dict[str, tuple[float, float]]:
        """Each row's (CPU s, wall s) without the cost of the clock's own switches."""
        cpu_cost, wall_cost = switch_cost_s()
        return {name: (max(0.0, cpu - n * cpu_cost), max(0.0, wall - n * wall_cost))
                for name, (cpu, wall, n) in self.rows.items()}

    def report(self) -> str:
        """LLVM's ``-time-passes`` table: rows by CPU time, largest first, and the total."""
        rows = self.net()
        cpu_total = sum(r[0] for r in rows.values())
        wall_total = sum(r[1] for r in rows.values())

        def pct(v: float, total: float) -> str:
            return f"({100.0 * v / total:5.1f}%)" if total > 0 else "(  0.0%)"

        bar = "===" + "-" * 73 + "==="
        lines = [bar, "                        ... Pass execution timing report ...", bar,
                 f"  Total Execution Time: {cpu_total:.4f} seconds ({wall_total:.4f} wall clock)", "",
                 "   ---CPU Time---     ---Wall Time---   --- Name ---"]
        for name, (cpu, wall) in sorted(rows.items(), key=lambda kv: (-kv[1][0], kv[0])):
            lines.append(f"   {cpu:.4f} {pct(cpu, cpu_total)}   {wall:.4f} {pct(wall, wall_total)}   {name}")
        lines.append(f"   {cpu_total:.4f} {pct(cpu_total, cpu_total)}   {wall_total:.4f} "
                     f"{pct(wall_total, wall_total)}   Total")
        return "\n".join(lines) + "\n"


_SWITCH_COST: list[tuple[float, float]] = []


def switch_cost_s() -> tuple[float, float]:
    """(CPU s, wall s) one switch of a :class:`Clock` costs, measured once per process."""
    if not _SWITCH_COST:
        probe = Clock()
        probe.enter("probe")
        n = 2000
        cpu0, wall0 = time.process_time(), time.perf_counter()
        for _ in range(n):
            probe._charge()
        cpu1, wall1 = time.process_time(), time.perf_counter()
        _SWITCH_COST.append(((cpu1 - cpu0) / n, (wall1 - wall0) / n))
    return _SWITCH_COST[0]


@dataclass(slots=True)
class Instrumentation:
    """What the pass manager does besides running the passes (``--verify-each``,
    ``--print-after=NAME``, ``--time-passes``); one per compilation."""

    verify_each: bool = False
    print_after: frozenset[str] = frozenset()
    time_passes: bool = False
    printer: Callable[[list[Command]], str] | None = None  # commands -> the --emit=ir text
    sources: SourceMap | None = None  # for the span invariant
    unit: str = ""  # the input being compiled (named in the dump headers)
    dumps: list[str] = field(default_factory=list)
    clock: Clock = field(default_factory=Clock)
    path_ran: frozenset[str] = frozenset()  # the last path stage's passes (the plan stage follows it)
    _pending: list[tuple[str, list[Command], list[bool]]] = field(default_factory=list)

    @property
    def active(self) -> bool:
        return self.verify_each or bool(self.print_after) or self.time_passes

    def finish(self) -> None:
        """Print the dumps of streams that were not read to their end (-fmax-errors)."""
        for header, items, done in self._pending:
            if not done[0]:
                done[0] = True
                self.dumps.append(self._dump(header + " (stopped early)", items))
        self._pending.clear()

    def _dump(self, header: str, items: list[Command]) -> str:
        body = self.printer(items) if self.printer is not None else "".join(f"{c!r}\n" for c in items)
        return f"; *** IR Dump After {header} ***\n{body}"

    def printed(self, items: Iterable[Command], name: str, label: str = "") -> Iterator[Command]:
        where = ", ".join(x for x in (self.unit, label) if x)
        header = f"{name} ({where})" if where else name
        kept: list[Command] = []
        done = [False]
        self._pending.append((header, kept, done))
        for c in items:
            kept.append(c)
            yield c
        if not done[0]:
            done[0] = True
            self.dumps.append(self._dump(header, kept))


class PassManager:
    """Runs pass lists; ``instrument`` (optional) is shared by all the runs of a compilation."""

    def __init__(self, instrument: Instrumentation | None = None) -> None:
        self.instrument = instrument if instrument is not None and instrument.active else None

    def source(self, cmds: Iterable[Item], row: str = "front end") -> Iterable[Item]:
        """The front end's stream, timed as a row of its own under ``--time-passes``."""
        return self.timed(cmds, row)

    def timed(self, items: Iterable[T], row: str) -> Iterable[T]:
        """``items`` (the front end's commands, a backend's text), timed as ``row`` under ``--time-passes``."""
        ins = self.instrument
        return ins.clock.timed(items, row) if ins is not None and ins.time_passes else items

    def call(self, row: str, fn: Callable[[], T]) -> T:
        """``fn()`` (a backend's eager work), timed as ``row`` under ``--time-passes``."""
        ins = self.instrument
        return ins.clock.call(row, fn) if ins is not None and ins.time_passes else fn()

    def run(self, passes: Iterable[Pass], cmds: Iterable[Command], ctx: PassContext, *,
            stage: str = "path", label: str = "") -> Iterator[Command]:
        """:meth:`run_items` over commands, giving commands."""
        return expand(self.run_items(passes, cmds, ctx, stage=stage, label=label))

    def run_items(self, passes: Iterable[Pass], cmds: Iterable[Item], ctx: PassContext, *,
                  stage: str = "path", label: str = "") -> Iterator[Item]:
        """The commands (and batches of moves, :mod:`cncc.ir.batch`) through ``passes`` in order
        (lazily); each pass gets batches only if it works on them (:meth:`Pass.run_items`), and the
        instruments see the commands (the batches expanded).  ``stage="plan"`` continues the
        invariants of the last path stage (``to-machine`` has run); ``label`` names the run in
        the --print-after headers (a planned column: "-O1 on generic-mill")."""
        stream: Iterable[Item] = cmds
        ins = self.instrument
        if ins is None:
            for p in passes:
                stream = p.run_items(stream, ctx)
            return iter(stream)
        ran = set(ins.path_ran) if stage == "plan" else set()
        for p in passes:
            ran.add(p.name)
            stream = self._one(p, stream, ctx, ins, frozenset(ran), label)
        if stage == "path":
            ins.path_ran = frozenset(ran)
        return iter(stream)

    @staticmethod
    def _one(p: Pass, stream: Iterable[Item], ctx: PassContext, ins: Instrumentation,
             ran: frozenset[str], label: str) -> Iterable[Item]:
        timing = ins.time_passes
        prev = stream
        out: Iterable[Item] = ins.clock.timed(_deferred(p, prev, ctx), p.name) if timing else p.run_items(prev, ctx)
        if not ins.verify_each and p.name not in ins.print_after:
            return out
        cmds: Iterable[Command] = expand(out)
        if ins.verify_each:
            checked = Checker(p.name, ctx.sink, ins.sources, ran).check(cmds)
            cmds = ins.clock.timed(checked, VERIFY_ROW) if timing else checked
        if p.name in ins.print_after:
            printed = ins.printed(cmds, p.name, label)
            cmds = ins.clock.timed(printed, PRINT_ROW) if timing else printed
        return cmds


def _deferred(p: Pass, stream: Iterable[Item], ctx: PassContext) -> Iterator[Item]:
    """``p.run_items(stream)`` started at the first pull, so eager work in ``run()`` is timed too."""
    yield from p.run_items(stream, ctx)
