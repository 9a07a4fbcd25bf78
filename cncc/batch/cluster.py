"""``--dask ADDRESS`` or a ``dask.distributed.Client``: the same sandboxed tasks on a Dask cluster.

Each task runs :func:`cncc.batch.sandbox.sandboxed_row` on a worker (one sandbox
child per worker thread), so a program that crashes or hangs costs a row, not the
worker.  A worker lost mid-run (killed, its machine gone) has its tasks rescheduled
by the scheduler; a task that has lost ``distributed.scheduler.allowed-failures``
workers gives a crash row.  At most ``window`` tasks are in flight, so a big library
does not sit in the scheduler's memory at once.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from typing import Any

from cncc import diagnostics as dg
from cncc.batch.options import Task
from cncc.batch.row import Row, failed_row
from cncc.batch.sandbox import sandboxed_row

INSTALL_HINT = "the Dask path needs dask.distributed: pip install 'cncc[cluster]'"


def connect(address: str, timeout_s: float = 30.0) -> Any:
    """A client of the scheduler at ``address`` (``tcp://host:8786``)."""
    try:
        from distributed import Client
    except ImportError:
        raise RuntimeError(INSTALL_HINT) from None
    return Client(address, timeout=f"{timeout_s}s")


def _threads(client: Any) -> int:
    try:
        return max(1, int(sum(client.nthreads().values())))
    except Exception:  # a client that cannot say: a modest window
        return 4


def cluster_rows(client: Any, tasks: Sequence[Task], window: int | None = None) -> Iterator[Row]:
    """The rows of ``tasks`` computed on ``client``'s cluster, in the order they finish."""
    from distributed import as_completed

    width = window or max(64, 8 * _threads(client))
    pending = iter(tasks)
    by_key: dict[str, Task] = {}

    def submit(task: Task) -> Any:
        key = f"cncc-batch-{task.key}"
        by_key[key] = task
        return client.submit(sandboxed_row, task, key=key, pure=False)

    first = [submit(t) for _, t in zip(range(width), pending, strict=False)]
    flight = as_completed(first)
    try:
        for fut in flight:
            task = by_key.pop(fut.key)
            try:
                row: Row = fut.result()
            except Exception as exc:  # KilledWorker after too many lost workers, or a cancelled task
                row = failed_row(task, "crash", dg.BATCH_CRASH, f"the Dask task failed: {type(exc).__name__}: {exc}")
            fut.release()
            nxt = next(pending, None)
            if nxt is not None:
                flight.add(submit(nxt))
            yield row
    finally:
        left = list(flight.futures) if hasattr(flight, "futures") else []
        if left:
            client.cancel(left)
