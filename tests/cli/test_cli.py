"""The command line: exit status, stdin/stdout, -o (atomic, never over an input),
-fsyntax-only, -Werror, --version, gcc-style diagnostics."""

from __future__ import annotations

import io
import os
import subprocess
import sys
from pathlib import Path

import pytest

from cncc.cli import main

ROOT = Path(__file__).resolve().parents[2]


def run(args: list[str], stdin: str = "") -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "cncc", *args], input=stdin, capture_output=True, text=True,
                          cwd=ROOT, timeout=120)


def test_example_compiles_cleanly() -> None:
    p = run(["examples/contour.nc"])
    assert p.returncode == 0, p.stderr
    assert " N..... STRAIGHT_FEED(55.0000, 45.0000, -10.0000, 0.0000, 0.0000, 0.0000)" in p.stdout.splitlines()


def test_stdin_to_stdout_and_exit_status_on_error() -> None:
    p = run(["-", "--emit=canon"], stdin="G01 X1. F10\nG999\n")
    assert p.returncode == 1
    assert "STRAIGHT_FEED(1.0000" in p.stdout  # the output so far is still printed on stdout
    assert "<stdin>:2:1: error: G999 is not a syntec code [E0201]" in p.stderr
    assert "  G999\n  ^~~~" in p.stderr
    assert "1 error generated." in p.stderr


def test_output_file_is_written_atomically(tmp_path: Path) -> None:
    src = tmp_path / "a.nc"
    src.write_text("G01 X1. F10\n")
    out = tmp_path / "out.txt"
    assert main([str(src), "-o", str(out)]) == 0
    assert "STRAIGHT_FEED" in out.read_text()
    assert not [p for p in os.listdir(tmp_path) if p.startswith(".cncc-")]


def test_output_never_overwrites_an_input(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    src = tmp_path / "a.nc"
    src.write_text("G01 X1. F10\n")
    assert main([str(src), "--emit=gcode", "-o", str(src)]) == 1
    assert src.read_text() == "G01 X1. F10\n"
    assert "E0906" in capsys.readouterr().err


def test_failed_compile_leaves_old_output_alone(tmp_path: Path) -> None:
    src = tmp_path / "a.nc"
    src.write_text("G999\n")
    out = tmp_path / "out.txt"
    out.write_text("previous")
    assert main([str(src), "-o", str(out)]) == 1
    assert out.read_text() == "previous"


def test_syntax_only_and_werror(tmp_path: Path) -> None:
    src = tmp_path / "a.nc"
    src.write_text("G01 X80.793. F10\n")
    p = run(["-fsyntax-only", str(src)])
    assert p.returncode == 0 and p.stdout == ""
    assert "warning: " in p.stderr and "[W0102]" in p.stderr
    p = run(["-fsyntax-only", "-Werror", str(src)])
    assert p.returncode == 1 and "error: " in p.stderr and "[W0102]" in p.stderr
    p = run(["-fsyntax-only", "-fstrict", str(src)])
    assert p.returncode == 1 and "error: " in p.stderr and "[E0102]" in p.stderr


def test_missing_file_and_bad_options() -> None:
    p = run(["does-not-exist.nc"])
    assert p.returncode == 1 and "cannot read does-not-exist.nc" in p.stderr
    p = run(["-x", "nosuch", "examples/contour.nc"])  # a bad option value is a usage error: exit 2
    assert p.returncode == 2 and "-x nosuch: unknown dialect" in p.stderr
    p = run(["--emit=bogus", "examples/contour.nc"])
    assert p.returncode == 2
    p = run(["-fnot_an_option=3", "examples/contour.nc"])
    assert p.returncode == 2 and "'not_an_option' is neither a cncc flag nor an option of dialect" in p.stderr
    p = run(["-Wfoo", "examples/contour.nc"])
    assert p.returncode == 2


def test_version() -> None:
    p = run(["--version"])
    assert p.returncode == 0 and p.stdout.startswith("cncc ")


def test_dialect_option_changes_meaning() -> None:
    r1 = run(["-", "-fsyntax-only"], stdin="G04 P2.5\n")
    r2 = run(["-", "-fsyntax-only", "-fg04_p_decimal=error"], stdin="G04 P2.5\n")
    assert r1.returncode == 0 and r2.returncode == 1


def test_main_in_process_does_not_raise_on_binary(capsys: pytest.CaptureFixture[str]) -> None:
    sys_stdin = sys.stdin
    try:
        sys.stdin = io.TextIOWrapper(io.BytesIO(bytes(range(256)) * 4))
        assert main(["-"]) == 1
    finally:
        sys.stdin = sys_stdin
    assert ": error: " in capsys.readouterr().err


def test_rapid_type_option_reaches_the_machine() -> None:
    from cncc.diagnostics import DiagnosticSink
    from cncc.driver import Options, apply_dialect_to_machine, default_machine
    from cncc.ir.machine import RapidMode

    sink = DiagnosticSink()
    m = apply_dialect_to_machine(default_machine(), Options(dialect_options={"rapid_type": "independent"}), sink)
    assert m.rapid_mode is RapidMode.INDEPENDENT and not list(sink)
    apply_dialect_to_machine(default_machine(), Options(dialect_options={"rapid_type": "dogleg"}), sink)
    assert [d.code for d in sink] == ["E0904"]


def test_readme_pulse_command_runs(tmp_path: Path) -> None:
    out = tmp_path / "p.vcd"
    p = run(["examples/contour.nc", "--emit=pulses", "--pulse-format=vcd", "--offsets", "examples/offsets.toml",
             "-o", str(out)])
    assert p.returncode == 0, p.stderr
    assert out.read_text().startswith("$comment cncc step/dir pulses $end")
