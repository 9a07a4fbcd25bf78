"""Program libraries: audit and time many programs, on this machine or a Dask cluster.

>>> from cncc.batch import run_batch                       # doctest: +SKIP
>>> run_batch(["library/"], ["syntec-900m"], "results.csv", jobs=2)
>>> from distributed import Client                         # doctest: +SKIP
>>> run_batch(["library/"], ["syntec-900m"], "results.csv", client=Client("tcp://sched:8786"))

The per-program work is :func:`cncc.batch.row.program_row` (program text + options
-> row), run in a sandboxed child process (:mod:`cncc.batch.sandbox`) by both the
local ``-j N`` path and the Dask path.  docs/batch.md has the worked examples.
"""

from cncc.batch.engine import run_batch, run_tasks
from cncc.batch.options import RowOptions, Task
from cncc.batch.row import COLUMNS, program_row

__all__ = ["COLUMNS", "RowOptions", "Task", "program_row", "run_batch", "run_tasks"]
