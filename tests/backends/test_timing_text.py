"""The terminal timing report fits the width it is given, shows h:mm:ss, ends no line in spaces."""

from __future__ import annotations

import re

import pytest
from rich.cells import cell_len

from cncc.backends.timing.text import render_text
from tests.backends.timing_pages import contour

ANSI = re.compile(r"\x1b\[[0-9;]*m")


@pytest.mark.parametrize("width", [60, 80, 100, 200])
@pytest.mark.parametrize("color", [False, True])
def test_text_report_fits_the_width(width: int, color: bool) -> None:
    out = render_text(contour().rep, color=color, width=width)
    lines = [ANSI.sub("", ln) for ln in out.splitlines()]
    assert max(cell_len(ln) for ln in lines) <= width
    assert all(ln == ln.rstrip() for ln in lines)
    assert any("N008" in ln for ln in lines)  # the block column keeps some text even when narrow


def test_text_report_totals_in_h_mm_ss() -> None:
    rep = contour().rep
    out = render_text(rep, width=120)
    for col in rep.columns:
        s = round(col.total_ns / 1e9)
        assert f"({s // 3600}:{s // 60 % 60:02d}:{s % 60:02d})" in out
    assert re.search(r"total\s+\d+\.\d{3} s \(\d+:\d\d:\d\d\)", out)


def test_width_from_columns_variable(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("COLUMNS", "72")
    out = render_text(contour().rep)
    assert max(cell_len(ln) for ln in out.splitlines()) <= 72
