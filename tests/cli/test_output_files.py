"""``-o PATH``: special files are written in place, regular files replaced atomically
with the mode a Unix tool gives them (issue 17)."""

from __future__ import annotations

import os
import stat
import subprocess
import sys
import threading
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PROGRAM = "G01 X1. F10\n"


def cncc(args: list[str], umask: int | None = None) -> subprocess.CompletedProcess[str]:
    def set_umask() -> None:
        if umask is not None:
            os.umask(umask)

    env = dict(os.environ, PYTHONPATH=str(ROOT))
    return subprocess.run([sys.executable, "-m", "cncc", *args], capture_output=True, text=True, cwd=ROOT,
                          timeout=120, env=env, preexec_fn=set_umask)


@pytest.fixture()
def src(tmp_path: Path) -> Path:
    p = tmp_path / "a.nc"
    p.write_text(PROGRAM)
    return p


def test_fifo_is_written_in_place_and_read_by_a_reader(src: Path, tmp_path: Path) -> None:
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    got: list[bytes] = []

    def reader() -> None:
        with open(fifo, "rb") as fh:
            got.append(fh.read())

    t = threading.Thread(target=reader)
    t.start()
    p = cncc([str(src), "-o", str(fifo)])
    t.join(timeout=60)
    assert p.returncode == 0, p.stderr
    assert b"STRAIGHT_FEED(1.0000" in got[0]
    assert stat.S_ISFIFO(os.stat(fifo).st_mode)  # still the FIFO, not a regular file
    assert not [n for n in os.listdir(tmp_path) if n.startswith(".cncc-")]


@pytest.mark.skipif(os.geteuid() != 0, reason="mknod of a character device needs root")
def test_character_device_stays_a_device(src: Path, tmp_path: Path) -> None:
    dev = tmp_path / "null"
    os.mknod(dev, 0o666 | stat.S_IFCHR, os.makedev(1, 3))  # the same device as /dev/null
    p = cncc([str(src), "-o", str(dev)])
    assert p.returncode == 0, p.stderr
    st = os.stat(dev)
    assert stat.S_ISCHR(st.st_mode)
    assert st.st_rdev == os.makedev(1, 3)


def test_dev_null_and_dev_stdout(src: Path) -> None:
    before = os.stat("/dev/null")
    if stat.S_ISCHR(before.st_mode):  # (on a machine where it already is a regular file, nothing to check)
        p = cncc([str(src), "-o", "/dev/null"])
        assert p.returncode == 0, p.stderr
        after = os.stat("/dev/null")
        assert stat.S_ISCHR(after.st_mode) and after.st_ino == before.st_ino
    p = cncc([str(src), "-o", "/dev/stdout"])
    assert p.returncode == 0, p.stderr
    assert "STRAIGHT_FEED(1.0000" in p.stdout


def test_existing_file_keeps_its_mode(src: Path, tmp_path: Path) -> None:
    out = tmp_path / "out.txt"
    out.write_text("old")
    os.chmod(out, 0o664)
    p = cncc([str(src), "-o", str(out)], umask=0o077)
    assert p.returncode == 0, p.stderr
    assert stat.S_IMODE(os.stat(out).st_mode) == 0o664
    assert "STRAIGHT_FEED" in out.read_text()


def test_new_file_gets_0666_minus_umask(src: Path, tmp_path: Path) -> None:
    out = tmp_path / "new.txt"
    p = cncc([str(src), "-o", str(out)], umask=0o022)
    assert p.returncode == 0, p.stderr
    assert stat.S_IMODE(os.stat(out).st_mode) == 0o666 & ~0o022 == 0o644


def test_symlink_to_a_regular_file_keeps_the_link(src: Path, tmp_path: Path) -> None:
    target = tmp_path / "real.txt"
    target.write_text("old")
    link = tmp_path / "link.txt"
    link.symlink_to(target)
    p = cncc([str(src), "-o", str(link)])
    assert p.returncode == 0, p.stderr
    assert link.is_symlink()
    assert "STRAIGHT_FEED" in target.read_text()


def test_errors_write_nothing_to_a_fifo_reader(tmp_path: Path) -> None:
    bad = tmp_path / "bad.nc"
    bad.write_text("G999\n")
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    p = cncc([str(bad), "-o", str(fifo)])  # no reader needed: nothing is opened on error
    assert p.returncode == 1
    assert "E0201" in p.stderr
