"""The batch path (cncc/ir/batch.py) and the command path give the same outputs and diagnostics.

``compile_files`` streams batches of moves from the front end through the passes into the
backends; with ``driver.front_end_items`` replaced by the command-only front end, every stage
sees commands.  Both runs must print the same canon trace, G-code (several targets), IR text
and timing report, and report the same diagnostics, on the corpus, the examples and generated
programs (plain rasters, arcs, G68 + G51 + G41, mode switches every few blocks, start
positions, offsets).
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from cncc import driver
from cncc.dialects import load_dialect
from cncc.frontend.fastpath import is_straight_line

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench"))
from pipeline import program  # noqa: E402

EMITS: list[list[str]] = [["--emit=canon"], ["--emit=ir"], ["--emit=gcode"], ["-t", "grbl", "--emit=gcode"],
                          ["-t", "fanuc", "--emit=gcode"], ["-t", "linuxcnc", "--emit=gcode"],
                          ["--emit=timing", "-O0", "--report-format=json"], ["-fsyntax-only"]]


def run(path: Path, args: list[str], monkeypatch: pytest.MonkeyPatch, batches: bool,
        start: tuple[float, ...] | None = None) -> tuple[str, list[object]]:
    from cncc.cli import _parser, build_options

    parser = _parser()
    opts = build_options(parser.parse_intermixed_args([*args, str(path)]), parser.error)
    opts.start_machine_mm = start
    with monkeypatch.context() as m:
        if not batches:
            m.setattr(driver, "front_end_items", driver.front_end)
        result = driver.compile_files(opts)
    return result.output, [(d.code, d.span, d.message) for d in result.sink]


def agree(path: Path, args: list[str], monkeypatch: pytest.MonkeyPatch, start: tuple[float, ...] | None = None) -> None:
    with_batches = run(path, args, monkeypatch, True, start)
    without = run(path, args, monkeypatch, False, start)
    assert with_batches[0] == without[0], (path, args)
    assert with_batches[1] == without[1], (path, args)


@pytest.mark.parametrize("kind", ["plain", "arcs", "transformed"])
def test_bench_programs(kind: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    path = tmp_path / f"{kind}.nc"
    path.write_text(program(kind, 3000))
    tools = tmp_path / "tools.toml"
    tools.write_text('units = "mm"\n[tools.1]\nlength_mm = 2.5\nradius_mm = 0.2\n')
    for args in EMITS:
        agree(path, ["-x", "syntec", "--tools", str(tools), *args], monkeypatch)


def test_with_offsets_and_tool_length(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    body = "\n".join(f"G1 X{i * 0.37:.3f} Y{(i % 7) * 0.11:.3f} Z-1.{i % 10}" + (" F800" if i % 50 == 0 else "")
                     for i in range(400))
    path = tmp_path / "offsets.nc"
    path.write_text(f"G90 G17 G21 G94\nG55\nG43 H1 G0 Z5.\nG1 Z-1. F1200\n{body}\nG92 X1 Y2\n{body}\nM30\n")
    offsets = tmp_path / "offsets.toml"
    offsets.write_text('units = "mm"\n[work.G54]\nX = 10.0\n[work.G55]\nX = 100.3\nY = -50.7\nZ = 3.3\n')
    tools = tmp_path / "tools.toml"
    tools.write_text('units = "mm"\n[tools.1]\nlength_mm = 12.5\nradius_mm = 1.0\n')
    for args in EMITS:
        agree(path, ["-x", "syntec", "--offsets", str(offsets), "--tools", str(tools), *args], monkeypatch)


@pytest.mark.usefixtures("small_chunks")
def test_corpus_and_examples(monkeypatch: pytest.MonkeyPatch) -> None:
    files = [(p, "syntec") for p in sorted((ROOT / "examples").glob("*.nc"))]
    for folder in ("fanuc", "syntec", "haas"):
        files += [(p, folder) for p in sorted((ROOT / "tests" / "corpus" / folder).iterdir()) if p.is_file()]
    checked = 0
    for path, dialect in files:
        if not is_straight_line(path.read_text(errors="replace"), load_dialect(dialect)):
            continue
        for args in EMITS:
            agree(path, ["-x", dialect, *args], monkeypatch)
        checked += 1
    assert checked >= 3


plain = st.tuples(st.sampled_from(["", "G1 ", "G0 ", "G01 "]),
                  st.lists(st.tuples(st.sampled_from("XYZ"), st.decimals(-99, 99, places=4).map(str)),
                           min_size=1, max_size=3, unique_by=lambda t: t[0]),
                  st.sampled_from(["", "", "", " F100", " F2500.", " F12.5"])).map(
    lambda t: t[0] + " ".join(a + v for a, v in t[1]) + t[2])
arc = st.sampled_from(["G2 X1. Y1. I0.5 J0.5", "G3 X0 Y0 I-0.5 J-0.5", "G3 X2. Y0 I1. J0 F400", "G02 X0 Y0 I1. J0"])
mode = st.sampled_from(["G90", "G91", "G17", "G18", "G20", "G21", "G94", "F800", "G68 X0 Y0 R30", "G69",
                        "G51 X0 Y0 P0.5", "G50", "G51.1 X0", "G50.1 X0", "G41 D1", "G40", "G55", "G54", "G92 X1 Y1",
                        "G43 H1", "G49", "(note)", "M08", "G0 X0 Y0 Z1.", "G1 Z-1. F300", "G64", "G61"])
runs = st.lists(st.tuples(mode, st.lists(st.one_of(plain, plain, plain, arc), min_size=0, max_size=10)),
                min_size=1, max_size=8).map(
    lambda blocks: "G21 G17 G90 G94 F1000\n" + "\n".join(m + "\n" + "\n".join(ls) for m, ls in blocks) + "\nM30\n")


@pytest.mark.usefixtures("small_chunks")
@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(runs, st.sampled_from(EMITS[:7]), st.sampled_from([None, (0.0, 0.0, 0.0), (12.5, -3.0, 40.0)]))
def test_generated_programs(tmp_path_factory: pytest.TempPathFactory, monkeypatch: pytest.MonkeyPatch,
                            text: str, args: list[str], start: tuple[float, ...] | None) -> None:
    folder = tmp_path_factory.mktemp("gen")
    path = folder / "gen.nc"
    path.write_text(text)
    tools = folder / "tools.toml"
    tools.write_text('units = "mm"\n[tools.1]\nlength_mm = 5.0\nradius_mm = 0.5\n')
    agree(path, ["-x", "syntec", "--tools", str(tools), *args], monkeypatch, start)
