"""cncc.api.compile / translate / time: typed results (issue 19)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import cncc.api as api
from cncc import driver

ROOT = Path(__file__).resolve().parents[2]


def test_text_and_path_and_guess(tmp_path: Path) -> None:
    prog = tmp_path / "p.ngc"
    prog.write_text("o100 if [1 GT 0]\nG01 X1 F100\no100 endif\nM2\n")
    r = api.compile(prog)  # a Path: the file; its O-words make it LinuxCNC
    assert r.ok and r.dialect == "linuxcnc"
    r = api.compile(str(prog), dialect="linuxcnc", emit="ir")
    assert r.ok and r.output
    r = api.compile("G01 X1. F100\n")  # text
    assert r.ok and r.dialect == "syntec" and "STRAIGHT_FEED(1.0000" in r.output


def test_diagnostics_are_typed_and_sorted() -> None:
    r = api.compile("M98 P1234\nG01 X1.2.3 F10\n", dialect="fanuc")
    assert [(d.file, d.line, d.column, d.severity, d.code) for d in r.diagnostics] == [
        ("<stdin>", 1, 1, "error", "E0310"), ("<stdin>", 2, 9, "error", "E0101")]
    assert str(r.diagnostics[1]) == "<stdin>:2:9: error: unexpected '.'; block skipped [E0101]"
    bad = api.compile("G0 X1\n", machine="no-such-machine")
    assert not bad.ok and bad.diagnostics[0].file is None and bad.diagnostics[0].code == "E0904"


def test_time_matches_an_independent_computation() -> None:
    # 100 mm at F600 (10 mm/s) on -O0, the nominal estimate: 10 s of feed, no rapid
    r = api.time("G90 G01 X100. F600.\n", dialect="syntec", opt_level=0)
    assert r.ok and r.timing is not None
    assert r.timing.total_s == pytest.approx(10.0, abs=1e-9)
    assert r.timing.per_category["feed"] == pytest.approx(10.0, abs=1e-9)
    assert [(ln.line, ln.time_s) for ln in r.timing.per_line] == [(1, pytest.approx(10.0, abs=1e-9))]
    p, v, _, _ = r.trajectory.sample(np.array([5.0]))
    assert p[0, 0] == pytest.approx(50.0, abs=1e-6) and v[0, 0] == pytest.approx(10.0, abs=1e-6)


def test_translate() -> None:
    r = api.translate("G90 G01 X10. F100.\n", "grbl", dialect="syntec")
    assert r.ok and r.gcode is not None and "G01 X10. F100." in r.gcode.splitlines()


def test_numpy_warnings_become_diagnostics(monkeypatch: pytest.MonkeyPatch) -> None:
    real = driver.run_backend

    def noisy(*args: object, **kwargs: object) -> object:
        np.log(np.zeros(1))  # RuntimeWarning: divide by zero encountered in log
        return real(*args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(driver, "run_backend", noisy)
    r = api.compile("G01 X1. F100\n")
    codes = [d.code for d in r.diagnostics]
    assert codes == ["W0909"] and "divide by zero" in r.diagnostics[0].message
    assert r.ok  # a warning
