"""The Python snippets of the documentation run: every ```python block of the pages below is
executed, in order, in one namespace per page, from a folder with a copy of examples/."""

from __future__ import annotations

import contextlib
import io
import os
import re
import shutil
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGES = ["docs/api.md", "docs/planning.md", "docs/pulses.md", "README.md"]
BLOCK = re.compile(r"^```python\n(.*?)^```", re.MULTILINE | re.DOTALL)


def blocks(page: str) -> list[str]:
    return BLOCK.findall((ROOT / page).read_text(encoding="utf-8"))


@pytest.mark.parametrize("page", PAGES)
def test_python_snippets_run(page: str, tmp_path: Path) -> None:
    found = blocks(page)
    assert found, f"{page} has no python block"
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    namespace: dict[str, object] = {"__name__": "__docs__"}
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        for i, code in enumerate(found):
            with contextlib.redirect_stdout(io.StringIO()):
                exec(compile(code, f"{page}[python block {i + 1}]", "exec"), namespace)
    finally:
        os.chdir(cwd)


def test_a_broken_snippet_fails(tmp_path: Path) -> None:
    namespace: dict[str, object] = {}
    with pytest.raises(AssertionError):
        exec(compile("import cncc.api\nassert cncc.api.compile('G999\\n').ok\n", "<t>", "exec"), namespace)
