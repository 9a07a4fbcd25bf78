"""examples/: one program per dialect compiles cleanly, and the README's example commands run."""

from __future__ import annotations

import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = {"contour.nc": "syntec", "szgh_macro.nc": "szgh", "series8_part.nc": "series8",
            "fanuc_bolt_circle.nc": "fanuc", "haas_slots.nc": "haas", "linuxcnc_pocket.ngc": "linuxcnc",
            "grbl_square.gcode": "grbl"}
MODELINE = {"szgh_macro.nc", "series8_part.nc"}  # read in their dialect without -x


def run(args: list[str], cwd: Path = ROOT) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "cncc", *args], capture_output=True, text=True, cwd=cwd,
                          timeout=300, env={**os.environ, "PYTHONPATH": str(ROOT)})


def test_one_example_per_dialect() -> None:
    from cncc.dialects import available

    assert sorted(EXAMPLES.values()) == sorted(available())
    assert all((ROOT / "examples" / name).is_file() for name in EXAMPLES)


@pytest.mark.parametrize("name", sorted(EXAMPLES))
def test_example_compiles_cleanly(name: str) -> None:
    p = run(["-x", EXAMPLES[name], "-Werror", f"examples/{name}"])
    assert p.returncode == 0 and p.stderr == "", p.stderr
    assert "STRAIGHT_FEED" in p.stdout or "ARC_FEED" in p.stdout
    if name in MODELINE:
        p = run(["-v", "-fsyntax-only", f"examples/{name}"])
        assert f"dialect {EXAMPLES[name]} from the modeline" in p.stderr


def readme_commands() -> list[str]:
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    section = text.split("## Examples", 1)[1].split("\n## ", 1)[0]
    cmds = []
    for block in re.findall(r"```sh\n(.*?)```", section, re.DOTALL):
        for line in block.splitlines():
            line = line.split("  #", 1)[0].strip()
            if line.startswith("cncc "):
                cmds.append(line)
    return cmds


def test_readme_example_commands_run(tmp_path: Path) -> None:
    cmds = readme_commands()
    assert len(cmds) >= 6
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    for cmd in cmds:
        p = run(shlex.split(cmd)[1:], cwd=tmp_path)
        assert p.returncode == 0, (cmd, p.stderr)
        assert " error: " not in p.stderr and " warning: " not in p.stderr, (cmd, p.stderr)
