"""Language server latency: start-up, and a one-character edit to published diagnostics.

    python bench/lsp.py [--lines 10000] [--edits 20] [--machine generic-mill] [--opt-level 0]

Starts ``cncc lsp`` as a subprocess and talks JSON-RPC to it over its stdin/stdout
(a minimal client, so the client's own overhead is not measured):

* **start-up**: from spawning the process to the answer of ``initialize``, and the
  ``-X importtime`` total of ``import cncc.lsp.server`` (goal: well under a second;
  no numpy, lark or solver module is imported before the first analysis);
* **edit -> diagnostics**: on a generated CAM-style program of ``--lines`` lines,
  the time from sending a ``didChange`` that changes one character to receiving the
  ``publishDiagnostics`` of that version (goal: < 300 ms at 10,000 lines).  The
  edits alternate between the middle and the end of the program.  The server's
  debounce is set to 0 here so the figure is the analysis itself plus the protocol.
"""

from __future__ import annotations

import argparse
import json
import os
import queue
import statistics
import subprocess
import sys
import threading
import time
from typing import Any

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gen import cam_program


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
        return self.wait(lambda m: m.get("id") == rid and "method" not in m)["result"]

    def wait(self, pred: Any, timeout_s: float = 60.0) -> dict[str, Any]:
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


def import_time_s() -> float:
    out = subprocess.run([sys.executable, "-X", "importtime", "-c", "import cncc.lsp.server"],
                         capture_output=True, text=True, check=True).stderr
    heavy = [m for m in ("numpy", "lark", "toppra", "casadi", "ruckig") if f"| {m}\n" in out or f" {m}\n" in out]
    if heavy:
        print(f"warning: imported at start-up: {', '.join(heavy)}")
    last = [ln for ln in out.splitlines() if ln.rstrip().endswith("cncc.lsp.server")][-1]
    return int(last.split("|")[1]) / 1e6


def load() -> str:
    one, five, _ = os.getloadavg()
    return f"load average {one:.2f} (1 min), {five:.2f} (5 min) on {os.cpu_count()} CPUs"


def edit_once(c: Client, uri: str, lines: list[str], k: int, version: int) -> float:
    """Change one digit (the middle or the end of the program); seconds to the first publication."""
    line = len(lines) // 2 if k % 2 == 0 else len(lines) - 3
    col = lines[line].find(".") + 1  # a digit after a decimal point: the program stays valid
    old = lines[line][col]
    new = "1" if old != "1" else "2"
    lines[line] = lines[line][:col] + new + lines[line][col + 1:]
    t = time.perf_counter()
    c.send({"method": "textDocument/didChange", "params": {
        "textDocument": {"uri": uri, "version": version},
        "contentChanges": [{"range": {"start": {"line": line, "character": col},
                                      "end": {"line": line, "character": col + 1}}, "text": new}]}})
    c.wait(diagnostics_of(uri, version))
    return time.perf_counter() - t


def summary(label: str, samples: list[float]) -> str:
    ms = sorted(s * 1000 for s in samples)
    return (f"{label}: median {statistics.median(ms):.0f} ms, best {ms[0]:.0f} ms, worst {ms[-1]:.0f} ms "
            f"({len(ms)} edits)")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--lines", type=int, default=10_000)
    ap.add_argument("--edits", type=int, default=20)
    ap.add_argument("--machine", default="", help="configure this machine: the second phase runs")
    ap.add_argument("--opt-level", type=int, default=0, help="planner level of the second phase")
    args = ap.parse_args()
    print(f"before: {load()}")
    options: dict[str, Any] = {"debounce_ms": 0, "budget_s": 30}
    if args.machine:
        options.update(machine=args.machine, opt_level=args.opt_level)
    t0 = time.perf_counter()
    c = Client([sys.executable, "-m", "cncc", "lsp"])
    c.request("initialize", {"processId": os.getpid(), "rootUri": None, "capabilities": {},
                             "initializationOptions": options})
    startup_s = time.perf_counter() - t0
    c.send({"method": "initialized", "params": {}})
    print(f"start-up to initialize answer: {startup_s * 1000:.0f} ms "
          f"(import cncc.lsp.server: {import_time_s() * 1000:.0f} ms)")

    text = cam_program(args.lines)
    lines = text.split("\n")
    uri = "file:///bench/cam.nc"
    t = time.perf_counter()
    c.send({"method": "textDocument/didOpen", "params": {"textDocument": {
        "uri": uri, "languageId": "gcode", "version": 1, "text": text}}})
    first = c.wait(diagnostics_of(uri, 1))
    print(f"open {len(lines)} lines -> first diagnostics: {(time.perf_counter() - t) * 1000:.0f} ms "
          f"({len(first['params']['diagnostics'])} diagnostics)")
    version = 1
    if args.machine:
        t = time.perf_counter()
        second = c.wait(diagnostics_of(uri, 1))
        print(f"  second phase ({args.machine}, -O{args.opt_level}) published "
              f"{(time.perf_counter() - t) * 1000:.0f} ms later ({len(second['params']['diagnostics'])} diagnostics)")
    samples = []
    for k in range(args.edits):
        version += 1
        samples.append(edit_once(c, uri, lines, k, version))
    print(summary(f"one-character edit -> diagnostics, {len(lines)} lines" +
                  (", the previous second phase running" if args.machine else ""), samples) + " (goal < 300 ms)")
    if args.machine:
        idle, second_s = [], []
        for k in range(args.edits):
            version += 1
            idle.append(edit_once(c, uri, lines, k, version))
            t = time.perf_counter()
            c.wait(diagnostics_of(uri, version))
            second_s.append(time.perf_counter() - t)
        print(summary("one-character edit -> diagnostics, idle server", idle))
        print(summary("  then the second phase's publication", second_s))
    c.close()
    print(f"after: {load()}")


if __name__ == "__main__":
    main()
