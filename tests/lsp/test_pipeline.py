"""The first phase's pipeline (frame passes started at the first frame that needs them) gives
the same commands and diagnostics as the driver's whole pipeline."""

from __future__ import annotations

from pathlib import Path

import pytest

from cncc import driver
from cncc.diagnostics import DiagnosticSink
from cncc.dialects import load_dialect
from cncc.ir import Command
from cncc.lsp.pipeline import _split, transforms
from cncc.source import SourceMap

CORPUS = sorted(p for p in (Path(__file__).parents[1] / "translate" / "corpus").glob("*/*") if p.is_file())
MIXED = {
    "rotation_after_plain_moves": "G90 G00 X0 Y0\nG01 X10. Y0 F300.\nG03 X0 Y10. R10.\nG68 X0 Y0 R30.\n"
                                  "G01 X20. Y5.\nG02 X25. Y10. R5.\nG69\nG01 X0 Y0\nM30\n",
    "comp_in_the_middle": "G90 G00 X-5. Y-5.\nG01 X0 Y0 F200.\nG41 D1 G01 X5. Y0\nG01 X20.\nG01 Y20.\n"
                          "G40 G01 X30. Y30.\nG01 X0 Y0\nM30\n",
    "work_offsets_and_cycles": "G90 G54 G00 X0 Y0 Z10.\nG55 G00 X5. Y5.\nG81 X10. Y10. Z-3. R2. F100.\n"
                               "X20.\nG80\nG52 X3. Y3.\nG01 X1. Y1. F500.\nG52 X0 Y0\nG02 X11. Y1. I5. J0\nM30\n",
    "scaling_then_plain": "G90 G00 X0 Y0\nG51 X0 Y0 P2000\nG01 X5. Y5. F100.\nG50\nG01 X20. Y0\nM30\n",
}


def both(text: str, dialect_name: str, tools: str | None = None) -> tuple[tuple[list[Command], list[str]], ...]:
    dialect = load_dialect(dialect_name)
    machine = driver.default_machine()
    out = []
    for split in (False, True):
        sink = DiagnosticSink()
        src = SourceMap().add("prog.nc", text)
        opts = driver.Options(inputs=["prog.nc"], dialect=dialect_name, tools_file=tools)
        cmds = driver.front_end(src, dialect, machine, opts, sink)
        stream = _split(cmds, dialect, machine, opts, sink) if split else driver.path_passes(
            cmds, dialect, machine, opts, sink)
        got = list(stream)
        out.append((got, sorted(f"{d.code} {d.span} {d.message}" for d in sink)))
    return out[0], out[1]


@pytest.mark.parametrize("path", CORPUS, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_corpus_programs_compile_alike(path: Path) -> None:
    whole, split = both(path.read_text(encoding="utf-8"), path.parent.name)
    assert split == whole


@pytest.mark.parametrize("name", sorted(MIXED))
def test_programs_that_switch_transforms_on_compile_alike(name: str, tmp_path: Path) -> None:
    tools = tmp_path / "tools.tbl"
    tools.write_text("T1 P1 D6.0 Z0\n", encoding="utf-8")
    whole, split = both(MIXED[name], "syntec", str(tools))
    assert split == whole
    assert len(whole[0]) > 3


def test_the_mixed_programs_do_switch() -> None:
    """Each mixed program starts plain and later has a frame that needs the frame passes (so
    the tests above compare the switch itself, not two plain runs)."""
    dialect = load_dialect("syntec")
    machine = driver.default_machine()
    for name, text in MIXED.items():
        src = SourceMap().add("prog.nc", text)
        cmds = list(driver.front_end(src, dialect, machine, driver.Options(dialect="syntec"), DiagnosticSink()))
        flags = [transforms(c.frame) for c in cmds]
        if name == "work_offsets_and_cycles":
            assert not any(flags)  # offsets and cycles only: the start-point linking is what is compared
        else:
            assert not flags[0] and any(flags), name
