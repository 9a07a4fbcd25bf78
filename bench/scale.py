"""Whole-process planner scale runs: ``cncc FILE --emit=timing --report-format=json`` per kind and size.

Each run is a child process; its CPU seconds (user + system) and peak RSS come from
``os.wait4``.  A run that exceeds the time limit is killed and shown as ``>limit``.
"""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


@dataclass(frozen=True)
class Run:
    cpu_s: float
    rss_mb: float
    rc: int  # -1: killed at the time limit
    stderr: str


TIME = "/usr/bin/time"


def run_cncc(path: Path, args: list[str], limit_s: float, root: Path = ROOT) -> Run:
    """Peak RSS through ``/usr/bin/time`` when present: a child forked from this (larger)
    process reports at least this process' RSS in ``wait4``, since exec keeps the forked
    copy's high-water mark."""
    env = dict(os.environ, PYTHONPATH=str(root))
    rss_file = path.with_suffix(".rss")
    timer = [TIME, "-f", "%M", "-o", str(rss_file)] if os.path.exists(TIME) else []
    cmd = [*timer, sys.executable, "-m", "cncc", str(path), *args]
    with tempfile.TemporaryFile() as err:
        # a session of its own: at the time limit the whole group goes (killing /usr/bin/time
        # alone left cncc running as an orphan)
        # cwd=root: 'python -m cncc' puts the cwd first on sys.path (a before run started from a
        # worktree would import the worktree)
        proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=err, env=env, start_new_session=True,
                                cwd=str(root))
        start = time.monotonic()
        killed = False
        while True:
            pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
            if pid:
                break
            if time.monotonic() - start > limit_s:
                os.killpg(proc.pid, signal.SIGKILL)
                killed = True
                pid, status, usage = os.wait4(proc.pid, 0)
                break
            time.sleep(0.02)
        proc.returncode = 0
        err.seek(0)
        text = err.read().decode(errors="replace")
    rc = -1 if killed else os.waitstatus_to_exitcode(status)
    rss_mb = usage.ru_maxrss / 1024
    if timer and not killed:
        with contextlib.suppress(OSError, ValueError, IndexError):
            rss_mb = int(rss_file.read_text().split()[-1]) / 1024
    return Run(usage.ru_utime + usage.ru_stime, rss_mb, rc, text)


def timing_run(path: Path, level: int, limit_s: float, extra: list[str] | None = None,
               root: Path = ROOT) -> tuple[Run, float]:
    """The run and the planned motion time (``columns[0].trajectory_s`` of the JSON report);
    ``root``: the source tree that runs (another checkout for before/after tables)."""
    import json

    out = path.with_suffix(f".O{level}.json")
    run = run_cncc(path, ["--emit=timing", "--report-format=json", f"-O{level}", "-o", str(out), *(extra or [])],
                   limit_s, root)
    try:
        cycle = float(json.loads(out.read_text())["columns"][0]["trajectory_s"])
    except (OSError, ValueError, KeyError, IndexError):
        cycle = float("nan")
    return run, cycle
