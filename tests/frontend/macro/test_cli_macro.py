"""-D, -I, -M, -E and --io on the command line."""

from __future__ import annotations

from pathlib import Path

import pytest

from cncc.cli import main


def run(args: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str, str]:
    status = main(args)
    out, err = capsys.readouterr()
    return status, out, err


def test_define_include_and_list_deps(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "lib").mkdir()
    (tmp_path / "lib" / "O0020.nc").write_text("O0020\nG00 X#100\nM99\n")
    prog = tmp_path / "main.nc"
    prog.write_text("M98 P20\nM30\n")
    status, out, _ = run(["-D#100=7.5", "-I", str(tmp_path / "lib"), str(prog)], capsys)
    assert status == 0 and "STRAIGHT_TRAVERSE(7.5000" in out
    status, out, _ = run(["-M", "-I", str(tmp_path / "lib"), str(prog)], capsys)
    unfolded = out.replace(" \\\n ", " ")  # make joins the continued lines
    assert status == 0 and unfolded == f"main.canon: {prog} {tmp_path / 'lib' / 'O0020.nc'}\n"  # a make rule


def test_expand_prints_a_flat_program_with_a_line_map(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    prog = tmp_path / "loop.nc"
    prog.write_text("#1=1.\nWHILE [#1 LE 3.] DO 1\nG01 X#1 F100.\n#1=#1+1.\nEND 1\nM30\n")
    status, out, _ = run(["-E", str(prog)], capsys)
    assert status == 0
    assert "#" not in out and "WHILE" not in out
    assert "X1." in out and "X2." in out and "X3." in out
    assert f"({prog}:3)" in out
    # the flat program compiles to the same moves
    flat = tmp_path / "flat.nc"
    flat.write_text(out)
    _, a, _ = run([str(prog)], capsys)
    _, b, _ = run([str(flat)], capsys)
    assert [ln for ln in a.splitlines() if "STRAIGHT" in ln] == [ln for ln in b.splitlines() if "STRAIGHT" in ln]


def test_bad_define_is_a_usage_error(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit):
        main(["-Dfoo", "-"])


def test_io_file_errors_are_reported(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    io = tmp_path / "io.txt"
    io.write_text("X12 = maybe\n")
    prog = tmp_path / "p.nc"
    prog.write_text("WAT+X12\nM30\n")
    status, _, err = run(["-x", "szgh", "--io", str(io), str(prog)], capsys)
    assert status == 1 and "E0324" in err
