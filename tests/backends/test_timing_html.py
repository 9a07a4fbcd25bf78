"""The HTML timing report: self-contained, and rendered by headless Chromium with its plots."""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from cncc.api import compile_text
from cncc.backends.timing.svg import CATEGORY_COLORS, LIMIT_COLORS, SPEED_COLORS

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "contour.nc"
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")


def html_report(opt_level: int = 2) -> str:
    r = compile_text(EXAMPLE.read_text(), emit="timing", report_format="html", opt_level=opt_level)
    assert r.ok, [d.message for d in r.sink]
    return r.output


def test_page_fetches_nothing() -> None:
    page = html_report()
    assert set(re.findall(r"https?://[^\s\"'<>]+", page)) <= {"http://www.w3.org/2000/svg"}  # a namespace name
    assert not re.search(r"<link|<img|<iframe|\bsrc=|@import|url\(", page)
    assert page.count("<svg") == 3 and "data-ready" in page


def _count(pixels: np.ndarray, hex_color: str, tol: int = 12) -> int:
    """Pixels within ``tol`` per channel of ``hex_color`` (``pixels``: (h, w, 3) uint8)."""
    want = np.array([int(hex_color[k:k + 2], 16) for k in (1, 3, 5)])
    return int((np.abs(pixels.astype(np.int64) - want) <= tol).all(axis=2).sum())


@pytest.mark.skipif(CHROMIUM is None, reason="chromium is not installed (scripts/ensure-chromium.sh)")
def test_chromium_renders_the_plots_without_console_errors(tmp_path: Path) -> None:
    from PIL import Image

    page = tmp_path / "timing.html"
    page.write_text(html_report(), encoding="utf-8")
    shot = tmp_path / "timing.png"
    proc = subprocess.run(
        [str(CHROMIUM), "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
         "--enable-logging=stderr", "--v=0", "--proxy-server=127.0.0.1:9",  # any network fetch would fail loudly
         f"--user-data-dir={tmp_path / 'profile'}", f"--screenshot={shot}", "--dump-dom",
         "--window-size=1100,1400", page.as_uri()],
        capture_output=True, text=True, timeout=120, check=False)
    console = [ln for ln in proc.stderr.splitlines() if ":CONSOLE" in ln]
    assert console == []
    assert 'data-ready="1"' in proc.stdout  # the page's script ran to the end
    img = Image.open(shot).convert("RGB")
    assert img.size == (1100, 1400)
    pixels = np.asarray(img)
    # colours that only the plots use: the speed trace limited by feed, the tool-path
    # segments at full feed, the tool-change bar
    assert _count(pixels, LIMIT_COLORS["feed"]) > 300
    assert _count(pixels, SPEED_COLORS[-1]) > 300
    assert _count(pixels, CATEGORY_COLORS["tool_change"]) > 300
