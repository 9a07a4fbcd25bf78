"""What a batch says on stderr: a rich progress bar with ETA on a terminal, a summary at the end."""

from __future__ import annotations

import sys
import time
from collections import Counter
from dataclasses import dataclass, field
from typing import Any, TextIO

from cncc.batch.row import Row


@dataclass(slots=True)
class Summary:
    """Counts of one batch run (``rows`` written now; ``skipped``: already in the results file)."""

    programs: int = 0
    machines: int = 0
    skipped: int = 0
    rows: int = 0
    by_status: Counter[str] = field(default_factory=Counter)
    cpu_s: float = 0.0
    wall_s: float = 0.0
    interrupted: bool = False

    def add(self, row: Row) -> None:
        self.rows += 1
        self.by_status[str(row.get("status"))] += 1
        self.cpu_s += float(row.get("cpu_s") or 0.0)

    def lines(self) -> list[str]:
        statuses = ", ".join(f"{n} {s}" for s, n in sorted(self.by_status.items())) or "none"
        rate = f", {self.rows / self.wall_s:.1f} rows/s" if self.wall_s > 0 and self.rows else ""
        head = "cncc batch: interrupted" if self.interrupted else "cncc batch"
        return [f"{head}: {_n(self.programs, 'program')} x {_n(self.machines, 'machine')}; "
                f"{_n(self.rows, 'row')} written "
                f"({statuses}), {self.skipped} already in the results file",
                f"cncc batch: {self.cpu_s:.1f} s CPU in the compilers, {self.wall_s:.1f} s wall{rate}"]


def _n(count: int, what: str) -> str:
    return f"{count} {what}{'' if count == 1 else 's'}"


class Reporter:
    """Progress while rows arrive: a rich bar on a terminal, nothing otherwise."""

    def __init__(self, total: int, stream: TextIO | None = None, live: bool | None = None) -> None:
        self.stream = stream or sys.stderr
        self.live = self.stream.isatty() if live is None else live
        self.total = total
        self.t0 = time.perf_counter()
        self._bar: Any = None
        self._task: Any = None

    def __enter__(self) -> Reporter:
        if self.live and self.total:
            from rich.console import Console
            from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeRemainingColumn

            self._bar = Progress(TextColumn("cncc batch"), BarColumn(), MofNCompleteColumn(),
                                 TextColumn("{task.fields[last]}"), TimeRemainingColumn(),
                                 console=Console(file=self.stream), transient=True)
            self._bar.start()
            self._task = self._bar.add_task("rows", total=self.total, last="")
        return self

    def advance(self, row: Row) -> None:
        if self._bar is not None:
            self._bar.update(self._task, advance=1, last=f"{row.get('status')}: {row.get('path')}")

    def __exit__(self, *exc: object) -> None:
        if self._bar is not None:
            self._bar.stop()

    def finish(self, summary: Summary) -> None:
        summary.wall_s = time.perf_counter() - self.t0
        for line in summary.lines():
            self.stream.write(line + "\n")
