"""One pipeline builder: every caller's passes come from cncc/pipeline/builder.py."""

from __future__ import annotations

import importlib
import re
from pathlib import Path
from typing import Any

import pytest

from cncc import driver
from cncc.api import compile_text
from cncc.diagnostics import DiagnosticSink
from cncc.dialects import load_dialect
from cncc.lsp.analysis import Request
from cncc.lsp.config import Settings
from cncc.lsp.pipeline import compile_commands
from cncc.passes import Pass, registered
from cncc.passes.arc_check import ArcCheck
from cncc.passes.cutter_comp import CutterComp
from cncc.pipeline import PipelineConfig, builder
from cncc.pipeline.manager import PassManager
from cncc.source import SourceMap
from tests.helpers import codes

ROOT = Path(__file__).resolve().parents[2]
PROGRAM = ("G90 G54 G00 X0 Y0 Z10.\nG41 D1 G01 X5. Y0 F200.\nG01 X20.\nG03 X30. Y10. R10.\nG40 G01 X40. Y40.\n"
           "G81 X10. Y10. Z-3. R2. F100.\nG80\nM30\n")


@pytest.fixture
def recorded(monkeypatch: pytest.MonkeyPatch) -> list[tuple[str, list[Pass]]]:
    """Every (stage, pass list) the pass manager runs."""
    seen: list[tuple[str, list[Pass]]] = []
    real = PassManager.run_items  # PassManager.run goes through it too

    def spy(self: PassManager, passes: Any, cmds: Any, ctx: Any, *, stage: str = "path", label: str = "") -> Any:
        passes = list(passes)
        seen.append((stage, passes))
        return real(self, passes, cmds, ctx, stage=stage, label=label)

    monkeypatch.setattr(PassManager, "run_items", spy)
    return seen


def test_the_registry_is_the_builders_table() -> None:
    for module in builder.PASS_MODULES.values():
        importlib.import_module(module)
    assert set(registered()) == set(builder.PASS_MODULES)
    for name, module in builder.PASS_MODULES.items():
        assert registered()[name].__module__ == module


def test_default_stages() -> None:
    d = load_dialect("syntec")
    canon = [p.name for p in builder.path_passes(PipelineConfig(), d)]
    assert canon == ["expand-cycles", "polar", "scaling", "mirror", "rotation", "cutter-comp", "arc-check"]
    timing = [p.name for p in builder.path_passes(PipelineConfig(machine_coords=True), d)]
    assert timing == ["expand-cycles", "polar", "scaling", "mirror", "rotation", "to-machine", "tool-length",
                      "cutter-comp", "arc-check"]
    assert [p.name for p in builder.plan_passes(PipelineConfig(), 2)] == ["blend", "plan", "verify"]
    assert [p.name for p in builder.plan_passes(PipelineConfig(), 0)] == ["blend", "plan"]  # -O0 not verified
    assert [p.name for p in builder.plan_passes(PipelineConfig(), 1, verify=False)] == ["blend", "plan"]


def test_options_come_from_the_dialect() -> None:
    d = load_dialect("series8")  # series8.toml: comp_outer_arc_below_deg = 70
    by_name = {p.name: p for p in builder.path_passes(PipelineConfig(repair_arcs=True), d)}
    comp, arc = by_name["cutter-comp"], by_name["arc-check"]
    assert isinstance(comp, CutterComp) and isinstance(arc, ArcCheck)
    assert comp.outer_arc_below_deg == pytest.approx(70.0)
    assert arc.repair is True
    lcnc = {p.name: p for p in builder.path_passes(PipelineConfig(), load_dialect("linuxcnc"))}
    assert "cutter-comp" not in lcnc and "cutter-comp-rs274" in lcnc  # linuxcnc.toml: comp_algorithm = "rs274"
    arc = lcnc["arc-check"]
    assert isinstance(arc, ArcCheck) and arc.abs_tol_mm == pytest.approx(0.028284271247461905)
    assert arc.abs_tol_inch_mm == pytest.approx(0.0028284271247461905 * 25.4) and arc.max_abs_factor == 100


def test_a_spec_replaces_the_path_stage_and_keeps_the_defaults_of_unnamed_options() -> None:
    d = load_dialect("syntec")
    got = builder.path_passes(PipelineConfig(spec="arc-check{repair=true},expand-cycles"), d)
    assert [p.name for p in got] == ["arc-check", "expand-cycles"]
    assert isinstance(got[0], ArcCheck)
    assert got[0].repair is True
    assert got[0].rel_tol == 0.001  # syntec.toml arc_radius_tolerance_rel


def test_the_lsp_and_the_cli_run_the_same_passes(recorded: list[tuple[str, list[Pass]]], tmp_path: Path) -> None:
    """Same program, same options (a dialect option the passes read, -O2): the language
    server's machine phase and ``cncc --emit=timing`` get equal pass lists."""
    path = tmp_path / "prog.nc"
    path.write_text(PROGRAM, encoding="utf-8")
    options = {"comp_outer_corner": "arc"}
    r = compile_text(PROGRAM, dialect="syntec", emit="timing", compare="O2", dialect_options=options)
    assert r.ok or codes(r)
    cli = list(recorded)
    recorded.clear()
    settings = Settings(dialect="syntec", dialect_options=options)
    req = Request(uri="file://" + str(path), path=str(path), version=1, text=PROGRAM, dialect="syntec",
                  settings=settings)
    dialect = load_dialect("syntec").with_options(options)
    machine = driver.default_machine()
    sink = DiagnosticSink()
    cmds = list(compile_commands(req, dialect, machine, SourceMap(), sink, machine_coords=True))
    driver.plan_trajectory(cmds, machine, 2, DiagnosticSink())
    lsp = list(recorded)
    assert [s for s, _ in cli] == [s for s, _ in lsp] == ["path", "plan"]
    assert cli[0][1] == lsp[0][1]  # frozen dataclasses: names and every option compared
    assert cli[1][1] == lsp[1][1]
    comp = next(p for p in cli[0][1] if p.name == "cutter-comp")
    assert isinstance(comp, CutterComp) and comp.outer_corner == "arc"


def test_the_lsp_light_pipeline_is_the_path_stage_with_relink(recorded: list[tuple[str, list[Pass]]]) -> None:
    req = Request(uri="untitled:1", path="", version=1, text="G01 X10. F100\nG01 Y5.\n", dialect="syntec",
                  settings=Settings(dialect="syntec"))
    d = load_dialect("syntec")
    list(compile_commands(req, d, driver.default_machine(), SourceMap(), DiagnosticSink(), machine_coords=False))
    ((stage, light),) = recorded
    assert stage == "path"
    full = builder.path_passes(PipelineConfig(), d)
    assert [p.name for p in light] == ["expand-cycles", "relink", "arc-check"]
    assert light[0] == full[0] and light[2] == full[-1]


def _python_files() -> list[Path]:
    return sorted(p for p in (ROOT / "cncc").rglob("*.py") if p.relative_to(ROOT / "cncc").parts[0] != "pipeline")


def test_no_module_outside_the_builder_makes_passes() -> None:
    """A grep: no ``SomePass(`` call of a registered pass class, and no hand-chained pipeline
    (``run_pipeline(`` or a pass's ``.run(`` on a stream), outside cncc/pipeline/."""
    for module in builder.PASS_MODULES.values():
        importlib.import_module(module)
    classes = sorted(cls.__name__ for cls in registered().values())
    made = re.compile(r"(?<!class )\b(" + "|".join(classes) + r")\(")
    chained = re.compile(r"\brun_pipeline\(|\b(?:" + "|".join(classes) + r")\([^)]*\)\.run\(")
    offenders = []
    for path in _python_files():
        rel = path.relative_to(ROOT).as_posix()
        if rel == "cncc/passes/__init__.py":
            continue  # defines run_pipeline for the pass unit tests
        for i, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            code = line.split("#", 1)[0]
            if made.search(code) or chained.search(code):
                offenders.append(f"{rel}:{i}: {line.strip()}")
    assert offenders == []


def test_the_grep_finds_a_hand_made_pass(tmp_path: Path) -> None:
    """The pattern of the test above matches what it is meant to forbid."""
    for module in builder.PASS_MODULES.values():
        importlib.import_module(module)
    classes = sorted(cls.__name__ for cls in registered().values())
    made = re.compile(r"(?<!class )\b(" + "|".join(classes) + r")\(")
    assert made.search("    passes = [ExpandCycles(keep=keep), ArcCheck()]")
    assert not made.search("class ArcCheck(Pass):")
