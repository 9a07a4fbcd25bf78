"""cncc batch on a generated library: -j 1, a 2-worker Dask LocalCluster on loopback, a worker
killed mid-batch, a batch killed mid-run and resumed."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import threading
import time
from collections import Counter
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from cncc.batch import RowOptions, run_batch
from cncc.batch.results import read_rows

distributed = pytest.importorskip("distributed")

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench"))
from gen import LIBRARY_MIX, write_library  # noqa: E402

N_PROGRAMS = 200
SUBSET = "part0[01]"  # the first 100 programs (a glob pattern): the kill and resume tests run these
N_SUBSET = 100
OPTIONS = RowOptions(opt_level=1, max_steps=20_000, time_limit_s=1.0)
CLI_OPTIONS = ["-O1", "--max-steps", "20000", "--time-limit", "1"]
MACHINES = ["generic-mill"]


def subset(library: Path) -> str:
    return str(library / SUBSET / "*")


def in_subset(rows: list[dict[str, Any]]) -> list[dict[str, Any]]:
    return [r for r in rows if Path(r["path"]).parent.name in ("part00", "part01")]


def strip(rows: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """Rows without their CPU time, in path order."""
    return sorted(({k: v for k, v in r.items() if k != "cpu_s"} for r in rows), key=lambda r: (r["path"], r["key"]))


@pytest.fixture(scope="module")
def library(tmp_path_factory: pytest.TempPathFactory) -> Path:
    folder = tmp_path_factory.mktemp("library")
    write_library(str(folder), N_PROGRAMS, big_lines=40_000)
    return folder


@pytest.fixture(scope="module")
def local_rows(library: Path, tmp_path_factory: pytest.TempPathFactory) -> list[dict[str, Any]]:
    out = tmp_path_factory.mktemp("j1") / "results.csv"
    run_batch([str(library)], MACHINES, str(out), options=OPTIONS, jobs=1)
    return read_rows(str(out))


@pytest.fixture(scope="module")
def client() -> Iterator[Any]:
    from distributed import Client, LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                      dashboard_address=None, memory_limit="768MiB") as cluster, Client(cluster) as c:
        yield c


def test_the_library_rows_are_what_the_generator_made(local_rows: list[dict[str, Any]]) -> None:
    assert len(local_rows) == N_PROGRAMS + 1 and len({r["path"] for r in local_rows}) == N_PROGRAMS + 1
    by_name = {Path(r["path"]).name: r for r in local_rows}
    big = by_name.pop("big.nc")
    assert big["status"] == "timeout" and big["codes"] == {"E0996": 1}
    loops = [r for r in by_name.values() if r["codes"] == {"E0301": 1}]
    assert len(loops) == 1 and loops[0]["status"] == "error"  # the endless loop, stopped by --max-steps
    kinds = [k for k in (LIBRARY_MIX[i % len(LIBRARY_MIX)] for i in range(N_PROGRAMS))]
    kinds[N_PROGRAMS // 2] = "loop"
    count = Counter(kinds)
    codes = Counter(next(iter(r["codes"]), "") for r in by_name.values())
    assert codes == {"": count["syntec"] + count["fanuc"] + count["linuxcnc"] + count["grbl"],
                     "E0101": count["error"], "E0201": count["unknown"], "E0301": 1}
    dialects = Counter(r["dialect"] for r in by_name.values())
    assert dialects == {"syntec": count["syntec"] + count["error"] + count["unknown"],
                        "fanuc": count["fanuc"] + count["loop"], "linuxcnc": count["linuxcnc"], "grbl": count["grbl"]}
    assert all(r["cycle_s"] > 0 for r in by_name.values() if r["status"] == "ok")


def test_a_local_cluster_gives_the_same_rows_as_one_job(local_rows: list[dict[str, Any]], client: Any,
                                                       library: Path, tmp_path: Path) -> None:
    out = tmp_path / "results.jsonl"
    summary = run_batch([str(library)], MACHINES, str(out), options=OPTIONS, client=client)
    assert summary.rows == N_PROGRAMS + 1
    assert strip(read_rows(str(out))) == strip(local_rows)


def test_a_worker_killed_mid_batch_loses_no_row(local_rows: list[dict[str, Any]], client: Any,
                                               library: Path, tmp_path: Path) -> None:
    out = tmp_path / "results.jsonl"
    pids: dict[str, int] = client.run(os.getpid)
    victim = sorted(pids.values())[0]
    seen_at_kill: list[int] = []

    def kill_when_started() -> None:
        deadline = time.monotonic() + 300
        while time.monotonic() < deadline:
            n = out.read_text().count("\n") if out.exists() else 0
            if n >= 20:
                os.kill(victim, signal.SIGKILL)
                seen_at_kill.append(n)
                return
            time.sleep(0.05)

    killer = threading.Thread(target=kill_when_started)
    killer.start()
    run_batch([subset(library)], MACHINES, str(out), options=OPTIONS, client=client)
    killer.join()
    assert seen_at_kill and seen_at_kill[0] < N_SUBSET  # killed mid-batch
    assert victim not in client.run(os.getpid).values()  # the nanny started another worker process
    rows = read_rows(str(out))
    assert len(rows) == N_SUBSET and strip(rows) == strip(in_subset(local_rows))


def test_a_killed_batch_resumes_without_loss_or_duplicates(local_rows: list[dict[str, Any]], library: Path,
                                                           tmp_path: Path) -> None:
    out = tmp_path / "results.csv"
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    proc = subprocess.Popen([sys.executable, "-m", "cncc", "batch", subset(library), *CLI_OPTIONS, "-j", "1",
                             "-o", str(out)], env=env, stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 300
        while time.monotonic() < deadline and proc.poll() is None:
            if out.exists() and out.read_text().count("\n") >= 30:
                break
            time.sleep(0.02)
        assert proc.poll() is None, "the batch ended before it could be killed"
        os.kill(proc.pid, signal.SIGKILL)
    finally:
        proc.wait()
    before = read_rows(str(out))
    assert 0 < len(before) < N_SUBSET
    assert out.read_bytes().endswith(b"\n")  # no partial row
    summary = run_batch([subset(library)], MACHINES, str(out), options=OPTIONS, jobs=2)
    assert summary.skipped == len(before) and summary.rows == N_SUBSET - len(before)
    after = read_rows(str(out))
    assert len({(r["path"], r["key"]) for r in after}) == len(after) == N_SUBSET
    assert strip(after) == strip(in_subset(local_rows))
