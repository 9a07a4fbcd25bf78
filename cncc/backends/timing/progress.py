"""A progress bar for long timing runs, on standard error and only when it is a terminal.

``track(items, total, label)`` yields the items unchanged; when ``total`` is at least
:data:`MIN_ITEMS` and ``sys.stderr`` is a TTY it also draws a rich progress bar (rich
is imported only then).  Reports written to pipes and files never see it.
"""

from __future__ import annotations

import sys
from collections.abc import Iterable, Iterator
from typing import TextIO, TypeVar

T = TypeVar("T")
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
