"""cncc.toml, the modeline and the command line: one resolver (cncc/config.py) for the CLI and the LSP."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

from cncc import config

ROOT = Path(__file__).resolve().parents[2]
# line 1: "80.793." is a warning where numbers are lenient (syntec, the guess), an error where they are not;
# line 3: a call of a program that is nowhere
PROGRAM = "G01 X80.793. F10\nG999\nM98 P77\nM30\n"
TOML = 'dialect = "szgh"\n[options]\nlenient_numbers = false\n'


def run(args: list[str], cwd: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "cncc", *args], capture_output=True, text=True, cwd=cwd,
                          timeout=120, env={**os.environ, "PYTHONPATH": str(ROOT)})


def cli_codes(path: Path, *args: str) -> list[tuple[int, str]]:
    p = run(["-fsyntax-only", "-fdiagnostics-format=json", *args, str(path)], path.parent)
    return [(d["line"], d["code"]) for d in json.loads(p.stderr)["diagnostics"]]


def project(tmp_path: Path, text: str = PROGRAM) -> Path:
    (tmp_path / "proj" / "sub").mkdir(parents=True)
    (tmp_path / "proj" / "cncc.toml").write_text(TOML)
    prog = tmp_path / "proj" / "sub" / "part.nc"
    prog.write_text(text)
    return prog


def test_cli_reads_cncc_toml_upward(tmp_path: Path) -> None:
    prog = project(tmp_path)
    alone = tmp_path / "alone.nc"
    alone.write_text(PROGRAM)
    assert ("1", "W0102") in {(str(line), c) for line, c in cli_codes(alone)}  # no project: syntec, lenient
    assert cli_codes(prog) == [(1, "E0102"), (2, "E0201"), (3, "E0310")]  # szgh, strict numbers
    # the command line wins over the file, key by key
    assert cli_codes(prog, "-flenient_numbers=true")[0] == (1, "W0102")
    assert "syntec code" in run(["-fsyntax-only", "-x", "syntec", str(prog)], prog.parent).stderr


def test_modeline_beats_the_file_and_the_command_line_beats_both(tmp_path: Path) -> None:
    prog = project(tmp_path, "(cncc: dialect=fanuc)\n" + PROGRAM)
    p = run(["-fsyntax-only", str(prog)], prog.parent)
    assert "G999 is not a fanuc code" in p.stderr
    p = run(["-fsyntax-only", "-x", "syntec", str(prog)], prog.parent)
    assert "G999 is not a syntec code" in p.stderr


def test_verbose_says_where_each_setting_came_from(tmp_path: Path) -> None:
    prog = project(tmp_path, "(cncc: dialect=fanuc)\n" + PROGRAM)
    toml = tmp_path / "proj" / "cncc.toml"
    p = run(["-v", "-fsyntax-only", "-O1", str(prog)], prog.parent)
    notes = [ln for ln in p.stderr.splitlines() if "[N0907]" in ln]
    text = "\n".join(notes)
    assert f"dialect fanuc from the modeline at {prog}:1" in text
    assert f"-flenient_numbers=False from {toml}" in text
    assert "opt_level 1 from the command line" in text
    assert "machine generic-mill (default)" in text


def test_a_broken_cncc_toml_is_reported(tmp_path: Path) -> None:
    prog = project(tmp_path)
    (tmp_path / "proj" / "cncc.toml").write_text("dialect = \n")
    p = run(["-fsyntax-only", str(prog)], prog.parent)
    assert p.returncode == 1 and "[E0908]" in p.stderr and "cncc.toml" in p.stderr
    (tmp_path / "proj" / "cncc.toml").write_text("opt_level = 9\n")
    assert "[E0908]" in run(["-fsyntax-only", str(prog)], prog.parent).stderr


def test_resolver_order_and_relative_paths(tmp_path: Path) -> None:
    (tmp_path / "cncc.toml").write_text('machine = "m.toml"\ntools = "t.tbl"\nopt-level = 1\n'
                                        '[cncc]\ndialect = "fanuc"\n[options]\na = 1\nb = 2\n')
    (tmp_path / "d").mkdir()
    res = config.resolve(str(tmp_path / "d" / "p.nc"), "G1 X1\n", {"options": {"b": 3}, "dialect": None})
    assert res.values == {"machine": str(tmp_path / "m.toml"), "tools": str(tmp_path / "t.tbl"), "opt_level": 1,
                          "dialect": "fanuc", "options": {"a": 1, "b": 3}}
    assert res.origins["options.a"] == str(tmp_path / "cncc.toml")
    assert res.origins["options.b"] == "the command line"
    res = config.resolve(None, "(cncc: dialect=grbl)\n", {})  # standard input: no project file
    assert res.values == {"dialect": "grbl"} and res.config_path is None


def test_cli_and_lsp_give_the_same_diagnostics(tmp_path: Path) -> None:
    from cncc.lsp.analysis import Request, analyze, new_analysis
    from cncc.lsp.server import CnccServer

    prog = project(tmp_path)
    text = prog.read_text()
    server = CnccServer()
    server.root = str(tmp_path / "proj")
    uri = prog.as_uri()
    settings, error = server.settings_for(uri)
    assert error is None
    a = new_analysis(Request(uri, str(prog), 1, text, server.dialect_name(uri, text, settings), settings))
    analyze(a, lambda: None)
    lsp = sorted((text.count("\n", 0, d.span.start) + 1, d.code) for d in a.diagnostics)
    cli = cli_codes(prog)
    assert cli == [(1, "E0102"), (2, "E0201"), (3, "E0310")]
    assert lsp == cli
