"""A child process that computes rows under a per-program CPU-time and memory limit.

The parent (a ``-j`` worker thread or a Dask task) sends tasks over a pipe and reads
rows back; ``Sandbox.run(task)`` always returns a row:

- a program over its CPU-time limit is stopped by a profiling timer in the child
  (``status = "timeout"``); one stuck in C code is killed by the parent after a
  wall-clock backstop of ``3 x limit + 30 s``;
- the child's address space is limited (``RLIMIT_AS``, Linux and the BSDs): a program
  that exhausts it gets ``status = "memory"``;
- an exception in the compiler, or the child dying (a signal), gives ``status = "crash"``.

After a failure the child is replaced, so the next program starts clean.  The child
is ``python -m cncc.batch.sandbox``; it imports the same cncc as its parent.
"""

from __future__ import annotations

import contextlib
import os
import pickle
import select
import signal
import struct
import subprocess
import sys
import threading
import time
from pathlib import Path
from typing import IO, Any

from cncc import diagnostics as dg
from cncc.batch.options import RowOptions, Task
from cncc.batch.row import Row, failed_row, program_row

_HEADER = struct.Struct("<I")
WALL_FACTOR, WALL_GRACE_S = 3.0, 30.0
STARTUP_S = 120.0  # a new child imports cncc and warms up before its first program (a loaded machine is slow)
WARM_UP = "G90 G0 X1 Y1 Z1\nG1 X2 F100\nG2 X3 Y2 I0.5 J0.5\nM30\n"


class _TimeLimit(BaseException):  # BaseException: no ``except Exception`` in the compiler swallows it
    pass


def _send(fh: IO[bytes], obj: object) -> None:
    blob = pickle.dumps(obj, protocol=pickle.HIGHEST_PROTOCOL)
    fh.write(_HEADER.pack(len(blob)) + blob)
    fh.flush()


def _recv(fh: IO[bytes]) -> Any:
    head = fh.read(_HEADER.size)
    if len(head) < _HEADER.size:
        raise EOFError
    (n,) = _HEADER.unpack(head)
    blob = fh.read(n)
    if len(blob) < n:
        raise EOFError
    return pickle.loads(blob)


def child_env() -> dict[str, str]:
    """The parent's environment, with this cncc first on the path and one BLAS thread per child."""
    env = dict(os.environ)
    root = str(Path(__file__).resolve().parents[2])
    env["PYTHONPATH"] = os.pathsep.join([root, *filter(None, [env.get("PYTHONPATH")])])
    for var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        env.setdefault(var, "1")
    return env


class Sandbox:
    """One child process; not thread-safe (one per worker thread)."""

    def __init__(self) -> None:
        self.proc: subprocess.Popen[bytes] | None = None
        self.memory_limit_mb: int | None = None

    def _start(self, memory_limit_mb: int) -> subprocess.Popen[bytes]:
        self.close()
        self.proc = subprocess.Popen([sys.executable, "-m", "cncc.batch.sandbox"],
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                                     env=child_env())
        self.memory_limit_mb = memory_limit_mb
        return self.proc

    @property
    def pid(self) -> int | None:
        return None if self.proc is None else self.proc.pid

    def run(self, task: Task) -> Row:
        limit = task.options.memory_limit_mb
        proc = self.proc
        fresh = proc is None or proc.poll() is not None or self.memory_limit_mb != limit
        if fresh:
            proc = self._start(limit)
        assert proc is not None and proc.stdin is not None and proc.stdout is not None
        try:
            _send(proc.stdin, task)
        except OSError:
            return self._died(task)
        cpu_s = task.options.time_limit_s
        wall_s = cpu_s * WALL_FACTOR + WALL_GRACE_S + (STARTUP_S if fresh else 0.0)
        ready, _, _ = select.select([proc.stdout], [], [], wall_s if cpu_s > 0 else None)
        if not ready:
            self.close()
            return failed_row(task, "timeout", dg.BATCH_TIME_LIMIT,
                              f"still running after {wall_s:g} s wall clock (stuck outside Python)")
        try:
            reply: tuple[Row, bool] = _recv(proc.stdout)
        except (EOFError, OSError, pickle.UnpicklingError):
            return self._died(task)
        row, restart = reply
        if restart:
            self.close()
        return row

    def _died(self, task: Task) -> Row:
        code = self.close()
        how = f"signal {signal.Signals(-code).name}" if code is not None and code < 0 else f"exit status {code}"
        if code == -signal.SIGKILL:
            how += " (the system's out-of-memory killer?)"
        return failed_row(task, "crash", dg.BATCH_CRASH, f"the compiling process died ({how})")

    def close(self) -> int | None:
        """End the child (by its own PID: closing its input, then killing it); its exit status."""
        proc, self.proc = self.proc, None
        if proc is None:
            return None
        if proc.poll() is None:
            if proc.stdin is not None:
                with contextlib.suppress(OSError):
                    proc.stdin.close()
            try:
                proc.wait(timeout=0.05)
            except subprocess.TimeoutExpired:
                proc.kill()
        code = proc.wait()
        for fh in (proc.stdin, proc.stdout):
            if fh is not None:
                with contextlib.suppress(OSError):
                    fh.close()
        return code


_local = threading.local()


def sandboxed_row(task: Task) -> Row:
    """The row of ``task``, computed in this thread's sandbox (started on first use).

    This is the function a Dask cluster runs: one child per worker thread, kept across tasks.
    """
    box = getattr(_local, "sandbox", None)
    if box is None:
        box = _local.sandbox = Sandbox()
    return box.run(task)


# ---- the child ------------------------------------------------------------------------------
def _warm_up(task: Task, seen: set[tuple[Any, ...]]) -> None:
    """Import what this kind of task needs before the clock starts (not counted against the limit)."""
    o = task.options
    combo = (task.machine, o.emit, o.opt_level, task.dialect)
    if combo in seen:
        return
    seen.add(combo)
    warm = RowOptions(emit=o.emit, opt_level=o.opt_level)
    with contextlib.suppress(Exception):  # the real task reports the problem
        program_row(Task("warm-up.nc", WARM_UP, task.machine, warm, task.dialect))


def _on_timer(signum: int, frame: object) -> None:
    raise _TimeLimit


def compute(task: Task, seen: set[tuple[Any, ...]]) -> tuple[Row, bool]:
    """(row, replace the child afterwards) for one task, under the CPU-time limit."""
    _warm_up(task, seen)
    limit = task.options.time_limit_s
    t0 = time.process_time()
    try:
        if limit > 0:
            signal.setitimer(signal.ITIMER_PROF, limit)
        try:
            row = program_row(task)
        finally:
            signal.setitimer(signal.ITIMER_PROF, 0)
    except _TimeLimit:
        return failed_row(task, "timeout", dg.BATCH_TIME_LIMIT,
                          f"over the time limit of {limit:g} s CPU", round(time.process_time() - t0, 3)), True
    except MemoryError:
        return failed_row(task, "memory", dg.BATCH_MEMORY_LIMIT,
                          f"over the memory limit of {task.options.memory_limit_mb} MB",
                          round(time.process_time() - t0, 3)), True
    except Exception as exc:
        return failed_row(task, "crash", dg.BATCH_CRASH, f"internal compiler error: {type(exc).__name__}: {exc}",
                          round(time.process_time() - t0, 3)), True
    row["cpu_s"] = round(time.process_time() - t0, 3)
    return row, False


def _limit_memory(mb: int) -> None:
    try:
        import resource
    except ImportError:  # pragma: no cover - Windows: no per-process limit
        return
    if mb > 0:
        soft = mb * 2**20
        _, hard = resource.getrlimit(resource.RLIMIT_AS)
        if hard != resource.RLIM_INFINITY:
            soft = min(soft, hard)
        resource.setrlimit(resource.RLIMIT_AS, (soft, hard))


def child_main(argv: list[str]) -> int:
    proto_in = os.fdopen(os.dup(0), "rb")
    proto_out = os.fdopen(os.dup(1), "wb")
    devnull = os.open(os.devnull, os.O_RDWR)
    os.dup2(devnull, 0)  # the compiler's own prints cannot corrupt the protocol
    os.dup2(devnull, 1)
    signal.signal(signal.SIGPROF, _on_timer)
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C reaches the parent, which ends the children
    seen: set[tuple[Any, ...]] = set()
    limited = False
    while True:
        try:
            task: Task = _recv(proto_in)
        except EOFError:
            return 0
        if not limited:
            _warm_up(task, seen)  # imports before the address-space limit
            _limit_memory(task.options.memory_limit_mb)
            limited = True
        reply = compute(task, seen)
        _send(proto_out, reply)
        if reply[1]:
            return 0


if __name__ == "__main__":
    sys.exit(child_main(sys.argv[1:]))
