"""``-j N``: N sandboxed child processes on this machine, fed by N threads of the parent."""

from __future__ import annotations

import queue
import threading
from collections.abc import Iterator, Sequence

from cncc.batch.options import Task
from cncc.batch.row import Row
from cncc.batch.sandbox import Sandbox


def local_rows(tasks: Sequence[Task], jobs: int) -> Iterator[Row]:
    """The rows of ``tasks``, in the order they finish; closing the iterator ends the children."""
    todo: queue.SimpleQueue[Task] = queue.SimpleQueue()
    for t in tasks:
        todo.put(t)
    done: queue.SimpleQueue[Row | None] = queue.SimpleQueue()
    stop = threading.Event()
    boxes = [Sandbox() for _ in range(max(1, min(jobs, len(tasks))))]

    def work(box: Sandbox) -> None:
        try:
            while not stop.is_set():
                try:
                    task = todo.get_nowait()
                except queue.Empty:
                    return
                row = box.run(task)
                if not stop.is_set():
                    done.put(row)
        finally:
            box.close()
            done.put(None)

    threads = [threading.Thread(target=work, args=(b,), name=f"cncc-batch-{i}", daemon=True)
               for i, b in enumerate(boxes)]
    for th in threads:
        th.start()
    running = len(threads)
    try:
        while running:
            row = done.get()
            if row is None:
                running -= 1
            else:
                yield row
    finally:
        stop.set()
        for b in boxes:  # a thread waiting on its child sees it end and stops
            b.close()
        for th in threads:
            th.join(timeout=5)
