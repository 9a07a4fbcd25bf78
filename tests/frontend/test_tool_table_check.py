"""LinuxCNC's tool-table check: T and M61 Q name a tool the given table must list.

rs274 2.9 stops at ``T1`` with "Requested tool 1 not found in the tool table" when its table
has no tool 1 (tests/oracle/cases.py holds the oracle cases: tool_not_in_given_table and the
others).  cncc checks only when a table is given (``--tools``): without one it cannot know
the machine's tools.  Other dialects select pockets and never check.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

PROGRAM = "G21\nG0 X1\nT1\nG0 X2\nM2\n"


def _run(tmp_path: Path, *args: str, text: str = PROGRAM) -> subprocess.CompletedProcess[str]:
    src = tmp_path / "p.ngc"
    src.write_text(text)
    return subprocess.run([sys.executable, "-m", "cncc", str(src), "--emit=canon", *args],
                          capture_output=True, text=True, check=False, cwd=tmp_path)


def _table(tmp_path: Path, body: str) -> str:
    path = tmp_path / "tool.tbl"  # a LinuxCNC tool table: T number, pocket, Z length, D diameter
    path.write_text(body)
    return str(path)


def _toml(tmp_path: Path, body: str) -> str:
    path = tmp_path / "tools.toml"  # cncc's own table: offset numbers, not tools
    path.write_text('units = "mm"\n' + body)
    return str(path)


def test_a_tool_missing_from_the_given_table_is_an_error_at_the_t_word(tmp_path: Path) -> None:
    r = _run(tmp_path, "-x", "linuxcnc", "--tools", _table(tmp_path, "T2 P2 Z10\n"))
    assert r.returncode == 1, r.stderr
    assert "p.ngc:3:1: error: Requested tool 1 not found in the tool table [E0250]" in r.stderr, r.stderr
    assert "Traceback" not in r.stderr


def test_a_listed_tool_and_t0_pass(tmp_path: Path) -> None:
    table = _table(tmp_path, "T1 P1 Z10\n")
    assert _run(tmp_path, "-x", "linuxcnc", "--tools", table).returncode == 0
    assert _run(tmp_path, "-x", "linuxcnc", "--tools", table, text="G21\nT0 M6\nM2\n").returncode == 0


def test_m61_checks_the_same_table(tmp_path: Path) -> None:
    r = _run(tmp_path, "-x", "linuxcnc", "--tools", _table(tmp_path, "T2 P2 D2\n"),
             text="G21\nM61 Q1\nM2\n")
    assert r.returncode == 1 and "Requested tool 1 not found in the tool table" in r.stderr, r.stderr


@pytest.mark.parametrize("dialect", ["linuxcnc", "syntec", "fanuc"])
def test_without_a_table_nothing_is_checked(tmp_path: Path, dialect: str) -> None:
    text = PROGRAM if dialect == "linuxcnc" else "G0 X1\nT1\nG0 X2\nM30\n"
    r = _run(tmp_path, "-x", dialect, text=text)
    assert r.returncode == 0, r.stderr


def test_other_dialects_do_not_check_a_given_table(tmp_path: Path) -> None:
    r = _run(tmp_path, "-x", "syntec", "--tools", _table(tmp_path, "T2 P2 Z10\n"),
             text="G0 X1\nT1\nG0 X2\nM30\n")
    assert r.returncode == 0, r.stderr


def test_a_toml_table_lists_offsets_not_tools(tmp_path: Path) -> None:
    # a syntec program translated to linuxcnc is re-read with the same TOML table of H/D offsets
    r = _run(tmp_path, "-x", "linuxcnc", "--tools", _toml(tmp_path, "[tools.2]\nlength_mm = 10.0\n"))
    assert r.returncode == 0, r.stderr
