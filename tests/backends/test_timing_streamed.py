"""The streamed -O0 timing report (cncc/backends/timing/streamed.py) against the command-list path.

``compile_files`` makes the ``--emit=timing -O0`` text and JSON reports while the commands and
batches stream (:func:`cncc.backends.timing.streamable`); with ``keep_trajectory`` it makes them
the way it always did -- a command list, the nominal trajectory, ``build_report``.  Both must
print the same report, byte for byte, and the same diagnostics, on the corpus, the examples and
generated programs that switch modes, tools, spindle and events every few blocks.  The helper
classes of :mod:`cncc.backends.timing.linecols` are checked against dense tables and
``str.split``.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from cncc import driver
from cncc.backends.timing import streamed
from cncc.backends.timing.linecols import LineStarts, SourceLines, SparseRows
from cncc.source import SourceMap

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench"))
from pipeline import program  # noqa: E402

FORMATS = [["--report-format=json"], ["--report-format=text"]]


def run(path: Path, args: list[str], keep: bool) -> tuple[str, list[object]]:
    from cncc.cli import _parser, build_options

    parser = _parser()
    opts = build_options(parser.parse_intermixed_args([*args, str(path)]), parser.error)
    opts.keep_trajectory = keep
    result = driver.compile_files(opts)
    return result.output, [(d.code, d.span, d.message) for d in result.sink]


def agree(path: Path, args: list[str], monkeypatch: pytest.MonkeyPatch) -> None:
    calls: list[int] = []
    real = streamed.streamed_report

    def spy(*a: object, **k: object) -> object:
        calls.append(1)
        return real(*a, **k)  # type: ignore[arg-type]

    with monkeypatch.context() as m:
        m.setattr(streamed, "streamed_report", spy)
        new = run(path, ["--emit=timing", "-O0", *args], keep=False)
        old = run(path, ["--emit=timing", "-O0", *args], keep=True)
    assert calls, "the streamed path was not taken"
    assert new[0] == old[0], (path, args)
    assert new[1] == old[1], (path, args)


@pytest.mark.parametrize("kind", ["plain", "arcs", "transformed"])
def test_bench_programs(kind: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    path = tmp_path / f"{kind}.nc"
    path.write_text(program(kind, 5000))
    tools = tmp_path / "tools.toml"
    tools.write_text('units = "mm"\n[tools.1]\nlength_mm = 2.5\nradius_mm = 0.2\n')
    for fmt in FORMATS:
        agree(path, ["-x", "syntec", "--tools", str(tools), *fmt], monkeypatch)


@pytest.mark.usefixtures("small_chunks")
def test_corpus_and_examples(monkeypatch: pytest.MonkeyPatch) -> None:
    files = [(p, "syntec") for p in sorted((ROOT / "examples").glob("*.nc"))]
    for folder in ("fanuc", "syntec", "haas", "linuxcnc", "grbl", "series8", "szgh"):
        if (ROOT / "tests" / "corpus" / folder).is_dir():
            files += [(p, folder) for p in sorted((ROOT / "tests" / "corpus" / folder).iterdir()) if p.is_file()]
    for path, dialect in files:
        agree(path, ["-x", dialect, "--report-format=json"], monkeypatch)
    assert len(files) >= 10


@pytest.mark.parametrize("machine", ["generic-mill", "syntec-900m", "szgh-990mdb"])
def test_machines_and_events(machine: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Tool changes, spindle starts and speed changes, dwells, stops, independent rapids (szgh)."""
    body = "\n".join(f"G1 X{i * 0.5:.3f} Y{(i % 9) * 0.25:.3f} Z-1.{i % 10}" for i in range(300))
    path = tmp_path / "events.nc"
    path.write_text(f"G90 G17 G21 G94\nT1 M06\nS1000 M03\nG0 X0 Y0 Z5.\nG1 Z-1. F900\n{body}\nG4 P2.5\n"
                    f"G0 X30. Y-20. Z40.\nS1500\nM01\nT2 M06\nM04 S900\nG0 X1 Y1 Z1\n{body}\nM00\n"
                    f"G3 X0 Y0 I-5. J0 F300\nM05\nM30\n")
    for fmt in FORMATS:
        agree(path, ["-x", "syntec", "-m", machine, *fmt], monkeypatch)


def test_clamped_times(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Absurd feeds and dwells: the same clamped sums and the same E-code on the same span."""
    path = tmp_path / "clamp.nc"
    path.write_text("G90 G21 G94\nG1 X1000000. F0.00001\nG1 X0 F1000\nG4 P99999999999.\nG4 P5.\nM30\n")
    agree(path, ["-x", "syntec", "--report-format=json"], monkeypatch)
    _out, diags = run(path, ["-x", "syntec", "--emit=timing", "-O0", "--report-format=json"], keep=False)
    assert "W0690" in [code for code, _span, _msg in diags]


plain = st.tuples(st.sampled_from(["", "G1 ", "G0 ", "G01 "]),
                  st.lists(st.tuples(st.sampled_from("XYZ"), st.decimals(-99, 99, places=4).map(str)),
                           min_size=1, max_size=3, unique_by=lambda t: t[0]),
                  st.sampled_from(["", "", "", " F100", " F2500.", " F12.5"])).map(
    lambda t: t[0] + " ".join(a + v for a, v in t[1]) + t[2])
arc = st.sampled_from(["G2 X1. Y1. I0.5 J0.5", "G3 X0 Y0 I-0.5 J-0.5", "G3 X2. Y0 I1. J0 F400", "G02 X0 Y0 I1. J0",
                       "G2 X0 Y0 Z-2. I1. J0 F700"])
mode = st.sampled_from(["G90", "G91", "G17", "G18", "G20", "G21", "G94", "F800", "G68 X0 Y0 R30", "G69",
                        "G51 X0 Y0 P0.5", "G50", "G41 D1", "G40", "G55", "G54", "G92 X1 Y1", "G43 H1", "G49",
                        "(note)", "M08", "G0 X0 Y0 Z1.", "G1 Z-1. F300", "G64", "G61", "T2 M06", "S3000 M03",
                        "S1200", "M05", "G4 P0.5", "M01", "N100 G1 X3.", "G1 X0 F0.5", "G0 A30."])
runs = st.lists(st.tuples(mode, st.lists(st.one_of(plain, plain, plain, arc), min_size=0, max_size=10)),
                min_size=1, max_size=8).map(
    lambda blocks: "G21 G17 G90 G94 F1000\n" + "\n".join(m + "\n" + "\n".join(ls) for m, ls in blocks) + "\nM30\n")


@pytest.mark.usefixtures("small_chunks")
@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(runs, st.sampled_from(FORMATS), st.sampled_from(["generic-mill", "szgh-990mdb"]))
def test_generated_programs(tmp_path_factory: pytest.TempPathFactory, monkeypatch: pytest.MonkeyPatch,
                            text: str, fmt: list[str], machine: str) -> None:
    folder = tmp_path_factory.mktemp("gen")
    path = folder / "gen.nc"
    path.write_text(text)
    tools = folder / "tools.toml"
    tools.write_text('units = "mm"\n[tools.1]\nlength_mm = 5.0\nradius_mm = 0.5\n[tools.2]\nlength_mm = 7.0\n')
    agree(path, ["-x", "syntec", "-m", machine, "--tools", str(tools), *fmt], monkeypatch)


@given(st.lists(st.tuples(st.integers(0, 9), st.integers(0, 5), st.integers(-50, 50)), max_size=40),
       st.integers(0, 10), st.integers(0, 10))
def test_sparse_rows_are_the_dense_table(entries: list[tuple[int, int, int]], lo: int, hi: int) -> None:
    dense = np.zeros((10, 6), dtype=np.int64)
    keep: dict[tuple[int, int], int] = {}
    for r, c, v in entries:
        keep[(r, c)] = v
    for (r, c), v in keep.items():
        dense[r, c] = v
    rows = SparseRows(10, 6, np.asarray([r for r, _ in keep], dtype=np.int64).reshape(-1),
                      np.asarray([c for _, c in keep], dtype=np.int64).reshape(-1),
                      np.asarray(list(keep.values()), dtype=np.int64).reshape(-1))
    assert rows[lo:hi].tolist() == dense[lo:hi].tolist()
    for k in range(10):
        assert rows[k].tolist() == dense[k].tolist()
    assert rows[-1].tolist() == dense[-1].tolist()


@given(st.text(alphabet="G1 X.5\n\r\tN0n\x1cé/", max_size=60), st.lists(st.integers(-1, 12), max_size=12))
def test_source_lines_are_split_lines(text: str, lines: list[int]) -> None:
    sources = SourceMap()
    src = sources.add("p.nc", text)
    split = text.split("\n")
    raw = [split[k - 1].rstrip("\r") if 1 <= k <= len(split) else "" for k in lines]
    want = [r.strip() for r in raw]
    got = SourceLines(LineStarts(sources), np.full(len(lines), src.source_id), np.asarray(lines, dtype=np.int64),
                      "text")
    assert list(got) == want
    assert got[:] == want
    numbers = [m.group(1).replace(" ", "").upper() if (m := re.match(r"\s*/?\s*([Nn]\s*\d+)", r)) else ""
               for r in raw]
    assert list(SourceLines(LineStarts(sources), np.full(len(lines), src.source_id),
                            np.asarray(lines, dtype=np.int64), "n")) == numbers
    assert LineStarts(sources).of(src.source_id).tolist() == src.line_starts  # type: ignore[union-attr]
