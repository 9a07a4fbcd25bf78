"""Typed mode commands: the deprecated SetMode(name, value) factory maps every legacy name to its
typed command (so that branches written against the old IR merge), and nothing in cncc calls it."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from cncc import ir
from cncc.ir import (
    CompSide,
    FeedMode,
    Frame,
    PathMode,
    Plane,
    SetMode,
    ToolData,
    Units,
)
from cncc.ir.frame import Mirror
from cncc.source import Span

SP, F = Span(0, 1, 2), Frame()
V6 = (1.0, 2.0, 3.0, 0.0, 0.0, 0.0)
MIRROR = Mirror((0.0, 0.0, 0.0), (True, False, False))

LEGACY = [
    ("units", Units.INCH, ir.SetUnits(SP, F, Units.INCH)),
    ("plane", Plane.ZX, ir.SetPlane(SP, F, Plane.ZX)),
    ("feed_mode", "per_rev", ir.SetFeedMode(SP, F, FeedMode.PER_REV)),
    ("feed_mode", "inverse_time", ir.SetFeedMode(SP, F, FeedMode.INVERSE_TIME)),
    ("path_mode", PathMode.EXACT_STOP, ir.SetPathMode(SP, F, PathMode.EXACT_STOP)),
    ("path_mode", (PathMode.CONTINUOUS, 0.5, 0.25), ir.SetPathMode(SP, F, PathMode.CONTINUOUS, 0.5, 0.25)),
    ("cycle_path_mode", PathMode.EXACT_PATH, ir.SetPathMode(SP, F, PathMode.EXACT_PATH, for_cycle=True)),
    ("cutter_comp", CompSide.LEFT, ir.SetCutterComp(SP, F, CompSide.LEFT)),
    ("tool_length_offset", 12.5, ir.SetToolLength(SP, F, 12.5)),
    ("g5x_offset", 2, ir.SetWorkSystem(SP, F, 2)),
    ("g92_offset", V6, ir.SetG92Offset(SP, F, V6)),
    ("g92_preset", (0, 2), ir.PresetG92(SP, F, (0, 2))),
    ("g52_offset", V6, ir.SetLocalOffset(SP, F, V6)),
    ("xy_rotation", 30.0, ir.SetXyRotation(SP, F, 30.0)),
    ("polar", (1.0, 2.0), ir.SetPolar(SP, F, (1.0, 2.0))),
    ("scaling", None, ir.SetScaling(SP, F, None)),
    ("mirror", MIRROR, ir.SetMirror(SP, F, MIRROR)),
    ("rotation", None, ir.SetRotation(SP, F, None)),
    ("tool_table", (3, 10.0, 6.0), ir.WriteToolTable(SP, F, 3, 10.0, 6.0)),
    ("tool_table", (3, 10.0, 6.0, (1.5, 80.0, 20.0, 2)), ir.WriteToolTable(SP, F, 3, 10.0, 6.0, 1.5, 80.0, 20.0, 2)),
    ("work_table", (2, V6, V6), ir.WriteWorkTable(SP, F, 2, V6, V6)),
    ("data_input", ("radius_wear", 4, 0.1), ir.WriteToolData(SP, F, ToolData.RADIUS_WEAR, 4, 0.1)),
    ("css_reference", (40.0, 20.0), ir.SetCssReference(SP, F, 40.0, 20.0)),
    ("spindle_mode", None, ir.SetSpindleMode(SP, F, 0.0)),
    ("spindle_mode", 2000.0, ir.SetSpindleMode(SP, F, 2000.0)),
    ("spindle_sync", 1.5, ir.SpindleSync(SP, F, 1.5)),
    ("rigid_tap", (V6, 4), ir.RigidTap(SP, F, V6, 4)),
    ("nurbs_feed", (5, 3, 7), ir.NurbsFeed(SP, F, 5, 3, 7)),
    ("probe", (V6, "probe_toward", 2), ir.Probe(SP, F, V6, "probe_toward", 2)),
    ("tool_number", 7, ir.SetToolNumber(SP, F, 7)),
    ("overrides", False, ir.SetOverrides(SP, F, False)),
    ("feed_override", True, ir.SetFeedOverride(SP, F, True)),
    ("held_axes", (True,) * 3 + (False,) * 3, ir.HoldAxes(SP, F, (True, True, True, False, False, False))),
    ("call_begin", ("0:12", "O100"), ir.CallBoundary(SP, F, True, "0:12", "O100")),
    ("call_end", ("0:12", "O100"), ir.CallBoundary(SP, F, False, "0:12", "O100")),
    ("output", ("Y03", True), ir.SetOutput(SP, F, "Y03", True)),
    ("smoothing", ("G05.1", (("Q", 1.0),)), ir.SetSmoothing(SP, F, "G05.1", (("Q", 1.0),))),
    ("interpreter_report", "cutter_comp_off", ir.InterpreterReport(SP, F, "cutter_comp_off")),
]


@pytest.mark.parametrize(("name", "value", "typed"), LEGACY, ids=[f"{n}-{k}" for k, (n, _, _) in enumerate(LEGACY)])
def test_legacy_name_builds_the_typed_command(name: str, value: object, typed: object) -> None:
    got = SetMode(SP, F, name, value)
    assert got == typed and type(got) is type(typed)


def test_every_mode_command_has_a_legacy_name() -> None:
    assert {type(t) for _, _, t in LEGACY} == set(ir.MODE_TYPES)


def test_an_unknown_legacy_name_is_refused() -> None:
    with pytest.raises(ValueError, match="no typed mode command"):
        SetMode(SP, F, "no_such_mode", 1)


def test_no_cncc_code_uses_the_legacy_factory() -> None:
    """Only cncc/ir/legacy.py builds from a name (cncc/ir/__init__.py re-exports it for old branches)."""
    root = Path(__file__).resolve().parents[2] / "cncc"
    call = re.compile(r"(?<![\w`.])(SetMode|set_mode)\(")
    hits = [str(p.relative_to(root)) for p in root.rglob("*.py")
            if p.name != "legacy.py" and call.search(p.read_text(encoding="utf-8"))]
    assert hits == []
