"""The language server reports every problem the compiler reports (issue 20): the first
phase of an analysis and ``cncc -fsyntax-only`` (``driver.compile_files``) of the same
file give the same diagnostic codes at the same places, on programs with several
problems in every dialect family."""

from __future__ import annotations

from pathlib import Path

import pytest

from cncc import driver
from cncc.lsp.analysis import Request, analyze, new_analysis
from cncc.lsp.config import Settings

PROGRAMS = {
    # two missing subprograms, a missing macro, then a block that does not parse
    "fanuc": "O1\nM98 P9001\nM98 P9002\nG65 P9003 A1.\nG01 X1. Q\nG01 X2. F100.\nM30\n",
    "syntec": "G90 G17 G00 X0 Y0\nG02 X8. Y0 I3. J4. F100.\nG01 X10. Q\nG01 X11. F0\nM30\n",
    "szgh": "G90 G00 X0 Y0\nM98 PNOSUCH\nG01 X1. Q\nG01 X2. F100.\nM30\n",
    "linuxcnc": "G21 G90\no<nosuch> call [1]\nG01 X1. F100.\nM2\n",
    "grbl": "G21 G90\nG01 X1.\nG02 X5. Y0 I0 J0 F100\nM2\n",
}


def compiler_codes(path: Path, dialect: str) -> list[tuple[str, int]]:
    opts = driver.Options(inputs=[str(path)], dialect=dialect, syntax_only=True, include_dirs=[str(path.parent)])
    result = driver.compile_files(opts)
    return sorted((d.code, d.span.start) for d in result.sink if d.span.source_id >= 0)


def server_codes(path: Path, dialect: str) -> list[tuple[str, int]]:
    text = path.read_text(encoding="utf-8")
    a = new_analysis(Request(path.as_uri(), str(path), 1, text, dialect, Settings(root=str(path.parent))))
    analyze(a, lambda: None)
    assert a.stopped is None
    return sorted((d.code, d.span.start) for d in a.diagnostics if d.span.source_id >= 0)


@pytest.mark.parametrize("dialect", sorted(PROGRAMS))
def test_the_server_reports_what_the_compiler_reports(dialect: str, tmp_path: Path) -> None:
    path = tmp_path / f"prog.{'ngc' if dialect == 'linuxcnc' else 'nc'}"
    path.write_text(PROGRAMS[dialect], encoding="utf-8")
    expected = compiler_codes(path, dialect)
    assert expected  # every program here has problems
    assert server_codes(path, dialect) == expected


def test_every_missing_subprogram_is_reported(tmp_path: Path) -> None:
    path = tmp_path / "prog.nc"
    text = PROGRAMS["fanuc"]
    path.write_text(text, encoding="utf-8")
    lines = {text[:at].count("\n") for code, at in server_codes(path, "fanuc") if code == "E0310"}
    assert {1, 2, 3} <= lines  # M98 P9001, M98 P9002, G65 P9003
