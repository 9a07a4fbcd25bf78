"""The LinuxCNC lexical views (issue 20): the quick subroutine scan used by hover agrees
with the full outline used by definition, references and symbols."""

from __future__ import annotations

from tests.lsp.conftest import DATA

SQUARE = (DATA / "square.ngc").read_text(encoding="utf-8")


def test_the_quick_subroutine_scan_agrees_with_the_outline() -> None:
    from cncc.dialects import load_dialect
    from cncc.lsp.navigate import outline, subroutines

    text = SQUARE + "O 100 sub\nG0 X#1\no100 endsub\no100 call [3]\n  o< Other Sub > call\n"
    fast, full = subroutines(text), outline(text, load_dialect("linuxcnc"))
    assert fast.subs == full.subs and fast.calls == full.calls and fast.sub_ends == full.sub_ends
