"""Batches of moves (cncc/ir/batch.py) stand for exactly the commands of the per-line fast path.

The chunk lowering (:func:`cncc.frontend.fastbatch.lower_batched`) must give, once its batches
are expanded, the same commands and diagnostics as :func:`cncc.frontend.fastpath.lower_straight`
(which ``test_fastpath.py`` compares with the grammar and interpreter), on the corpus, the
examples, the bench programs and generated programs that switch modes every few blocks.
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from cncc.diagnostics import DiagnosticSink
from cncc.dialects import load_dialect
from cncc.frontend import fastbatch
from cncc.frontend.fastpath import is_straight_line, lower_straight
from cncc.frontend.interp import InterpOptions
from cncc.ir.batch import MoveBatch, command_count, expand
from cncc.source import SourceMap

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench"))
from gen import cam_program  # noqa: E402
from pipeline import program  # noqa: E402


def both(text: str, dialect: str = "syntec", start: tuple[float, ...] = (0.0,) * 6) -> tuple[int, bool]:
    """(number of batches, whether both paths agree on commands and diagnostics)."""
    d = load_dialect(dialect)
    src = SourceMap().add("t.nc", text)
    s1, s2 = DiagnosticSink(), DiagnosticSink()
    line = list(lower_straight(src, d, s1, InterpOptions(start_mm=start)))  # type: ignore[arg-type]
    items = list(fastbatch.lower_batched(src, d, s2, InterpOptions(start_mm=start, batches=True)))  # type: ignore[arg-type]
    batched = list(expand(items))
    assert command_count(items) == len(batched)
    same = line == batched and [(x.code, x.span, x.message) for x in s1] == [(x.code, x.span, x.message) for x in s2]
    return sum(isinstance(x, MoveBatch) for x in items), same


@pytest.fixture
def small_chunks(monkeypatch: pytest.MonkeyPatch) -> None:
    """Hand over to chunks after 2 plain lines, chunks from 64 characters: every seam is exercised."""
    monkeypatch.setattr(fastbatch, "STREAK", 2)
    monkeypatch.setattr(fastbatch, "MIN_CHUNK", 64)
    monkeypatch.setattr(fastbatch, "MAX_CHUNK", 512)


@pytest.mark.parametrize("kind", ["plain", "arcs", "transformed"])
def test_bench_programs(kind: str) -> None:
    n, same = both(program(kind, 20_000))
    assert n > 0 and same


def test_cam_program() -> None:
    n, same = both(cam_program(20_000, seed=3))
    assert n > 0 and same


def corpus_files() -> list[tuple[Path, str]]:
    out = [(p, "syntec") for p in sorted((ROOT / "examples").glob("*.nc"))]
    for corpus in (ROOT / "tests" / "corpus", ROOT / "tests" / "translate" / "corpus"):
        for folder in sorted(corpus.iterdir()):
            if folder.is_dir() and folder.name in ("fanuc", "syntec", "haas", "szgh"):
                out += [(p, folder.name) for p in sorted(folder.iterdir()) if p.is_file()]
    return out


@pytest.mark.usefixtures("small_chunks")
def test_corpus_and_examples() -> None:
    checked = 0
    for path, dialect in corpus_files():
        text = path.read_text(encoding="utf-8", errors="replace")
        if not is_straight_line(text, load_dialect(dialect)):
            continue
        _, same = both(text, dialect)
        assert same, path
        checked += 1
    assert checked >= 3


num = st.one_of(
    st.integers(-99999, 99999).map(str),
    st.decimals(-999, 999, places=3, allow_nan=False, allow_infinity=False).map(lambda d: f"{d}"),
    st.integers(0, 999).map(lambda i: f"{i}."),
    st.sampled_from(["1.2.3", ".", "-0", "-0.", "+5", "0"]),
)
plain = st.tuples(st.sampled_from(["", "", "G1 ", "G0 ", "G01 ", "N20 G1 "]),
                  st.lists(st.tuples(st.sampled_from("XYZ"), num), min_size=0, max_size=3, unique_by=lambda t: t[0]),
                  st.sampled_from(["", "", "", " F100", " F2500.", " F0", " F12.5  "]),
                  st.sampled_from(["", "", "", ";", " ;", " (c)", "\r"])).map(
    lambda t: t[0] + " ".join(a + v for a, v in t[1]) + t[2] + t[3])
arc = st.tuples(st.sampled_from(["G2", "G3", "G02", ""]), num, num, num, num,
                st.sampled_from(["", " F300", " Z1."])).map(
    lambda t: f"{t[0]} X{t[1]} Y{t[2]} I{t[3]} J{t[4]}{t[5]}")
mode = st.sampled_from(["G90", "G91", "G17", "G18", "G20", "G21", "G70", "G71", "G94", "G95", "G16", "G15",
                        "G81 X1 Y1 Z-1 R1 F100", "G80", "M30", "M03 S1000", "G92 X1 Y2", "G54", "G55", "",
                        "(comment)", "G01 X1 Y2 Z3 A4 F5", "G51 X0 Y0 P2", "G50", "G68 X0 Y0 R30", "G69",
                        "G41 D1", "G40", "G28 X0", "G53 X1", "N30", "G00 X1.5 Y-2.25 Z3."])
runs = st.lists(st.tuples(mode, st.lists(st.one_of(plain, plain, plain, arc), min_size=0, max_size=12)),
                min_size=1, max_size=8).map(
    lambda blocks: "\n".join(m + "\n" + "\n".join(lines) for m, lines in blocks) + "\n")
start = st.sampled_from([(0.0,) * 6, (10.0, -5.0, 2.5, 0.0, 0.0, 0.0), (-0.0, 0.0, -0.0, 1.0, 2.0, 3.0)])


@pytest.mark.usefixtures("small_chunks")
@settings(max_examples=200, deadline=None)
@given(runs, st.sampled_from(["syntec", "fanuc"]), start)
def test_generated_programs_switching_modes(text: str, dialect: str, at: tuple[float, ...]) -> None:
    if not is_straight_line(text, load_dialect(dialect)):
        return
    _, same = both(text, dialect, at)
    assert same


@pytest.mark.usefixtures("small_chunks")
def test_long_runs_become_batches_across_mode_switches() -> None:
    body = []
    for k in range(40):
        body.append(["G90", "G91", "G90", "F500", "G17", "(c)", "G0 X0 Y0", "M08"][k % 8])
        body += [f"G1 X{(k * 7 + i) % 13}.{i} Y{i * 0.25:.2f} Z-1." for i in range(15)]
        body += [f"G3 X{i + 1}. Y0. I0.5 J0" for i in range(3)]
    n, same = both("G21 G17 F1000\n" + "\n".join(body) + "\n")
    assert n >= 20 and same
