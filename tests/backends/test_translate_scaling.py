"""G51 scaling kept as codes by targets that have the op (cncc.backends.gcode.keep_transforms).

The round trip (test_translate_roundtrip.py, corpus scaling.nc) checks that the kept
scaling moves the machine as the source does; these tests check that it is kept (the
codes with the programmed centre and factors, coordinates unscaled) and where it is not.
"""

from __future__ import annotations

import pytest

from cncc.api import compile_text
from tests.backends.test_translate_rotation import axis_words, translate
from tests.backends.test_translate_roundtrip import DATA, TABLES, check

SCALING = (DATA / "corpus" / "syntec" / "scaling.nc").read_text()
HEAD = "G90 G17 G71 G94 G54\nG00 X0. Y0. Z10.\nG01 Z-1. F200.\n"


def lines(out: str) -> list[str]:
    return [line.rstrip(";").strip() for line in out.splitlines()]


@pytest.mark.parametrize("target", ["fanuc", "syntec"])
def test_scaling_is_kept_with_programmed_numbers(target: str) -> None:
    out, codes = translate(SCALING, target)
    got = lines(out)
    assert "G51 X10. Y5. Z0. P2." in got and "G51 X10. Y20. I1.5 J0.5 K1." in got
    assert "G51 X50. Y50. Z2. P0.5" in got and got.count("G50") == 3
    # programmed, not scaled: (20, 5) about (10, 5) by 2 would be X30.; (15, 5) by 1.5/0.5 X17.5 Y12.5
    assert {"X20.", "X30.", "X40.", "J10.", "X15.", "X60.", "X70."} <= axis_words(out)
    assert "X17.5" not in out and "N0802" not in codes


def test_szgh_keeps_uniform_scaling_as_g36_and_applies_per_axis_factors() -> None:
    out, codes = translate(SCALING, "szgh")
    got = lines(out)
    assert "G36 X10. Y5. Z0. R2." in got and "G36 X50. Y50. Z2. R0.5" in got and got.count("G37") == 2
    # G36 R has one factor for the named axes: I1.5 J0.5 is scaled by cncc about (10, 20)
    assert "G01 X17.5 Y12.5 F150." in got and "N0802" in codes


def test_szgh_source_g36_on_named_axes_to_fanuc_ijk() -> None:
    text = "G90 G17 G21 G94 G54\nG00 X0. Y0. Z10.\nG36 X10. Y0. R2.\nG01 X20. Y5. F200.\nG37\nM30\n"
    # R on the named X and Y: factors (2, 2, 1), written per axis
    assert "G51 X10. Y0. I2. J2. K1." in lines(check(text, "szgh", "fanuc"))
    out = check("G90 G17 G71 G94 G54\nG00 X0. Y0. Z10.\nG51 X10. P2.\nG01 X20. Y5. F200.\nG50\nM30\n",
                "syntec", "szgh")
    assert "G36 X10. Y0. Z10. R2." in lines(out)


@pytest.mark.parametrize("target", ["linuxcnc", "grbl"])
def test_targets_without_scaling_codes_get_scaled_coordinates(target: str) -> None:
    out, codes = translate(SCALING, target)
    assert "G51" not in out and "N0802" in codes
    assert "X30. Y5." in out  # (20, 5) scaled by 2 about (10, 5)
    check(SCALING, "syntec", target)


@pytest.mark.parametrize(("why", "body"), [
    ("cutter compensation", "G51 X0. Y0. P2.\nG41 D1 G01 X20. Y0.\nG01 Y20.\nG40 G01 X30. Y30.\nG50"),
    ("incremental moves", "G51 X0. Y0. P2.\nG91 G01 X10. Y0.\nG90 G01 X0. Y0.\nG50"),
    ("a G52 inside", "G51 X0. Y0. P2.\nG01 X20. Y0.\nG52 X5. Y5.\nG01 X0. Y0.\nG52 X0. Y0.\nG50"),
    ("a rotation inside", "G51 X0. Y0. P2.\nG68 X0. Y0. R30.\nG01 X20. Y0.\nG69\nG50"),
    ("an unwritable centre", "G51 X1.0005 Y0. P2.\nG01 X20. Y0.\nG50"),
    ("an unwritable factor", "G51 X0. Y0. P1.0000005\nG01 X20. Y0.\nG50"),
    ("an arc under per-axis factors", "G51 X0. Y0. I2. J1. K1.\nG01 X10. Y0.\nG03 X0. Y10. I-10. J0.\nG50"),
])
def test_scaling_is_applied_by_cncc_when_the_target_could_not_run_it_alike(why: str, body: str) -> None:
    text = HEAD + body + "\nG00 Z10.\nM30\n"
    out, codes = translate(text, "fanuc")
    assert "G51 " not in out and "N0802" in codes, why


def test_g50_is_cancel_false_names_the_swapped_codes_or_applies_the_scaling() -> None:
    text = HEAD + "G51 X0. Y0. P2.\nG01 X20. Y5.\nG50\nG00 Z10.\nM30\n"
    swapped = {"g50_is_cancel": False}
    r = compile_text(text, dialect="syntec", emit="gcode", target="syntec", target_options=swapped,
                     **TABLES)  # type: ignore[arg-type]
    # with the codes swapped, G50 (which takes P/I/J/K in syntec.toml) scales and G51 cancels
    got = lines(r.output)
    assert "G50 X0. Y0. Z-1. P2." in got and "G51" in got and "X40. Y10." not in r.output
    assert "N0802" not in [d.code for d in r.sink]
    # and the swapped target reads its own output back to the same motion
    from cncc.api import compile_commands
    from cncc.ir import Linear

    want, r1 = compile_commands(text, **TABLES)  # type: ignore[arg-type]
    back, r2 = compile_commands(r.output, dialect_options=swapped, **TABLES)  # type: ignore[arg-type]
    assert r1.ok and r2.ok
    ends = [[round(v, 6) for v in c.end[:3]] for c in want if isinstance(c, Linear)]
    assert [[round(v, 6) for v in c.end[:3]] for c in back if isinstance(c, Linear)] == ends
