"""Code actions and dialect guesses on real dialect files, in process."""

from __future__ import annotations

import pytest

from cncc.dialects import available, load_dialect
from cncc.lsp.actions import convert_selection
from cncc.lsp.analysis import Request, analyze, new_analysis
from cncc.lsp.config import Settings, guess_dialect

SYNTEC, GRBL = load_dialect("syntec"), load_dialect("grbl")


def converted(text: str, line: int) -> list[str]:
    a = new_analysis(Request("file:///p.nc", "/p.nc", 1, text, "syntec", Settings()))
    analyze(a, lambda: None)
    got = convert_selection(a.index, a.commands, line, line, SYNTEC, GRBL)
    assert got is not None
    (_start, _end, new), = got[1]
    return new.split("\n")


def test_conversion_has_no_preamble_when_the_modes_agree() -> None:
    assert converted("G90 G17 G00 X0 Y0\nG01 X10. Y5. F300.\nM30\n", 1) == ["G01 X10. Y5. F300."]


def test_conversion_under_g91_states_g90_and_restores_g91() -> None:
    text = "G90 G00 X0 Y0\nG91 G01 X10. Y5. F300.\nX1.\nM30\n"
    assert converted(text, 1) == ["G01 X10. Y5. F300.", "G91"]  # the selection's own G91 is restored
    assert converted(text, 2) == ["G90", "G01 X11. F300.", "G91"]  # absolute 10 + 1, then back to G91


def test_conversion_keeps_a_plane_code_only_for_moves_in_that_plane() -> None:
    assert converted("G18\nG02 X10. Z0 I5. K0 F100.\nM30\n", 2) == ["M30"]
    text = "G18 G00 X0 Z0\nG17 G02 X10. Y0 I5. J0 F100.\nM30\n"
    assert converted(text, 1)[0] == "G17"


def claimed_by(ext: str) -> list[str]:
    return [n for n in available() if ext in load_dialect(n).extensions]


@pytest.mark.parametrize("ext", [".ngc", ".gcode", ".gc", ".fnc", ".txt", ".s8"])
def test_extension_guess(ext: str) -> None:
    owners = claimed_by(ext)
    if not owners:
        pytest.skip(f"no dialect file claims {ext} in this tree")
    expected = {".ngc": "linuxcnc", ".gcode": "grbl", ".gc": "grbl", ".fnc": "fanuc"}.get(ext)
    if expected is None:  # otherwise the one dialect file that claims the extension
        assert len(owners) == 1
        expected = owners[0]
    assert guess_dialect(f"/p/prog{ext}", "G01 X1. F100.\n", None) == expected


@pytest.mark.parametrize(("text", "expected"), [
    ("G01 X1. F100.\nWAT+ X1\n", "szgh"),  # SZGH statements
    ("M98 PSUB1\nM30\n", "szgh"),  # an SZGH program called by name
    ("o<drill> sub\nG01 X1\no<drill> endsub\n", "linuxcnc"),
    ("#<depth> = 3\nG01 Z-#<depth>\n", "linuxcnc"),
    ("$H\nG21 G01 X1 F100\n", "grbl"),
    ("G20\n#1=2\nG01 X#1\n", "fanuc"),  # G20/G21 with macro B
    ("G70 G01 X1. F10.\n", "syntec"),
    ("G01 X1. F100.\n", "syntec"),  # nothing to go by: the default
])
def test_content_guess(text: str, expected: str) -> None:
    assert guess_dialect("/p/prog.nc", text, None) == expected


def test_modeline_and_setting_come_before_the_content() -> None:
    assert guess_dialect("/p/a.ngc", "(cncc: dialect=fanuc)\no100 sub\n", "grbl") == "fanuc"
    assert guess_dialect("/p/a.ngc", "o100 sub\n", "szgh") == "szgh"
