"""Generated documentation must match the code and data it is generated from."""

from __future__ import annotations

from cncc import diagnostics as dg
from cncc.tools import gendocs


def test_generated_pages_are_current() -> None:
    for rel, fn in gendocs.PAGES.items():
        text = (gendocs.ROOT / rel).read_text(encoding="utf-8")
        assert text == fn() + "\n", f"{rel} is stale: run python -m cncc.tools.gendocs"


def test_every_code_is_documented_once() -> None:
    page = gendocs.diagnostics_md()
    for code in dg.CODES:
        assert page.count(f"`{code}`") == 1, code
