"""Shared by the HTML timing page tests: build a report, read the page's data back."""

from __future__ import annotations

import base64
import json
import re
import sys
from dataclasses import dataclass
from functools import cache
from pathlib import Path
from typing import Any

import numpy as np

from cncc.api import compile_commands
from cncc.backends.timing.aggregate import build_report
from cncc.backends.timing.html import render_html
from cncc.backends.timing.model import TimingReport
from cncc.diagnostics import DiagnosticSink
from cncc.driver import Options, resolve_machine, timing_runs
from cncc.ir import Command

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "contour.nc"
sys.path.insert(0, str(ROOT / "bench"))

from gen import shop_program  # noqa: E402

BIG_LINES = 100_000
BIG_LEVEL = 1  # the -O2 planner takes many minutes on this job; -O1 plans it in seconds


@dataclass
class Built:
    text: str
    cmds: list[Command]
    rep: TimingReport
    page: str

    def data(self) -> dict[str, Any]:
        m = re.search(r'<script type="application/json" id="cncc-data">(.*?)</script>', self.page, re.S)
        assert m is not None
        doc: dict[str, Any] = json.loads(m.group(1))
        return doc


def build(text: str, level: int) -> Built:
    cmds, res = compile_commands(text)
    assert res.ok, [d.message for d in res.sink]
    sink = DiagnosticSink()
    machine = resolve_machine("generic-mill", sink)
    assert machine is not None
    runs = timing_runs(cmds, machine, Options(opt_level=level), sink)
    rep = build_report(cmds, runs, res.sources, "job.nc", "syntec")
    return Built(text, cmds, rep, render_html(rep, cmds))


@cache
def contour() -> Built:
    return build(EXAMPLE.read_text(), 2)


@cache
def big() -> Built:
    return build(shop_program(BIG_LINES), BIG_LEVEL)


def arr(s: str, dtype: str) -> Any:
    return np.frombuffer(base64.b64decode(s), dtype=np.dtype(dtype).newbyteorder("<"))


def line_of(text: str, needle: str, last: bool = False) -> int:
    """1-based number of the first (or last) line of ``text`` containing ``needle``."""
    hits = [k for k, ln in enumerate(text.splitlines(), 1) if needle in ln]
    assert hits, needle
    return hits[-1] if last else hits[0]
