"""Emitter details: arc forms from a dialect's [emit] table, units, notes and -Werror, limits."""

from __future__ import annotations

import math
import re

from cncc.api import compile_text
from cncc.backends.gcode import EmitOptions, emit_gcode
from cncc.backends.gcode.arcs import ArcForm, split
from cncc.diagnostics import DiagnosticSink
from cncc.dialects import load_dialect, parse_dialect
from cncc.ir import Arc, Frame, Plane
from cncc.source import NO_SPAN
from tests.backends.test_translate_roundtrip import check

F = Frame()


def arc(start: tuple[float, float], end: tuple[float, float], center: tuple[float, float], turns: int) -> Arc:
    def v(p: tuple[float, float]) -> tuple[float, float, float, float, float, float]:
        return (p[0], p[1], 0.0, 0.0, 0.0, 0.0)

    return Arc(NO_SPAN, F, v(start), v(end), v(center), turns, Plane.XY, 100.0)


def variant(**emit: object) -> object:
    raw = dict(load_dialect("syntec").raw)
    raw["emit"] = emit
    return parse_dialect(raw)


def test_single_quadrant_pieces_end_on_quadrant_boundaries() -> None:
    # 3/4 of a circle of radius 10 about the origin, CCW from 45 degrees
    s = (10 * math.cos(math.pi / 4), 10 * math.sin(math.pi / 4))
    e = (10 * math.cos(7 * math.pi / 4 - 2 * math.pi), 10 * math.sin(-math.pi / 4))
    a = arc(s, e, (0.0, 0.0), 1)
    pieces = split(a.start, a.end, a.center, Plane.XY, 1, ArcForm(single_quadrant=True))
    ends = [(round(p.end[0], 9), round(p.end[1], 9)) for p in pieces]
    assert ends[:3] == [(0.0, 10.0), (-10.0, 0.0), (0.0, -10.0)] and len(pieces) == 4
    assert math.isclose(sum(p.sweep_rad for p in pieces), 1.5 * math.pi)


def test_series8_style_target_writes_unsigned_offsets() -> None:
    a = arc((10.0, 0.0), (-10.0, 0.0), (0.0, 0.0), 1)  # half circle CCW: two quadrants
    out = "".join(emit_gcode([a], variant(arc_single_quadrant=True)))  # type: ignore[arg-type]
    lines = [ln for ln in out.splitlines() if ln.startswith("G03")]
    assert lines == ["G03 X0. Y10. I10. J0. F100.;", "G03 X-10. Y0. I0. J10.;"]


def test_r_form_target_round_trips_through_syntec() -> None:
    text = "G90 G17 G00 X0 Y0\nG01 X10. F100.\nG03 X-10. Y0. I-10. J0.\nG02 I10. J0.\nG03 X0. Y-10. R-10.\nM30\n"
    cmds = [c for c in compile_cmds(text)]
    out = "".join(emit_gcode(cmds, variant(arc_form="r")))  # type: ignore[arg-type]
    assert "I" not in out.replace("(", "") and out.count("R") >= 5  # full circle in 2+, half circle in 2 parts
    r = compile_text(out, emit="canon")
    assert r.ok and r.output.count("ARC_FEED") == compile_text(out, emit="canon").output.count("ARC_FEED")


def compile_cmds(text: str) -> list[object]:
    from cncc.api import compile_commands

    cmds, r = compile_commands(text)
    assert r.ok
    return cmds


def test_units_conversion_to_inch_round_trips_with_five_decimals() -> None:
    text = "G90 G17 G71 G00 X0 Y0 Z5.\nG01 Z-1. F254.\nG02 X20. Y0. I10. J0.\nG01 X12.7 Y-3.3\nM30\n"
    out = check(text, "syntec", "fanuc", units="inch", decimals_inch=5)
    assert "G20" in out and "G21" not in out and "X0.5" in out and "F10." in out  # 12.7 mm, 254 mm/min


def test_notes_are_notes_and_errors_under_werror() -> None:
    text = "G90 G17 G00 X0 Y0\nG68 X0 Y0 R90.\nG01 X10. F100.\nG69\nM30\n"
    r = compile_text(text, emit="gcode", target="linuxcnc")  # no G68: cncc rotates
    assert r.ok and [d.code for d in r.sink] == ["N0801"]
    assert "G01 Y10. F100." in r.output  # (10, 0) rotated by 90 degrees: X stays 0
    r = compile_text(text, emit="gcode", target="linuxcnc", werror=True)
    assert not r.ok and [(d.code, d.severity.name) for d in r.sink] == [("N0801", "ERROR")]


def test_szgh_exact_stop_and_units_are_mapped_by_meaning() -> None:
    text = "G20 G90 G00 X0 Y0\nG60\nG01 X1. F10.\nG64\nM30\n"
    out = compile_text(text, dialect="szgh", emit="gcode", target="syntec").output
    assert re.search(r"^G17 G70 G90 G94;$", out, re.M) and "G61;" in out and "G64;" in out


def test_line_numbers_and_line_length_limit() -> None:
    sink = DiagnosticSink()
    a = arc((10.0, 0.0), (-10.0, 0.0), (0.0, 0.0), 1)
    out = "".join(emit_gcode([a], variant(max_line_length=20), EmitOptions(line_numbers=True), sink))  # type: ignore[arg-type]
    assert out.splitlines()[0].startswith("N10 ") and "W0811" in [d.code for d in sink]


def test_keep_subprograms_without_calls_changes_nothing() -> None:
    text = "G01 X1. F100.\nM30\n"
    kept = compile_text(text, emit="gcode", target="fanuc", keep_subprograms=True)
    plain = compile_text(text, emit="gcode", target="fanuc")
    assert kept.ok and kept.output == plain.output and "N0808" not in [d.code for d in kept.sink]
