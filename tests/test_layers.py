"""Project-wide checks: the import layers hold, ruff is clean, and the CLI and the
language server start without importing the heavy numerical packages."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.skipif(shutil.which("lint-imports") is None, reason="import-linter not installed")
def test_import_layers() -> None:
    p = subprocess.run(["lint-imports"], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stdout[-3000:]


@pytest.mark.skipif(shutil.which("ruff") is None, reason="ruff not installed")
def test_ruff_clean() -> None:
    p = subprocess.run(["ruff", "check", "cncc", "bench", "tests"], cwd=ROOT, capture_output=True, text=True,
                       timeout=300)
    assert p.returncode == 0, p.stdout[-3000:]


def test_cli_start_is_light() -> None:
    code = ("import sys, cncc.cli, cncc.driver, cncc.frontend; "
            "heavy = [m for m in ('numpy', 'toppra', 'casadi', 'ruckig', 'rich') if m in sys.modules]; "
            "print(','.join(heavy))")
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    assert p.stdout.strip() == ""


@pytest.mark.skipif(shutil.which("mypy") is None, reason="mypy not installed")
def test_mypy_strict() -> None:
    """The whole package type-checks under ``mypy --strict`` (configured in pyproject.toml)."""
    p = subprocess.run(["mypy"], cwd=ROOT, capture_output=True, text=True, timeout=900)
    assert p.returncode == 0, p.stdout[-3000:]
