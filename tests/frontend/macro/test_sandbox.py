"""SZGH program-writing statements write only inside --write-dir."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from tests.helpers import codes, compile_text


def write(name: str, out: Path) -> list[str]:
    text = f"FILEON({name})\nFILEWD(G0X1)\nFILECE\nM30\n"
    return codes(compile_text(text, dialect="szgh", write_dir=str(out)))


@pytest.mark.parametrize("name", ["../escape", "a/../../escape", "/tmp/cncc-escape-abs", "sub/./x", "~/x"])
def test_names_leaving_the_folder_are_refused(tmp_path: Path, name: str) -> None:
    out = tmp_path / "out"
    out.mkdir()
    assert "E0315" in write(name, out)
    assert not (tmp_path / "escape").exists()
    assert not Path("/tmp/cncc-escape-abs").exists()
    assert list(out.iterdir()) == []


def test_symlink_out_of_the_folder_is_refused(tmp_path: Path) -> None:
    out = tmp_path / "out"
    outside = tmp_path / "outside"
    out.mkdir()
    outside.mkdir()
    os.symlink(outside, out / "link")
    os.symlink(outside / "target", out / "file_link")
    assert "E0315" in write("link/prog", out)
    assert "E0315" in write("file_link", out)
    assert list(outside.iterdir()) == []


def test_a_subfolder_inside_is_allowed(tmp_path: Path) -> None:
    assert write("progs/P1", tmp_path) == []
    assert (tmp_path / "progs" / "P1").read_text() == "G0X1\n"


def test_an_input_file_is_never_overwritten(tmp_path: Path) -> None:
    from cncc.driver import Options, compile_files

    prog = tmp_path / "MAIN"
    prog.write_text("FILEON(MAIN)\nFILEWD(G0X9)\nFILECE\nM30\n")
    r = compile_files(Options(inputs=[str(prog)], dialect="szgh", write_dir=str(tmp_path)))
    assert "E0315" in codes(r)
    assert prog.read_text().startswith("FILEON(MAIN)")


def test_filewd_without_fileon_is_reported(tmp_path: Path) -> None:
    r = compile_text("FILEWD(G0X1)\nM30\n", dialect="szgh", write_dir=str(tmp_path))
    assert "E0315" in codes(r)
