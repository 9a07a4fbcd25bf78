"""SERIES 8 rules beyond the manual's examples: the spec's extra vectors (D001-01 ... 04),
the arc rules, G06, G10 edge cases, G21-G23, G67-G69, cycles, strict mode and options."""

from __future__ import annotations

import math

import pytest

from cncc.frontend.series8.arcs import quadrant_centre
from cncc.passes.series8_cycles import first_peck_depths
from tests.helpers import canon, codes, compile_commands, moves, nominal

S8 = "series8"
IN = 25.4


def _z_moves(text: str) -> list[tuple[str, float]]:
    return [("rapid" if k == "STRAIGHT_TRAVERSE" else "feed", round(p[2], 4)) for k, p in moves(text, S8)]


def test_d001_01_g83_first_depth_then_pecks() -> None:
    got = _z_moves("G00X0Y0Z1.\nG83 X0 Y0 Z-1. R.1 I-.3 J.25 F10\n")
    assert got[1:] == [("rapid", 0.1), ("feed", -0.3), ("rapid", 0.1),
                       ("rapid", -0.25), ("feed", -0.55), ("rapid", 0.1),
                       ("rapid", -0.5), ("feed", -0.8), ("rapid", 0.1),
                       ("rapid", -0.75), ("feed", -1.0), ("rapid", 0.1)]
    t = nominal("G00X0Y0Z1.\nG83 X0 Y0 Z-1. R.1 I-.3 J.25 F10\n", S8)
    assert t.by_category_s["feed"] == pytest.approx(1.25 / 10 * 60, abs=1e-3)  # 7.5 s


def test_first_peck_depths_count() -> None:
    depths = first_peck_depths(0.1, -1.0, -0.3, 0.25)
    assert depths == pytest.approx([-0.3, -0.55, -0.8, -1.0])
    assert len(depths) == 1 + math.ceil(0.7 / 0.25)


def test_g83_first_depth_beyond_z_or_no_peck_is_an_error() -> None:
    for block in ("G83 X0 Y0 Z-1. R.1 I-1.5 J.25 F10", "G83 X0 Y0 Z-1. R.1 I-.3 F10"):
        _, r = canon("G00X0Y0Z1.\n" + block + "\n", S8)
        assert codes(r) == ["E0404"], block


def test_d001_02_quadrant_rule() -> None:
    got = moves("G00X10Y0\nF10\nG03 X0 Y10 I10\n", S8)
    assert got[-1][1][:5] == pytest.approx((0.0, 10.0, 0.0, 0.0, 1))
    _, r = canon("G00X10Y0\nF10\nG02 X0 Y10 I10\n", S8)
    assert codes(r) == ["E0253"]  # 270 degrees about (0,0); (20,0) is not equidistant


def test_quadrant_centre_candidates() -> None:
    assert quadrant_centre((20, 30), (30, 20), 0, 10, True, 1e-6) == pytest.approx((20, 20))
    assert quadrant_centre((20, 30), (30, 20), 0, 10, False, 1e-6) is None  # CCW would sweep 270 degrees
    assert quadrant_centre((1, 0), (0, 1), 1, 0, False, 1e-6) == pytest.approx((0, 0))
    assert quadrant_centre((0, 0), (1, 1), 1, 0, True, 1e-6) == pytest.approx((1, 0))  # ends on the boundaries
    assert quadrant_centre((0, 0), (1, 1), 1, 0, False, 1e-6) is None


def test_signed_ij_is_ignored_with_a_warning_or_refused() -> None:
    got, r = canon("G00X20.Y30.\nF10\nG02 X30. Y20. I0 J-10.\n", S8)
    assert codes(r) == ["W0254"] and any("ARC_FEED(30.0000, 20.0000, 20.0000, 20.0000" in ln for ln in got)
    _, r = canon("G00X20.Y30.\nF10\nG02 X30. Y20. I0 J-10.\n", S8, dialect_options={"arc_ij_sign": "error"})
    assert codes(r) == ["E0253"]


def test_d001_03_small_radius_is_enlarged_or_refused() -> None:
    got, r = canon("G00X0Y0\nF10\nG02X2.Y0R.5\n", S8)
    assert codes(r) == ["W0256"]
    assert any("ARC_FEED(2.0000, 0.0000, 1.0000, 0.0000, -1" in ln for ln in got)
    _, r = canon("G00X0Y0\nF10\nG02X2.Y0R.5\n", S8, dialect_options={"arc_r_small": "error"})
    assert codes(r) == ["E0209"]


def test_r_of_other_codes_does_not_become_the_arc_radius() -> None:
    # the G10 R and the G55 R do not set the arc radius; the arc has no centre.
    _, r = canon("G00X0Y0\nF10\nG01G10X1.R.2\nY1.\nG55R30\nG56\nG02X2.Y1.\n", S8)
    assert codes(r) == ["E0207"]


def test_d001_04_chamfer_on_a_right_angle() -> None:
    got = moves("G00X0Y0\nG01F10G10X1.L.25\nY1.\n", S8)
    pts = [tuple(round(v, 4) for v in p[:2]) for _, p in got]
    assert pts == [(0.0, 0.0), (0.75, 0.0), (1.0, 0.25), (1.0, 1.0)]
    assert math.dist(pts[1], pts[2]) == pytest.approx(2 * 0.25 * math.cos(math.radians(45)), abs=1e-4)


@pytest.mark.parametrize(("prog", "why"), [
    ("G00X0Y0\nG01F10G10X1.L.25\nG02X2.Y1.R1.\n", "next is an arc"),
    ("G00X0Y0\nG01F10G10X1.L1.5\nY1.\n", "setback too long"),
    ("G00X0Y0\nG01F10G10X1.R.2\nX2.\n", "no corner"),
    ("G00X0Y0\nG01F10G10X1.R.2L.1\nY1.\n", "both R and L"),
    ("G00X0Y0\nG01F10G10X1.R.2\nM30\n", "nothing follows"),
])
def test_g10_corners_that_cannot_be_made(prog: str, why: str) -> None:
    _, r = canon(prog, S8)
    assert "E0257" in codes(r), why


def test_g06_runs_the_loop_count_and_ends_at_the_start() -> None:
    prog = "G00X0Y0\nF10\nG06X1.Y0\n"
    got = moves(prog, S8)
    assert [p[:2] for _, p in got[1:]] == [(1.0, 0.0), (0.0, 0.0)]
    _, r = canon(prog, S8)
    assert codes(r) == ["W0256"]  # the @RUNG6 loop is not known statically
    t = nominal(prog, S8, dialect_options={"g06_cycles": 3})
    assert t.by_category_s["feed"] == pytest.approx(3 * math.pi * 1.0 / 10 * 60, abs=1e-3)  # N x pi L / F


def test_g21_to_g23_stop_exactly_and_g01_blends_again() -> None:
    cmds, r = compile_commands("G00X0Y0\nF10\nG21X1.\nY1.\nG01X0\nG23X1.Y2.R1.\n", dialect=S8)
    assert r.ok
    modes = [(type(c).__name__, c.motion.mode.value) for c in cmds if type(c).__name__ in ("Linear", "Arc")]
    assert modes == [("Linear", "exact-stop"), ("Linear", "exact-stop"), ("Linear", "continuous"),
                     ("Arc", "exact-stop")]


def test_g67_g68_one_block_modes() -> None:
    got = moves("G91\nG00X1.\nG67X5.\nX1.\nG90\nG68X1.\nX1.\n", S8)
    assert [p[0] for _, p in got] == [1.0, 5.0, 6.0, 7.0, 1.0]


def test_g69_machine_coordinates_skip_presets_and_rotation() -> None:
    prog = "G00X5.\nG92X0\nG55R90\nG69X5.Y0\nX1.\n"
    cmds, r = compile_commands(prog, dialect=S8, emit="timing")
    assert r.ok
    ends = [tuple(round(v / IN, 4) for v in c.end[:2]) for c in cmds if type(c).__name__ == "Rapid"]
    # G69 X5 is machine X5 whatever G92 and G55 say; X1 afterwards is program X1 Y0 rotated, plus the preset
    assert ends == [(5.0, 0.0), (5.0, 0.0), (5.0, 1.0)]


def test_g57_rejects_a_non_positive_factor() -> None:
    _, r = canon("G57R0\n", S8)
    assert codes(r) == ["E0501"]
    _, r = canon("G57R-1.\n", S8)
    assert codes(r) == ["E0501"]


def test_vendor_cycles_need_a_macro_or_are_skipped() -> None:
    for code in ("G34", "G35", "G36", "G43", "G49", "G50", "G51"):  # the spec's opaque reading
        _, r = canon(f"{code} X1. Y1.\n", S8, dialect_options={"vendor_cycles": "error"})
        assert codes(r) == ["E0255"], code
    for code in ("G43", "G51"):  # cncc has no reading of these: refused even when the others expand
        _, r = canon(f"{code} X1. Y1.\n", S8)
        assert codes(r) == ["E0255"], code
    got, r = canon("G34 X1. Y1.\n", S8, dialect_options={"vendor_cycles": "skip"})
    assert codes(r) == ["W0256"] and not [ln for ln in got if "STRAIGHT" in ln]


def test_fanuc_codes_are_not_series8_codes() -> None:
    for code in ("G20", "G54", "G28", "G73", "G99"):
        _, r = canon(f"{code}\n", S8)
        assert codes(r) == ["E0201"], code


def test_g04_f_is_not_a_feed() -> None:
    got, r = canon("F10\nG04F2.\nG01X1.\n", S8)
    assert r.ok
    assert [ln.split("N..... ")[1] for ln in got if "DWELL" in ln or "FEED_RATE" in ln] == [
        "SET_FEED_RATE(10.0000)", "DWELL(2.0000)"]  # program units (inch/min), like the positions


def test_bare_letters_only_for_axes() -> None:
    assert [p[:3] for _, p in moves("G00X1.Y1.Z1.\nG00XY\n", S8)] == [(1.0, 1.0, 1.0), (0.0, 0.0, 1.0)]
    _, r = canon("G01X1.F\n", S8)
    assert codes(r) == ["E0108"]


def test_strict_mode_refuses_what_the_manual_never_shows() -> None:
    _, r = canon("%\n(hello)\nG00X1.\n", S8)
    assert r.ok
    _, r = canon("(hello)\nG00X1.\n", S8, strict=True)
    assert codes(r) == ["E0250"]


def test_units_switch_converts_the_feed() -> None:
    prog = "F10\nG01X1.\nG71\nX50.\n"
    cmds, r = compile_commands(prog, dialect=S8)
    assert codes(r) == ["W0256"]  # a unit switch after motion
    feeds = [c.feed_mm_min for c in cmds if type(c).__name__ == "Linear"]
    assert feeds == pytest.approx([254.0, 254.0])  # 10 in/min stays 10 in/min


def test_cycles_keep_levels_absolute_in_g91_and_return_to_r() -> None:
    got = _z_moves("G00X0Y0Z1.\nG91\nG81 X1. Y0 Z-.5 R.1 F10\nX1.\n")
    assert got == [("rapid", 1.0), ("rapid", 1.0), ("rapid", 0.1), ("feed", -0.5), ("rapid", 0.1),
                   ("rapid", 0.1), ("feed", -0.5), ("rapid", 0.1)]
    assert [round(p[0], 4) for _, p in moves("G00X0Y0Z1.\nG91\nG81 X1. Y0 Z-.5 R.1 F10\nX1.\n", S8)][-1] == 2.0


def test_g84_lead_k_sets_the_feed() -> None:
    cmds, r = compile_commands("G00X0Y0Z1.\nM03S500\nG84 X0 Y0 Z-.5 R.1 K.05\n", dialect=S8)
    assert r.ok
    taps = [c for c in cmds if type(c).__name__ == "Linear"]
    assert taps[0].feed_mm_min == pytest.approx(500 * 0.05 * IN)  # rpm x lead


def test_g86_and_g88_return_options() -> None:
    base = "G00X0Y0Z1.\nM03S500\n{} X0 Y0 Z-.5 R.1 P1. I.1 F10\n"
    for code, option in (("G86", "g86_rapid_return"), ("G88", "g88_rapid_return")):
        feed_out = _z_moves(base.format(code))
        rapid_out = [m for m in moves(base.format(code), S8, dialect_options={option: True})]
        assert ("feed", 0.1) in feed_out, code
        ups = [k for k, p in rapid_out if round(p[2], 4) == 0.1 and k != "STRAIGHT_TRAVERSE"]
        assert ups == [], code


def test_g87_rejects_xy_at_depth_and_warns_on_g80() -> None:
    _, r = canon("G00X0Y0Z4.\nG87 X5. Y6. R3.5 Z3.0 F20.\nX6.\n", S8)
    assert codes(r) == ["E0250"]
    _, r = canon("G00X0Y0Z4.\nG87 X5. Y6. R3.5 Z3.0 F20.\nG80\n", S8)
    assert codes(r) == ["W0256"]


def test_g89_back_bore_sequence() -> None:
    got = [(k, tuple(round(v, 4) for v in p[:3])) for k, p in moves(
        "G00X0Y0Z1.\nM03S500\nG89 X5. Y0 Z.5 R-1. I.1 P1. F10\n", S8)]
    assert got[1:] == [("STRAIGHT_TRAVERSE", (5.0, 0.0, 1.0)), ("STRAIGHT_TRAVERSE", (5.1, 0.0, 1.0)),
                       ("STRAIGHT_TRAVERSE", (5.1, 0.0, -1.0)), ("STRAIGHT_TRAVERSE", (5.0, 0.0, -1.0)),
                       ("STRAIGHT_FEED", (5.0, 0.0, 0.5)), ("STRAIGHT_FEED", (5.0, 0.0, -1.0)),
                       ("STRAIGHT_TRAVERSE", (5.1, 0.0, -1.0)), ("STRAIGHT_TRAVERSE", (5.1, 0.0, 1.0)),
                       ("STRAIGHT_TRAVERSE", (5.0, 0.0, 1.0))]


def test_translation_target_splits_arcs_at_quadrants() -> None:
    from cncc.api import compile_text

    r = compile_text("G90 G17 G00 X10. Y0\nG03 X-10. Y0 I-10. J0 F100.\n", dialect="linuxcnc", emit="gcode",
                     target=S8)
    arcs = [ln for ln in r.output.splitlines() if ln.lstrip().startswith(("G02", "G03")) or " G03" in ln]
    assert len(arcs) >= 2  # 180 degrees: at least two one-quadrant blocks


def test_detection_guesses_series8() -> None:
    from cncc.frontend.detect import guess_dialect

    assert guess_dialect("part.nc", "G70\nG00XY ; home\nG55R45\n")[0] == S8
    assert guess_dialect("part.nc", "G00X0Y0 ; start\nG01F50G10Y5R.5;Move 1\n")[0] == S8
    assert guess_dialect("part.nc", "G70\nG00 X1. ; move to the start\n")[0] == S8
    assert guess_dialect("part.nc", "G70\nG00 X1.;\nG10 L2 P1 X0;\n")[0] == "syntec"
