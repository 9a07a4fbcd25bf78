"""cncc batch: Ctrl-C (SIGINT) stops a batch with exit status 130 and keeps its rows, Parquet
included (its journal); the rerun completes it.  The progress bar on a terminal."""

from __future__ import annotations

import io
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from cncc.batch.progress import Reporter, Summary
from cncc.batch.results import journal_path, read_rows

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench"))
from gen import write_library  # noqa: E402

N = 40


def batch(*args: str) -> subprocess.Popen[bytes]:
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    return subprocess.Popen([sys.executable, "-m", "cncc", "batch", *args], env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)


def test_sigint_keeps_the_parquet_journal_and_the_rerun_completes(tmp_path: Path) -> None:
    pytest.importorskip("pyarrow")
    lib = tmp_path / "lib"
    write_library(str(lib), N, loop=False)
    out = tmp_path / "r.parquet"
    journal = Path(journal_path(str(out)))
    args = [str(lib), "-O1", "-j", "1", "-o", str(out)]
    proc = batch(*args)
    deadline = time.monotonic() + 300
    while time.monotonic() < deadline and proc.poll() is None:
        if journal.exists() and journal.read_text().count("\n") >= 10:
            break
        time.sleep(0.02)
    assert proc.poll() is None, "the batch ended before it could be interrupted"
    os.kill(proc.pid, signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 130, err
    assert b"interrupted" in err and not out.exists() and journal.exists()
    kept = read_rows(str(out))
    assert 10 <= len(kept) < N
    proc = batch(*args)
    _, err = proc.communicate(timeout=600)
    assert proc.returncode == 0, err
    assert f"{len(kept)} already in the results file".encode() in err
    assert out.exists() and not journal.exists()
    rows = read_rows(str(out))
    assert len(rows) == N and len({(r["path"], r["key"]) for r in rows}) == N
    assert sorted(r["path"] for r in rows) == sorted(str(p) for p in lib.rglob("*") if p.is_file())


def test_the_progress_bar_runs_on_a_terminal_and_the_summary_is_printed() -> None:
    stream = io.StringIO()
    summary = Summary(programs=2, machines=1)
    with Reporter(2, stream, live=True) as rep:
        for name in ("a.nc", "b.nc"):
            row = {"path": name, "status": "ok", "cpu_s": 0.5}
            summary.add(row)
            rep.advance(row)
        assert rep._bar is not None and rep._bar.tasks[0].completed == 2
    rep.finish(summary)
    text = stream.getvalue()
    assert "2 programs x 1 machine; 2 rows written (2 ok)" in text and "1.0 s CPU" in text
