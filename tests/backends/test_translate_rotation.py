"""G68 rotation and G51.1 mirror kept as codes by targets that have them
(cncc.backends.gcode.keep_transforms).

The round trip (test_translate_roundtrip.py, corpus rotation*.nc and mirror.nc) checks
that the kept transform moves the machine as the source does; these tests check that
it is kept (the codes in the output, coordinates untransformed) and where it is not.
"""

from __future__ import annotations

import re

import pytest

from cncc.api import compile_text
from tests.backends.test_translate_roundtrip import DATA, TABLES, check

ROTATION = (DATA / "corpus" / "syntec" / "rotation.nc").read_text()


def translate(text: str, target: str) -> tuple[str, list[str]]:
    r = compile_text(text, dialect="syntec", emit="gcode", target=target, **TABLES)  # type: ignore[arg-type]
    return re.sub(r"\(.*?\)", "", r.output), [d.code for d in r.sink]  # comments may name G68


def axis_words(out: str) -> set[str]:
    return set(re.findall(r"[XYIJ]-?\d+\.\d*", out))


@pytest.mark.parametrize("target", ["fanuc", "szgh", "syntec"])
def test_rotation_is_kept_with_program_coordinates(target: str) -> None:
    out, codes = translate(ROTATION, target)
    assert "G68 X10. Y5. R30." in out and "G68 X0. Y0. R-120." in out and "G68 X50. Y50. R90." in out
    assert out.count("G69") == 2
    # the programmed numbers, not rotated ones: 20 turned 30 deg about (10, 5) would be X21.16 Y5.67
    assert {"X20.", "I-20.", "J0.", "X-10.", "X15.", "I-15.", "X60."} <= axis_words(out)
    assert "N0801" not in codes


def test_incremental_angle_is_written_as_the_total_about_the_current_point() -> None:
    text = (DATA / "corpus" / "syntec" / "rotation_incremental.nc").read_text()
    out, _ = translate(text, "fanuc")
    # R10 about the origin, then G91 R15 at (20, 0): 25 deg about (20, 0); then +20 at (30, 20)
    assert "G68 X20. Y0. R25." in out and "G68 X30. Y20. R45." in out


@pytest.mark.parametrize("target", ["linuxcnc", "grbl", "series8"])
def test_targets_without_g68_get_rotated_coordinates(target: str) -> None:
    out, codes = translate(ROTATION, target)
    assert "G68" not in out and "N0801" in codes
    # (20, 0) turned 30 deg about (10, 5): (10 + 10 cos 30 + 5 sin 30, 5 + 10 sin 30 - 5 cos 30)
    assert "X21.16 Y5.67" in out
    check(ROTATION, "syntec", target)


@pytest.mark.parametrize(("why", "inside"), [
    ("cutter compensation", "G41 D1 G01 X20. Y0.\nG01 Y20.\nG40 G01 X30. Y30."),
    ("incremental moves", "G91 G01 X10. Y0.\nG90 G01 X0. Y0."),
    ("a G52 inside", "G01 X20. Y0.\nG52 X5. Y5.\nG01 X0. Y0.\nG52 X0. Y0."),
    ("scaling inside", "G51 X0. Y0. P2.\nG01 X20. Y0.\nG50"),
    ("an unwritable centre", None),
])
def test_rotation_is_applied_by_cncc_when_the_target_could_not_run_it_alike(why: str, inside: str | None) -> None:
    head = "G90 G17 G71 G94 G54\nG00 X0. Y0. Z10.\nG01 Z-1. F200.\n"
    if inside is None:
        text = head + "G68 X1.0005 Y0. R30.\nG01 X20. Y0.\nG69\nM30\n"
    else:
        text = head + f"G68 X0. Y0. R30.\n{inside}\nG69\nG00 Z10.\nM30\n"
    out, codes = translate(text, "fanuc")
    assert "G68" not in out and "N0801" in codes, why
    check(text, "syntec", "fanuc")


def test_increment_after_a_kept_rotation_makes_cncc_apply_it() -> None:
    # G69 then G68 with no move between: the first G91 move starts where the rotated path ended
    text = ("G90 G17 G71 G94 G54\nG00 X0. Y0. Z10.\nG68 X0. Y0. R30.\nG01 X20. Y0. F200.\n"
            "G69\nG68 X5. Y5. R45.\nG91 G01 X10. Y0.\nG90 G69\nM30\n")
    out, _ = translate(text, "fanuc")
    assert "G68" not in out
    check(text, "syntec", "fanuc")


MIRROR = (DATA / "corpus" / "syntec" / "mirror.nc").read_text()


@pytest.mark.parametrize(("target", "on", "off"), [("fanuc", "G51.1", "G50.1"), ("syntec", "G51.1", "G50.1"),
                                                   ("szgh", "G11", "G12")])
def test_mirror_is_kept_with_programmed_arcs(target: str, on: str, off: str) -> None:
    out, codes = translate(MIRROR, target)
    assert f"{on} X10.\n" in out.replace(";", "") and f"{on} X10. Y20." in out and f"{on} Y30." in out
    assert out.count(off) == 3
    # the arcs as programmed: the control reverses them, not the output
    assert "G03 X30. Y15. I0. J10." in out and "G02 X70. Y50. I10. J0." in out
    assert "N0803" not in codes


@pytest.mark.parametrize("target", ["linuxcnc", "grbl"])
def test_targets_without_mirror_codes_get_mirrored_coordinates(target: str) -> None:
    out, codes = translate(MIRROR, target)
    assert "G51.1" not in out and "N0803" in codes
    assert "G02 X-10. Y15." in out  # X30 about X10 is X-10, and the G03 turns into G02


def test_mirror_with_a_rotation_inside_is_applied_by_cncc() -> None:
    text = ("G90 G17 G71 G94 G54\nG00 X0. Y0. Z10.\nG51.1 X10.\nG68 X0. Y0. R30.\nG01 X20. Y5. F200.\n"
            "G69\nG50.1 X0.\nG00 X0. Y0.\nM30\n")
    out, codes = translate(text, "fanuc")
    assert "G51.1" not in out and "G68" not in out and {"N0801", "N0803"} <= set(codes)
    check(text, "syntec", "fanuc")
