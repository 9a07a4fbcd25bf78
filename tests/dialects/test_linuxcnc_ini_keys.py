"""The INI keys that change what LinuxCNC's interpreter does (cncc/inifile.py ``dialect_options``, the
``[ini]`` table of linuxcnc.toml).  Ranges and verdicts measured on LinuxCNC 2.9's stand-alone rs274
(tests/oracle/gen_ini_keys.py compares generated programs with it); RETAIN_G43's meaning is the INI
documentation's ("turn on G43 after loading the first tool ... when you unload the last tool, G43 mode
is canceled")."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.helpers import canon, codes

LINUXCNC = "linuxcnc"
TOOLS_MM = "T1 P1 Z12.7 D6.35\nT2 P2 Z2.54 D5.08\n"


def _run(tmp_path: Path, ini: str, text: str, **opts: object) -> tuple[list[str], list[str]]:
    (tmp_path / "m.ini").write_text(ini)
    (tmp_path / "t.tbl").write_text(TOOLS_MM)
    lines, r = canon(text, LINUXCNC, ini_file=str(tmp_path / "m.ini"), tools_file=str(tmp_path / "t.tbl"), **opts)
    return lines, codes(r)


# A centre arc whose end radius is 0.006 mm longer than its start radius of 1 mm (0.6 %).
_ARC = "G21 F100\nG0 X0 Y0\nG2 X2.006 Y0 I1 J0\nM2\n"


def test_default_arc_tolerance_accepts_the_arc(tmp_path: Path) -> None:
    _, got = _run(tmp_path, "[RS274NGC]\n", _ARC)
    assert "E0208" not in got  # 0.006 mm is within 2 x 0.01 x sqrt(2) mm


def test_a_smaller_center_arc_tolerance_refuses_it(tmp_path: Path) -> None:
    _, got = _run(tmp_path, "[RS274NGC]\nCENTER_ARC_RADIUS_TOLERANCE_MM = 0.005\n", _ARC)
    assert "E0208" in got  # over 0.005 mm and over 0.1 % of the radius


@pytest.mark.parametrize("value", ["0.0005", "0.05", "abc"])
def test_a_tolerance_rs274_refuses_is_a_warning_and_the_default_stays(tmp_path: Path, value: str) -> None:
    _, got = _run(tmp_path, f"[RS274NGC]\nCENTER_ARC_RADIUS_TOLERANCE_MM = {value}\n", _ARC)
    assert "W0972" in got and "E0208" not in got


def test_the_inch_tolerance_applies_to_inch_programs(tmp_path: Path) -> None:
    text = "G20 F10\nG0 X0 Y0\nG2 X0.2005 Y0 I0.1 J0\nM2\n"  # 0.0005 inch longer (0.5 %)
    _, default = _run(tmp_path, "[RS274NGC]\n", text)
    _, strict = _run(tmp_path, "[RS274NGC]\nCENTER_ARC_RADIUS_TOLERANCE_INCH = 0.0001\n", text)
    assert "E0208" not in default and "E0208" in strict


def test_a_dialect_option_on_the_command_line_wins(tmp_path: Path) -> None:
    _, got = _run(tmp_path, "[RS274NGC]\nCENTER_ARC_RADIUS_TOLERANCE_MM = 0.005\n", _ARC,
                  dialect_options={"arc_radius_tolerance_mm": 0.028})
    assert "E0208" not in got


def _lengths(lines: list[str]) -> list[float]:
    """The Z of each USE_TOOL_LENGTH_OFFSET(x y z, ...) call."""
    return [float(ln.split("USE_TOOL_LENGTH_OFFSET(")[1].split(",")[0].split()[2]) for ln in lines
            if "USE_TOOL_LENGTH_OFFSET(" in ln]


_TOOLS = "G21\nT1 M6\nG43\nG0 Z1\nT2 M6\nG0 Z2\nT0 M6\nG0 Z3\nT1 M6\nG0 Z4\nM2\n"


def test_retain_g43_applies_each_new_tool_and_unloading_ends_it(tmp_path: Path) -> None:
    lines, _ = _run(tmp_path, "[RS274NGC]\nRETAIN_G43 = 1\n", _TOOLS)
    # T1 (G43), T2 (its M6), T0 unloads and ends G43: the T1 after it gets no offset
    assert _lengths(lines) == [pytest.approx(12.7), pytest.approx(2.54), 0.0]


def test_without_retain_g43_a_tool_change_keeps_the_offset(tmp_path: Path) -> None:
    lines, _ = _run(tmp_path, "[RS274NGC]\nRETAIN_G43 = 0\n", _TOOLS)
    assert _lengths(lines) == [pytest.approx(12.7)]


def test_spindles_allows_more_spindle_numbers(tmp_path: Path) -> None:
    text = "G21\nS100 $1 M3\nG0 X1\nM2\n"
    _, one = _run(tmp_path, "[TRAJ]\n", text)
    _, two = _run(tmp_path, "[TRAJ]\nSPINDLES = 2\n", text)
    assert "E0250" in one
    assert "E0250" not in two and "W0273" in two  # cncc runs it on its one spindle, and says so
    _, three = _run(tmp_path, "[TRAJ]\nSPINDLES = 2\n", "G21\nS100 $2 M3\nM2\n")
    assert "E0250" in three


def test_unknown_keys_are_ignored(tmp_path: Path) -> None:
    _, got = _run(tmp_path, "[RS274NGC]\nNO_SUCH_KEY = 3\nOWORD_NARGS = 1\n[NOSUCH]\nA = b\n", _ARC)
    assert got == []
