"""Language server latency, each figure beside its baseline in the same run.

    python bench/lsp.py [--sizes 10000,100000] [--edits 6] [--machine NAME] [--opt-level 0]

Starts ``cncc lsp`` as a subprocess and talks JSON-RPC to it over stdin/stdout (a
minimal client, so no client overhead is measured), and prints:

* **start-up**: spawn -> the ``initialize`` answer, for ``cncc lsp`` and for a bare
  pygls server (``LanguageServer`` with no features) started the same way; median of
  three spawns each (goal: cncc <= 1.5x the bare server);
* **first diagnostics** on a generated CAM-style program of each size (``didOpen`` ->
  the first ``publishDiagnostics`` of that version);
* **edit -> first diagnostics** for one-character edits at the start, the middle and
  the end of each program (alternately a digit replaced and a digit inserted, so the
  text after the edit both stays and moves), beside a full ``cncc -fsyntax-only`` of the
  same file (process wall time and CPU).  Goals: the median edit <= 0.1x the full
  compile on 100k lines, and < 300 ms on 10k lines (on a quiet machine).

The server's debounce is set to 0, so the figures are the analysis and the protocol.
Wall times are what an editor user waits for; the load average is printed before and
after (the machine is shared).
"""

from __future__ import annotations

import argparse
import json
import os
import queue
import resource
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from typing import Any

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gen import cam_program

BARE_SERVER = ("from pygls.lsp.server import LanguageServer\n"
               "LanguageServer('bare', '0').start_io()\n")


class Client:
    def __init__(self, cmd: list[str]) -> None:
        self.proc = subprocess.Popen(cmd, stdin=subprocess.PIPE, stdout=subprocess.PIPE)
        self.inbox: queue.Queue[dict[str, Any]] = queue.Queue()
        self.next_id = 0
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self) -> None:
        out = self.proc.stdout
        assert out is not None
        while True:
            length = 0
            while True:
                line = out.readline()
                if not line:
                    return
                if line in (b"\r\n", b"\n"):
                    break
                if line.lower().startswith(b"content-length:"):
                    length = int(line.split(b":")[1])
            self.inbox.put(json.loads(out.read(length)))

    def send(self, msg: dict[str, Any]) -> None:
        body = json.dumps({"jsonrpc": "2.0", **msg}).encode()
        assert self.proc.stdin is not None
        self.proc.stdin.write(b"Content-Length: %d\r\n\r\n" % len(body) + body)
        self.proc.stdin.flush()

    def request(self, method: str, params: Any) -> Any:
        self.next_id += 1
        rid = self.next_id
        self.send({"id": rid, "method": method, "params": params})
        return self.wait(lambda m: m.get("id") == rid and "method" not in m).get("result")

    def wait(self, pred: Any, timeout_s: float = 120.0) -> dict[str, Any]:
        end = time.monotonic() + timeout_s
        while True:
            msg = self.inbox.get(timeout=max(0.01, end - time.monotonic()))
            if "method" in msg and "id" in msg:  # a request from the server: answer it
                self.send({"id": msg["id"], "result": None})
            if pred(msg):
                return msg

    def close(self) -> None:
        self.request("shutdown", None)
        self.send({"method": "exit"})
        self.proc.wait(timeout=10)


def diagnostics_of(uri: str, version: int) -> Any:
    def pred(m: dict[str, Any]) -> bool:
        p = m.get("params") or {}
        return bool(m.get("method") == "textDocument/publishDiagnostics" and p.get("uri") == uri
                    and p.get("version") == version)

    return pred


def load() -> str:
    one, five, _ = os.getloadavg()
    return f"load average {one:.2f} (1 min), {five:.2f} (5 min) on {os.cpu_count()} CPUs"


def children_cpu_s() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def startup_s(cmd: list[str], options: dict[str, Any] | None = None) -> tuple[float, Client]:
    t0 = time.perf_counter()
    c = Client(cmd)
    c.request("initialize", {"processId": os.getpid(), "rootUri": None, "capabilities": {},
                             "initializationOptions": options or {}})
    return time.perf_counter() - t0, c


def compare_startup(runs: int = 3) -> None:
    """Wall time to the initialize answer, and the CPU seconds of the whole short session
    (start, initialize, shutdown: steadier than wall time on a loaded machine)."""
    walls: dict[str, list[float]] = {"cncc": [], "bare": []}
    cpus: dict[str, list[float]] = {"cncc": [], "bare": []}
    cmds = {"cncc": [sys.executable, "-m", "cncc", "lsp"], "bare": [sys.executable, "-c", BARE_SERVER]}
    for _ in range(runs):
        for name, cmd in cmds.items():
            cpu0 = children_cpu_s()
            t, c = startup_s(cmd)
            c.close()
            walls[name].append(t)
            cpus[name].append(children_cpu_s() - cpu0)
    a, b = statistics.median(walls["cncc"]), statistics.median(walls["bare"])
    ca, cb = statistics.median(cpus["cncc"]), statistics.median(cpus["bare"])
    print(f"start-up to the initialize answer (median of {runs}): cncc lsp {a * 1000:.0f} ms, "
          f"bare pygls server {b * 1000:.0f} ms -> {a / b:.2f}x (goal <= 1.5x); "
          f"CPU of the session: {ca:.2f} s vs {cb:.2f} s -> {ca / cb:.2f}x")


def import_times() -> None:
    """``python -X importtime`` of what ``cncc lsp`` imports before ``initialize`` beside pygls'
    server module; names any heavy module imported that early."""
    def total_us(stmt: str, module: str) -> tuple[int, str]:
        err = subprocess.run([sys.executable, "-X", "importtime", "-c", stmt], capture_output=True,
                             text=True, check=True).stderr
        last = [ln for ln in err.splitlines() if ln.rstrip().endswith(f"| {module}")]
        return (int(last[-1].split("|")[1]) if last else 0), err

    ours, err = total_us("import cncc.lsp.server, cncc.lsp.features", "cncc.lsp.server")
    theirs, _ = total_us("import pygls.lsp.server", "pygls.lsp.server")
    early = [m for m in ("numpy", "lark", "cncc.frontend", "cncc.dialects", "cncc.driver", "cncc.passes")
             if f" {m}\n" in err + "\n" or f"| {m}\n" in err + "\n"]
    print(f"import before initialize (-X importtime): cncc.lsp.server {ours / 1000:.0f} ms, "
          f"pygls.lsp.server {theirs / 1000:.0f} ms" + (f"; also imported: {', '.join(early)}" if early else
                                                          "; no compiler module, numpy or lark"))


def full_compile(path: str) -> tuple[float, float]:
    """(wall s, CPU s) of ``cncc -fsyntax-only path``."""
    cpu0 = children_cpu_s()
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-m", "cncc", "-fsyntax-only", "-x", "syntec", path],
                   check=False, capture_output=True)
    return time.perf_counter() - t0, children_cpu_s() - cpu0


def one_edit(c: Client, uri: str, lines: list[str], line: int, insert: bool, version: int) -> float:
    """Change one character on ``line`` (a digit after its decimal point); seconds to the
    first publication of the new version."""
    col = lines[line].find(".") + 1
    if col <= 0:
        col = len(lines[line])
    if insert:
        new, end = "5", col
        lines[line] = lines[line][:col] + new + lines[line][col:]
    else:
        old = lines[line][col:col + 1]
        new, end = ("1" if old != "1" else "2"), col + 1
        lines[line] = lines[line][:col] + new + lines[line][col + 1:]
    t = time.perf_counter()
    c.send({"method": "textDocument/didChange", "params": {
        "textDocument": {"uri": uri, "version": version},
        "contentChanges": [{"range": {"start": {"line": line, "character": col},
                                      "end": {"line": line, "character": end}}, "text": new}]}})
    c.wait(diagnostics_of(uri, version))
    return time.perf_counter() - t


def bench_size(c: Client, n_lines: int, edits: int, machine: str, version: list[int]) -> None:
    text = cam_program(n_lines)
    lines = text.split("\n")
    with tempfile.NamedTemporaryFile("w", suffix=".nc", delete=False, encoding="utf-8") as f:
        f.write(text)
        path = f.name
    try:
        wall, cpu = full_compile(path)
    finally:
        os.unlink(path)
    uri = f"file:///bench/cam{n_lines}.nc"
    version[0] += 1
    t = time.perf_counter()
    c.send({"method": "textDocument/didOpen", "params": {"textDocument": {
        "uri": uri, "languageId": "gcode", "version": version[0], "text": text}}})
    first = c.wait(diagnostics_of(uri, version[0]))
    print(f"{len(lines)} lines: open -> first diagnostics {(time.perf_counter() - t) * 1000:.0f} ms "
          f"({len(first['params']['diagnostics'])} diagnostics); "
          f"cncc -fsyntax-only of the same file: {wall * 1000:.0f} ms wall, {cpu:.2f} CPU s")
    if machine:
        t = time.perf_counter()
        second = c.wait(diagnostics_of(uri, version[0]))  # the second phase of the opened version
        found = second["params"]["diagnostics"]
        kinds = sorted({str(d.get("code")) for d in found})
        print(f"  second phase ({machine}) published {(time.perf_counter() - t) * 1000:.0f} ms later: "
              f"{len(found)} diagnostics ({', '.join(kinds)})")
    where = {"start": 10, "middle": len(lines) // 2, "end": len(lines) - 4}
    all_ms: list[float] = []
    machine_ms: list[float] = []
    for label, line in where.items():
        samples = []
        for k in range(edits):
            version[0] += 1
            samples.append(one_edit(c, uri, lines, line, insert=k % 2 == 1, version=version[0]) * 1000)
            if machine:  # the next publication: the changed region's machine checks (or the full phase)
                t = time.perf_counter()
                c.wait(diagnostics_of(uri, version[0]))
                machine_ms.append((time.perf_counter() - t) * 1000 + samples[-1])
        all_ms += samples
        print(f"  edit at the {label:6} -> first diagnostics: median {statistics.median(samples):.0f} ms, "
              f"best {min(samples):.0f}, worst {max(samples):.0f} ({len(samples)} edits)")
    med = statistics.median(all_ms)
    ratio = med / (wall * 1000)
    goal = "goal <= 0.1x on 100k lines" if n_lines >= 100_000 else "goal < 300 ms on 10k lines"
    print(f"  median of all edits {med:.0f} ms = {ratio:.3f}x the full compile ({goal})")
    if machine_ms:
        print(f"  edit -> machine checks published: median {statistics.median(machine_ms):.0f} ms "
              f"(best {min(machine_ms):.0f}, worst {max(machine_ms):.0f})")
    c.send({"method": "textDocument/didClose", "params": {"textDocument": {"uri": uri}}})


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--sizes", default="10000,100000", help="program sizes in lines, comma-separated")
    ap.add_argument("--lines", type=int, default=0, help="one size only (overrides --sizes)")
    ap.add_argument("--edits", type=int, default=6, help="edits at each of start, middle and end")
    ap.add_argument("--machine", default="", help="configure this machine: the second phase runs")
    ap.add_argument("--opt-level", type=int, default=0, help="planner level of the second phase")
    args = ap.parse_args()
    sizes = [args.lines] if args.lines else [int(s) for s in args.sizes.split(",") if s]
    print(f"before: {load()}")
    compare_startup()
    import_times()
    options: dict[str, Any] = {"debounce_ms": 0, "budget_s": 60}
    if args.machine:
        options.update(machine=args.machine, opt_level=args.opt_level)
    log = ["--log", os.environ["CNCC_LSP_LOG"]] if os.environ.get("CNCC_LSP_LOG") else []  # the server's own times
    _, c = startup_s([sys.executable, "-m", "cncc", "lsp", *log], options)
    c.send({"method": "initialized", "params": {}})
    version = [0]
    for n in sizes:
        bench_size(c, n, args.edits, args.machine, version)
    c.close()
    print(f"after: {load()}")


if __name__ == "__main__":
    main()
