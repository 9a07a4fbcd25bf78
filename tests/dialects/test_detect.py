"""Dialect detection when -x is not given (reported with -v)."""

from __future__ import annotations

import pytest

from cncc.cli import main
from cncc.frontend.detect import guess_dialect


@pytest.mark.parametrize("name, text, want", [
    ("a.nc", "o<peck> sub\nG1 X1\no<peck> endsub\n", "linuxcnc"),
    ("a.nc", "#<depth> = 2\nG1 Z#<depth>\n", "linuxcnc"),
    ("a.txt", "WAT+X12\nG0 X1\n", "szgh"),
    ("a.nc", "$H\nG21 G0 X1\n", "grbl"),
    ("part.gcode", "G21 G90\nG1 X1 F100\n", "grbl"),
    ("part.ngc", "G0 X1\n", "linuxcnc"),
    ("a.nc", "G71 G90\nG0 X5500\n", "syntec"),
    ("a.nc", "O1000\nG21\n#1=5.\nG0 X#1\n", "fanuc"),
    ("a.nc", "G21 G90\nG1 X1 F100\n", "linuxcnc"),
    ("a.nc", "G0 X1\n", "syntec"),
])
def test_guess(name: str, text: str, want: str) -> None:
    assert guess_dialect(name, text)[0] == want


def test_verbose_reports_the_guess(tmp_path: object, capsys: pytest.CaptureFixture[str]) -> None:
    import pathlib

    p = pathlib.Path(str(tmp_path)) / "part.ngc"
    p.write_text("o100 if [1]\nG0 X1\no100 endif\nM2\n")
    assert main(["-v", "--emit=none", str(p)]) == 0
    err = capsys.readouterr().err
    assert "N0251" in err and "dialect linuxcnc" in err
    assert main(["--emit=none", str(p)]) == 0
    assert "N0251" not in capsys.readouterr().err
