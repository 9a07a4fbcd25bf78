"""Progress display for long timing runs, on standard error and only when it is a terminal.

``track(items, total, label)`` and ``track_source(cmds, ...)`` yield their items
unchanged; ``stage(label, size)`` wraps a step.  When the work is at least
:data:`MIN_ITEMS` items and ``sys.stderr`` is a TTY they also draw a rich progress bar
or spinner (rich is imported only then).  Pipes, files and tests never see them.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from typing import Protocol, TextIO, TypeVar

from cncc.source import Span


class _Spanned(Protocol):
    @property
    def span(self) -> Span: ...


T = TypeVar("T")
C = TypeVar("C", bound=_Spanned)
MIN_ITEMS = 50_000
"""Below this many items the work takes well under a second: no bar."""


def wanted(total: int, stream: TextIO | None = None) -> bool:
    s = stream if stream is not None else sys.stderr
    isatty = getattr(s, "isatty", None)
    return total >= MIN_ITEMS and bool(isatty and isatty())


def track(items: Iterable[T], total: int, label: str, stream: TextIO | None = None) -> Iterator[T]:
    if not wanted(total, stream):
        yield from items
        return
    from rich.console import Console
    from rich.progress import Progress

    console = Console(file=stream if stream is not None else sys.stderr)
    with Progress(console=console, transient=True) as bar:
        task = bar.add_task(label, total=total)
        step = max(total // 200, 1)
        for k, item in enumerate(items, 1):
            yield item
            if k % step == 0:
                bar.update(task, completed=k)
        bar.update(task, completed=total)


def track_source(cmds: Iterable[C], text_length: int, source_id: int, stream: TextIO | None = None) -> Iterator[C]:
    """Yield ``cmds`` (streamed from the front end) with a bar over the source text read so far.

    ``text_length`` is the length of the program text; the bar follows the span start of
    each command of source ``source_id`` (subprogram commands leave it where it is).
    """
    if not wanted(text_length // 20, stream):  # about 20 characters a block
        yield from cmds
        return
    from rich.console import Console
    from rich.progress import Progress

    console = Console(file=stream if stream is not None else sys.stderr)
    with Progress(console=console, transient=True) as bar:
        task = bar.add_task("reading the program", total=text_length)
        for k, c in enumerate(cmds):
            yield c
            if k % 2000 == 0 and c.span.source_id == source_id:
                bar.update(task, completed=c.span.start)


@contextmanager
def stage(label: str, size: int, stream: TextIO | None = None) -> Iterator[None]:
    """A spinner with ``label`` while a long step runs (``size``: items it works on)."""
    if not wanted(size, stream):
        yield
        return
    from rich.console import Console

    console = Console(file=stream if stream is not None else sys.stderr)
    with console.status(label):
        yield


PLAN_MIN_ITEMS = 20_000
"""Commands from which planning is expected to take more than about 2 s: a bar with ETA."""


@contextmanager
def planning_bar(label: str, total: int, quiet: bool = False, stream: TextIO | None = None
                 ) -> Iterator[Callable[[int], None]]:
    """A bar with percentage and ETA over ``total`` commands; yields ``update(done)``.

    Drawn only on a terminal, for at least :data:`PLAN_MIN_ITEMS` commands and without
    ``quiet`` (``-q``); otherwise ``update`` does nothing."""
    s = stream if stream is not None else sys.stderr
    isatty = getattr(s, "isatty", None)
    if quiet or total < PLAN_MIN_ITEMS or not (isatty and isatty()):
        yield lambda done: None
        return
    from rich.console import Console
    from rich.progress import BarColumn, Progress, TaskProgressColumn, TextColumn, TimeRemainingColumn

    console = Console(file=s)
    with Progress(TextColumn("{task.description}"), BarColumn(), TaskProgressColumn(), TimeRemainingColumn(),
                  console=console, transient=True) as bar:
        task = bar.add_task(label, total=total)
        yield lambda done: bar.update(task, completed=done)
