"""Parsing in several threads at once gives the same blocks (and spans) as one thread.

The language server runs analyses in threads; the parser's cached lark transformer must
not carry one thread's line offset into another thread's nodes.
"""

from __future__ import annotations

import threading
from pathlib import Path
from typing import Any

from cncc.diagnostics import DiagnosticSink
from cncc.dialects import load_dialect
from cncc.frontend.parser import Parser
from cncc.source import SourceMap

ROOT = Path(__file__).resolve().parents[2]
THREADS = 4
ROUNDS = 2

# Lines that take the grammar path (expressions, statements, comments, malformed numbers).
MACRO_LINES = ["#1=[#2+3.5]*SIN[30.]", "IF[#1 GT 2.]GOTO10", "N10 G01 X[#1+1.] Y-2.5 F#3 (cut)",
               "WHILE[#1 LT 10]DO1", "#[#1+100]=-#1", "END1", "G65 P9001 A1. B-2.", "G01 X1.2.3 Y2 F100",
               "G01 X-[ABS[#5]] Y#[#6] (x) (y)"]


def _programs() -> list[tuple[str, str]]:
    out = [("syntec", "\n".join(f"N{i} " + MACRO_LINES[i % len(MACRO_LINES)] for i in range(1, 400)) + "\n"),
           ("fanuc", "\n".join("   " * (i % 4) + MACRO_LINES[i % len(MACRO_LINES)] for i in range(400)) + "\n")]
    for name, dialect in [("szgh_macro.nc", "szgh"), ("series8_part.nc", "series8"),
                          ("linuxcnc_pocket.ngc", "linuxcnc"), ("fanuc_bolt_circle.nc", "fanuc")]:
        text = (ROOT / "examples" / name).read_text(encoding="utf-8")
        out.append((dialect, text * 4))
    return out


def _parse(dialect: str, text: str) -> tuple[list[Any], list[Any]]:
    sm = SourceMap()
    src = sm.add("t.nc", text)
    sink = DiagnosticSink()
    blocks = list(Parser(load_dialect(dialect), sink).blocks(src))
    return blocks, [(d.code, d.span) for d in sink]


def test_concurrent_parsing_matches_sequential() -> None:
    programs = _programs()
    expected = [_parse(d, t) for d, t in programs]
    assert all(blocks for blocks, _ in expected)
    assert any(diags for _, diags in expected)  # the malformed numbers are reported with spans
    got: dict[tuple[int, int], tuple[list[Any], list[Any]]] = {}
    barrier = threading.Barrier(THREADS)
    errors: list[BaseException] = []

    def work(k: int) -> None:
        try:
            barrier.wait()
            for r in range(ROUNDS):
                for j in range(len(programs)):
                    p = (j + k) % len(programs)  # threads parse different programs at the same time
                    got[(k, r * len(programs) + p)] = _parse(*programs[p])
        except BaseException as exc:  # reported below
            errors.append(exc)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(THREADS)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors
    assert len(got) == THREADS * ROUNDS * len(programs)
    for (_k, i), result in got.items():
        assert result == expected[i % len(programs)]
