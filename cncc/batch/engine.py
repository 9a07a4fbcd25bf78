"""A batch run: tasks -> rows (locally or on a cluster) -> the results file, resumable."""

from __future__ import annotations

from collections.abc import Iterator, Mapping, Sequence
from typing import Any, TextIO

from cncc.batch.options import RowOptions, Task
from cncc.batch.progress import Reporter, Summary
from cncc.batch.results import ResultsWriter, read_rows
from cncc.batch.row import Row


def pending_tasks(tasks: Sequence[Task], done: set[tuple[str, str]]) -> tuple[list[Task], dict[str, list[Task]]]:
    """(tasks to compute, one per key; every task waiting for each key's row), skipping ``done`` (path, key)."""
    todo: list[Task] = []
    waiting: dict[str, list[Task]] = {}
    for t in tasks:
        if (t.path, t.key) in done:
            continue
        same = waiting.setdefault(t.key, [])
        if not same:
            todo.append(t)
        if all(o.path != t.path for o in same):
            same.append(t)
    return todo, waiting


def rows_for(task: Task, row: Row) -> Row:
    """``row`` (computed for an equal program) as the row of ``task``."""
    return row if row["path"] == task.path else {**row, "path": task.path}


def run_tasks(tasks: Sequence[Task], output: str, *, jobs: int = 1, client: Any = None,
              stream: TextIO | None = None, live: bool | None = None, programs: int = 0,
              machines: int = 0) -> Summary:
    """Compute the rows ``output`` does not have yet and append them as they arrive.

    ``client``: a ``dask.distributed.Client`` (else ``jobs`` local processes).  A
    ``KeyboardInterrupt`` stops the run; the rows written so far stay, and a rerun
    with the same ``output`` computes only the others.
    """
    done = {(r["path"], r["key"]) for r in read_rows(output)}
    todo, waiting = pending_tasks(tasks, done)
    summary = Summary(programs=programs, machines=machines, skipped=len(tasks) - sum(map(len, waiting.values())))
    writer = ResultsWriter(output)
    reporter = Reporter(sum(map(len, waiting.values())), stream, live)
    source: Iterator[Row]
    if client is not None:
        from cncc.batch.cluster import cluster_rows

        source = cluster_rows(client, todo)
    else:
        from cncc.batch.local import local_rows

        source = local_rows(todo, jobs)
    try:
        with reporter:
            for row in source:
                for t in waiting.pop(row["key"], []):
                    out = rows_for(t, row)
                    writer.write(out)
                    summary.add(out)
                    reporter.advance(out)
    except KeyboardInterrupt:
        summary.interrupted = True
    finally:
        close = getattr(source, "close", None)
        if close is not None:
            close()
        writer.close(finish=not summary.interrupted)  # interrupted Parquet: the journal stays for the resume
    reporter.finish(summary)
    return summary


def run_batch(inputs: Sequence[str], machines: Sequence[str], output: str, *,
              options: RowOptions | Mapping[str, RowOptions] | None = None,
              dialect: str | None = None, jobs: int = 1, client: Any = None, stream: TextIO | None = None,
              live: bool | None = None) -> Summary:
    """The Python API: ``inputs`` (folders, glob patterns, files) x ``machines`` -> rows in ``output``.

    ``options``: for every machine, or a mapping machine name -> options (the work offsets of
    each machine).  ``client``: a ``dask.distributed.Client`` to run on its cluster; otherwise ``jobs``
    local worker processes.  Raises :class:`cncc.batch.results.ResultsError` when the
    results file cannot be used, :class:`LookupError` when no program matches.
    """
    from cncc.batch.programs import find_programs, make_tasks

    paths = find_programs(inputs)
    if not paths:
        raise LookupError(f"no program file matches {' '.join(inputs)}")
    tasks = list(make_tasks(paths, machines, options or RowOptions(), dialect))
    return run_tasks(tasks, output, jobs=jobs, client=client, stream=stream, live=live,
                     programs=len(paths), machines=len(machines))
