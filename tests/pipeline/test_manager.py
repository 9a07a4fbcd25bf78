"""The pass manager's instruments: --verify-each, --print-after, --time-passes."""

from __future__ import annotations

import json
import re
import time
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any, ClassVar

import pytest

from cncc import diagnostics as dg
from cncc.api import compile_text
from cncc.cli import main
from cncc.ir import Arc, Command, Linear, Rapid
from cncc.passes import Pass, PassContext
from cncc.pipeline import builder
from cncc.pipeline.manager import Clock
from cncc.source import Span
from tests.helpers import codes

CORPUS = sorted(p for p in (Path(__file__).parents[1] / "corpus").glob("*/*") if p.is_file())
PROGRAM = "G90 G54 G00 X0 Y0 Z10.\nG01 X10. F300.\nG01 Y10.\nG02 X20. Y0 R10.\nG01 X0 Y0\nM30\n"
DIALECT = {"haas": "fanuc"}


@dataclass(frozen=True, kw_only=True)
class DropSecondMotion(Pass):
    """A broken pass: loses the second motion (the path jumps)."""

    name: ClassVar[str] = "drop-second-motion"

    def run(self, cmds: Iterable[Command], ctx: PassContext) -> Iterator[Command]:
        n = 0
        for c in cmds:
            if isinstance(c, Rapid | Linear | Arc):
                n += 1
                if n == 2:
                    continue
            yield c


@dataclass(frozen=True, kw_only=True)
class StretchSpans(Pass):
    """A broken pass: spans end far past the end of the file."""

    name: ClassVar[str] = "stretch-spans"

    def run(self, cmds: Iterable[Command], ctx: PassContext) -> Iterator[Command]:
        for c in cmds:
            yield replace(c, span=Span(c.span.source_id, c.span.start, c.span.end + 10_000))


@dataclass(frozen=True, kw_only=True)
class AddOffset(Pass):
    """A broken pass after to-machine: puts a work offset back into the frames."""

    name: ClassVar[str] = "add-offset"

    def run(self, cmds: Iterable[Command], ctx: PassContext) -> Iterator[Command]:
        for c in cmds:
            yield replace(c, frame=replace(c.frame, work_offset_mm=(1.0, 0.0, 0.0, 0.0, 0.0, 0.0)))


def _inject(monkeypatch: pytest.MonkeyPatch, broken: Pass, after: str) -> None:
    real = builder.path_passes

    def with_broken(config: Any, dialect: Any) -> list[Pass]:
        out = real(config, dialect)
        i = [p.name for p in out].index(after)
        return [*out[:i + 1], broken, *out[i + 1:]]

    monkeypatch.setattr(builder, "path_passes", with_broken)


@pytest.mark.parametrize(("broken", "after", "emit", "invariant"), [
    (DropSecondMotion(), "expand-cycles", "canon", "continuity"),
    (StretchSpans(), "arc-check", "canon", "spans"),
    (AddOffset(), "to-machine", "timing", "frame"),
])
def test_verify_each_names_the_pass_that_broke_an_invariant(monkeypatch: pytest.MonkeyPatch, broken: Pass,
                                                            after: str, emit: str, invariant: str) -> None:
    _inject(monkeypatch, broken, after)
    quiet = compile_text(PROGRAM, emit=emit, compare="O1" if emit == "timing" else "")
    assert "E0992" not in codes(quiet)  # without --verify-each nobody looks
    r = compile_text(PROGRAM, emit=emit, verify_each=True, compare="O1" if emit == "timing" else "")
    found = [d for d in r.sink if d.code == "E0992"]
    assert found
    assert f"after pass '{broken.name}'" in found[0].message and f"[{invariant}]" in found[0].message
    assert not any(f"after pass '{after}'" in d.message for d in found)  # the pass before it is not blamed


def test_verify_each_blames_only_the_broken_pass_first(monkeypatch: pytest.MonkeyPatch) -> None:
    _inject(monkeypatch, DropSecondMotion(), "expand-cycles")
    r = compile_text(PROGRAM, emit="canon", verify_each=True)
    first = next(d for d in r.sink if d.code == "E0992")
    assert "drop-second-motion" in first.message
    # the jump is at the third motion (G01 Y10.), which now follows the rapid
    src = r.sources.get(first.span.source_id)
    assert src is not None and src.text[first.span.start:first.span.end].startswith("G01 Y10.")


CASES = [(p, e) for p in CORPUS for e in ("canon", "gcode")] + [(p, "timing") for p in CORPUS[::5]]


@pytest.mark.parametrize(("path", "emit"), CASES, ids=lambda v: f"{v.parent.name}/{v.name}" if isinstance(v, Path)
                         else str(v))
def test_the_corpus_keeps_every_invariant_and_its_output(path: Path, emit: str) -> None:
    dialect = DIALECT.get(path.parent.name, path.parent.name)
    text = path.read_text(encoding="utf-8")
    extra: dict[str, Any] = {"compare": "O1", "quiet": True} if emit == "timing" else {}
    plain = compile_text(text, dialect=dialect, emit=emit, **extra)
    checked = compile_text(text, dialect=dialect, emit=emit, verify_each=True, **extra)
    assert "E0992" not in codes(checked), [d.message for d in checked.sink if d.code == "E0992"][:3]
    assert checked.output == plain.output
    assert codes(checked) == codes(plain)


def test_a_spec_of_the_default_names_gives_the_default_output() -> None:
    spec = ",".join(builder.default_path_names(builder.PipelineConfig()))
    for path in CORPUS[:6]:
        dialect = DIALECT.get(path.parent.name, path.parent.name)
        text = path.read_text(encoding="utf-8")
        assert compile_text(text, dialect=dialect, passes=spec).output == compile_text(text, dialect=dialect).output


def test_a_spec_option_changes_what_the_pass_does() -> None:
    bad_arc = "G01 X0 Y0 F100\nG02 X10. Y0 I5.1 J0\nM30\n"  # end radius 4.9, start radius 5.1
    assert dg.ARC_RADIUS in codes(compile_text(bad_arc))
    repaired = codes(compile_text(bad_arc, passes="expand-cycles,arc-check{repair=true}"))
    assert dg.ARC_REPAIRED in repaired and dg.ARC_RADIUS not in repaired
    assert codes(compile_text(bad_arc, repair_arcs=True)) == repaired


def test_a_plan_stage_in_the_spec_replaces_the_default_one() -> None:
    prog = "G90 G00 X0 Y0\nG01 X10. F3000.\nG01 X10. Y10.\nG01 X0 Y10.\nG01 X0 Y0\nM30\n"
    names = ",".join(builder.default_path_names(builder.PipelineConfig(machine_coords=True)))
    def total(spec: str) -> float:
        r = compile_text(prog, emit="timing", report_format="json", compare="O1", passes=spec, quiet=True)
        assert r.ok, [d.message for d in r.sink]
        return float(json.loads(r.output)["columns"][0]["total_s"])

    default = total("")
    assert total(names + ",blend,plan,verify") == default
    assert total(names + ",blend{exact_stop=true},plan,verify") > default  # a stop at every corner takes longer


def test_print_after_prints_the_ir_text_form(tmp_path: Path) -> None:
    ir = compile_text(PROGRAM, emit="ir").output  # the IR after the last path pass, arc-check
    r = compile_text(PROGRAM, emit="canon", print_after=("arc-check",))
    assert r.pass_report == "; *** IR Dump After arc-check (<stdin>) ***\n" + ir
    out = tmp_path / "dump.ir"
    r2 = compile_text(PROGRAM, emit="canon", print_after=("arc-check",), print_file=str(out))
    assert r2.pass_report == ""
    assert out.read_text(encoding="utf-8") == r.pass_report


def test_print_after_expand_cycles_shows_the_expanded_moves() -> None:
    prog = "G90 G00 X0 Y0 Z10.\nG81 X10. Y10. Z-3. R2. F100.\nG80\nM30\n"
    r = compile_text(prog, emit="canon", print_after=("expand-cycles",), passes="expand-cycles")
    dump = r.pass_report
    assert dump.startswith("; *** IR Dump After expand-cycles")
    assert "Cycle(" not in dump and "Linear(" in dump
    before = compile_text(prog, emit="canon", print_after=("expand-cycles",), passes="mirror,expand-cycles")
    assert before.pass_report == dump  # mirror before changes nothing here


def test_time_passes_lists_every_pass(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    src = tmp_path / "p.nc"
    src.write_text(PROGRAM, encoding="utf-8")
    cpu0 = time.process_time()
    assert main([str(src), "-x", "syntec", "--emit=timing", "--compare=O1", "-q", "--time-passes"]) == 0
    cpu = time.process_time() - cpu0
    err = capsys.readouterr().err
    assert "Pass execution timing report" in err
    row = re.compile(r"^\s+([\d.]+) \(\s*[\d.]+%\)\s+[\d.]+ \(\s*[\d.]+%\)\s+(.+)$")
    rows = {m.group(2): float(m.group(1)) for m in map(row.match, err.splitlines()) if m}
    for name in [*builder.default_path_names(builder.PipelineConfig(machine_coords=True)), "blend", "plan", "verify",
                 "front end", "backend (--emit=timing)", "Total"]:
        assert name in rows, name
    parts = sum(v for k, v in rows.items() if k != "Total")
    assert parts == pytest.approx(rows["Total"], abs=1e-3)
    assert rows["Total"] <= cpu + 1e-3  # what the table claims fits in the CPU time the run took


def test_the_clock_charges_each_stage_its_own_time() -> None:
    """An expensive producer and a cheap consumer: the consumer's row gets only its own time,
    although every item it pulls is made while it waits (inclusive timing would charge it all)."""
    clock = Clock()

    def busy() -> Iterator[int]:
        for i in range(20):
            t = time.process_time()
            while time.process_time() - t < 0.005:
                pass
            yield i

    def cheap(items: Iterable[int]) -> Iterator[int]:
        for i in items:
            yield i + 1

    out = list(clock.timed(cheap(clock.timed(busy(), "busy")), "cheap"))
    assert out == list(range(1, 21))
    assert clock.rows["busy"][0] >= 20 * 0.005
    assert clock.rows["cheap"][0] < clock.rows["busy"][0] / 5


def test_help_shows_the_pass_manager_flags(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit):
        main(["--help"])
    out = capsys.readouterr().out
    for flag in ("-p SPEC", "--verify-each", "--print-after NAME", "--print-file FILE", "--time-passes"):
        assert flag in out, flag


def test_a_bad_spec_on_the_command_line_exits_2(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    src = tmp_path / "p.nc"
    src.write_text(PROGRAM, encoding="utf-8")
    assert main([str(src), "-x", "syntec", "-p", "expand-cycles,arc-chek"]) == 2
    err = capsys.readouterr().err
    assert "E0991" in err and "arc-check" in err and "cutter-comp" in err
    assert main([str(src), "-x", "syntec", "--print-after=nope"]) == 2
    assert "E0991" in capsys.readouterr().err


def test_the_print_file_is_kept_when_a_pass_broke_the_ir(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    _inject(monkeypatch, DropSecondMotion(), "expand-cycles")
    out = tmp_path / "dump.ir"
    r = compile_text(PROGRAM, emit="canon", verify_each=True, print_after=("polar",), print_file=str(out))
    assert "E0992" in codes(r)
    dump = out.read_text(encoding="utf-8")
    assert dump.startswith("; *** IR Dump After polar")
    assert "<stdin>:2:1: Linear(" not in dump  # the dropped motion (the second: after the G00)
    assert "<stdin>:3:1: Linear(" in dump
