"""The HTML timing page: self-contained, bounded, and working in headless Chromium.

The browser tests drive Chromium over its DevTools pipe (tests/browser.py): the page
must load with an empty console, draw every canvas, draw a rapid dashed, zoom the speed
chart with the wheel, and select the right program line when the path is clicked.
Expected lines are found in the program text; pixel colours come from the page's palette.
"""

from __future__ import annotations

import io
import itertools
import re
import time
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

from cncc.api import compile_text
from cncc.backends.timing.svg import LIMIT_COLORS, RAPID_COLOR, TOOL_COLORS
from cncc.ir import Rapid
from tests.backends.timing_pages import EXAMPLE, Built, big, contour, line_of
from tests.browser import CHROMIUM, Browser

MAX_PAGE_BYTES = 5_000_000
"""The page's bound whatever the program (docs/timing.md): 40 000 vertices, 16 384 speed columns,
the texts of the lines those refer to, 2 000 table rows."""

needs_chromium = pytest.mark.skipif(CHROMIUM is None, reason="chromium is not installed (scripts/ensure-chromium.sh)")


def test_page_fetches_nothing_and_is_small() -> None:
    r = compile_text(EXAMPLE.read_text(), emit="timing", report_format="html")
    assert r.ok, [d.message for d in r.sink]
    page = r.output
    assert not re.findall(r"https?://(?!www\.w3\.org/2000/svg)[^\s\"'<>]+", page)  # the SVG namespace name only
    assert not re.search(r"<link|<img|<iframe|\bsrc=|@import|url\(|fetch\(|XMLHttpRequest", page)
    assert page.count("<canvas") == 5 and 'data-ready="0"' in page
    assert len(page.encode()) < 400_000


def test_totals_and_tool_table_show_h_mm_ss() -> None:
    page = contour().page
    total_ns = contour().rep.primary.total_ns
    s = round(total_ns / 1e9)
    assert f"({s // 3600}:{s // 60 % 60:02d}:{s % 60:02d})" in page
    tools = page[page.index("<h2>Tools</h2>"):]
    assert "<td class=l>T1</td>" in tools


def _rgb(hex_color: str) -> np.ndarray:
    return np.array([int(hex_color[k:k + 2], 16) for k in (1, 3, 5)])


def _near(pixels: np.ndarray, hex_color: str, tol: int = 40) -> np.ndarray:
    return (np.abs(pixels.astype(np.int64) - _rgb(hex_color)) <= tol).all(axis=-1)


@pytest.fixture
def browser(tmp_path: Path) -> Iterator[Browser]:
    b = Browser(tmp_path / "profile", 1200, 900)
    try:
        yield b
    finally:
        b.close()


def _open(b: Browser, built: Built, tmp_path: Path) -> Path:
    page = tmp_path / "timing.html"
    page.write_text(built.page, encoding="utf-8")
    b.open(page.as_uri())
    return page


def _canvas_pixels(b: Browser, canvas_id: str, shot: Path) -> np.ndarray:
    """Screenshot pixels of one canvas (scrolled into view), (h, w, 3)."""
    from PIL import Image

    b.scroll_to(f"#{canvas_id}")
    time.sleep(0.1)
    r = b.js(f"(function(){{var r=document.getElementById('{canvas_id}').getBoundingClientRect();"
             f"return [r.left, r.top, r.width, r.height];}})()")
    img = Image.open(io.BytesIO(b.screenshot(shot))).convert("RGB")
    x, y, w, h = (round(v) for v in r)
    return np.asarray(img)[max(y, 0):y + h, max(x, 0):x + w]


def _check_views(b: Browser, tmp_path: Path) -> None:
    for cid in ("speed", "view-iso", "view-xy", "view-xz", "view-yz"):
        px = _canvas_pixels(b, cid, tmp_path / f"{cid}.png")
        assert px.size, cid
        ink = (px < 200).any(axis=-1).mean()
        assert ink > 0.002, (cid, ink)  # drawn, not blank
        if cid == "speed":
            assert _near(px, LIMIT_COLORS["feed"], 20).sum() > 200
        else:
            assert _near(px, TOOL_COLORS[1], 30).sum() > 50, cid  # T1 (the first tool after "no tool")


def _zoom(b: Browser) -> None:
    before = b.js("cnccTiming.speedRange()")
    b.scroll_to("#speed")
    r = b.js("(function(){var r=document.getElementById('speed').getBoundingClientRect();"
             "return [r.left + r.width / 2, r.top + r.height / 2];})()")
    b.wheel(r[0], r[1], -300)
    b.wheel(r[0], r[1], -300)
    after = b.js("cnccTiming.speedRange()")
    assert after[1] - after[0] < 0.8 * (before[1] - before[0])
    assert after[0] > before[0] and after[1] < before[1]
    shown = b.js("cnccTiming.shownSpeedMax()")
    assert 0 < shown <= b.js("JSON.parse(document.getElementById('cncc-data').textContent).speed.max")


def _click_selects(b: Browser, view: str, xyz: tuple[float, float, float], want_line: int) -> None:
    b.scroll_to(f"#view-{view}")
    time.sleep(0.1)
    x, y = b.js(f"cnccTiming.project('{view}', {xyz[0]}, {xyz[1]}, {xyz[2]})")
    sx, sy = b.js("[window.scrollX, window.scrollY]")
    b.click(x - sx, y - sy)
    sel = b.js("cnccTiming.selected()")
    assert sel is not None and sel["line"] == want_line, sel
    assert f"line {want_line}" in b.js("document.getElementById('selected').textContent")


def _dashed(b: Browser, view: str, p0: tuple[float, ...], p1: tuple[float, ...], tmp_path: Path) -> None:
    """Along the projection of the rapid p0-p1 the rapid colour comes and goes (dashes)."""
    from PIL import Image

    b.scroll_to(f"#view-{view}")
    time.sleep(0.1)
    sx, sy = b.js("[window.scrollX, window.scrollY]")
    img = np.asarray(Image.open(io.BytesIO(b.screenshot(tmp_path / "dash.png"))).convert("RGB"))
    on = []
    for u in np.linspace(0.15, 0.85, 200):
        q = [a + u * (c - a) for a, c in zip(p0, p1, strict=True)]
        x, y = b.js(f"cnccTiming.project('{view}', {q[0]}, {q[1]}, {q[2]})")
        xi, yi = round(x - sx), round(y - sy)
        patch = img[yi - 1:yi + 2, xi - 1:xi + 2]
        on.append(bool(_near(patch, RAPID_COLOR, 45).any()))
    changes = sum(1 for a, c in itertools.pairwise(on) if a != c)
    assert sum(on) > 40 and changes >= 6, (sum(on), changes)  # ink, and gaps in it


@needs_chromium
def test_contour_page_in_chromium(browser: Browser, tmp_path: Path) -> None:
    built = contour()
    _open(browser, built, tmp_path)
    assert browser.console == []
    _check_views(browser, tmp_path)
    _zoom(browser)
    # N008 X55.0 runs along Y45 from X20 to X55 at Z-10: click its middle in XY
    _click_selects(browser, "xy", (37.5, 45.0, -10.0), line_of(built.text, "N008"))
    # hovering shows the line, its N number and its block text
    browser.scroll_to("#view-xy")
    x, y = browser.js("cnccTiming.project('xy', 55.0, 25.0, -10.0)")  # on N009 Y10.0 (X55 from Y45 to Y10)
    sx, sy = browser.js("[window.scrollX, window.scrollY]")
    browser.call("Input.dispatchMouseEvent", {"type": "mouseMoved", "x": x - sx, "y": y - sy})
    tip = browser.js("document.getElementById('tip').textContent")
    assert f"line {line_of(built.text, 'N009')} · N009 · N009 Y10.0" in tip
    # a click on the speed chart in the middle of N006 selects N006
    n006 = line_of(built.text, "N006")
    browser.js("cnccTiming.setSpeedRange(0, 1e9)")
    row = browser.js(f"(function(){{var r=document.querySelectorAll('tr[data-i]');for(var k=0;k<r.length;k++)"
                     f"if(r[k].cells[0].textContent==='{n006}')return [+r[k].dataset.t0,+r[k].dataset.t1];}})()")
    browser.scroll_to("#speed")
    x, y = browser.js(f"cnccTiming.speedPoint({(row[0] + row[1]) / 2})")
    sx, sy = browser.js("[window.scrollX, window.scrollY]")
    browser.click(x - sx, y - sy)
    assert browser.js("cnccTiming.selected()")["line"] == n006
    # the table links back: a row click selects its line and zooms the speed chart to it
    n011 = line_of(built.text, "N011")
    browser.js(f"document.querySelectorAll('tr[data-i]')"
               f".forEach(function(tr){{if(tr.cells[0].textContent==='{n011}')tr.click();}})")
    assert browser.js("cnccTiming.selected()")["line"] == n011
    rng = browser.js("cnccTiming.speedRange()")
    assert rng[1] - rng[0] < 0.5 * built.data()["end_s"]
    # dragging the 3-D view turns it: the projection of a corner moves
    browser.scroll_to("#view-iso")
    time.sleep(0.1)
    before = browser.js("cnccTiming.project('iso', 55, 45, -10)")
    sx, sy = browser.js("[window.scrollX, window.scrollY]")
    x0, y0 = browser.js("cnccTiming.project('iso', 27.5, 22.5, 0)")
    for kind, dx in (("mousePressed", 0), ("mouseMoved", 40), ("mouseMoved", 80), ("mouseReleased", 80)):
        browser.call("Input.dispatchMouseEvent", {"type": kind, "x": x0 - sx + dx, "y": y0 - sy, "button": "left",
                                                  "clickCount": 1})
    after = browser.js("cnccTiming.project('iso', 55, 45, -10)")
    assert abs(after[0] - before[0]) + abs(after[1] - before[1]) > 10
    assert browser.console == []


@needs_chromium
@pytest.mark.slow
def test_100k_line_page_in_chromium(browser: Browser, tmp_path: Path) -> None:
    built = big()
    page = _open(browser, built, tmp_path)
    assert page.stat().st_size < MAX_PAGE_BYTES
    assert browser.console == []
    _check_views(browser, tmp_path)
    _zoom(browser)
    # the last rapid: G00 Z50.0 after the drilling, straight up from Z10 above the last hole
    last = next(c for c in reversed(built.cmds) if isinstance(c, Rapid) and c.end[2] == 50.0)
    p0, p1 = last.start[:3], last.end[:3]
    _dashed(browser, "xz", p0, p1, tmp_path)
    mid = tuple((a + c) / 2 for a, c in zip(p0, p1, strict=True))
    _click_selects(browser, "xz", mid, line_of(built.text, "G00 Z50.0", last=True))
    assert browser.console == []


@needs_chromium
@pytest.mark.parametrize("program", ["", "G04 X1.\nM00\n", "G00 X10.\n", "G01 X0 F100\n"])
def test_odd_pages_load_without_console_errors(browser: Browser, tmp_path: Path, program: str) -> None:
    page = tmp_path / "odd.html"
    page.write_text(compile_text(program, emit="timing", report_format="html", opt_level=0).output)
    browser.open(page.as_uri())
    assert browser.console == []


def test_contour_extents_and_path_lengths() -> None:
    path = contour().data()["path"]
    # examples/contour.nc: X0..55, Y0..45, Z-10..10 (the rapid N004 to Z10, the plunge N005 to Z-10)
    assert path["lo"] == pytest.approx([0.0, 0.0, -10.0], abs=1e-6)
    assert path["hi"] == pytest.approx([55.0, 45.0, 10.0], abs=1e-6)
    # feed: plunge 20, N006 38, N007 hypot(20, 7), N008 35, N009 35, the R10 quarter arc, N011 45
    feed = 20 + 38 + np.hypot(20, 7) + 35 + 35 + np.pi * 10 / 2 + 45
    assert path["feed_mm"] == pytest.approx(feed, abs=0.2)  # corners blended within 0.01 mm at -O2
    assert path["rapid_mm"] == pytest.approx(10 + 20, abs=0.05)  # N004 up 10 from the start at 0, N012 up 20
    assert path["holes_total"] == 0
    page = contour().page
    assert "Minimum Z <b>-10.000 mm</b>" in page


@pytest.mark.slow
def test_100k_page_marks_every_drilled_hole() -> None:
    built = big()
    path = built.data()["path"]
    text = built.text
    g81 = next(ln for ln in text.splitlines() if ln.startswith("G81"))
    bottom = float(re.search(r"Z(-?[\d.]+)", g81).group(1))  # type: ignore[union-attr]
    start = text.splitlines().index(g81)
    holes = [(10.0, 10.0)]
    for ln in text.splitlines()[start + 1:]:
        m = re.fullmatch(r"X([\d.]+) Y([\d.]+)", ln)
        if not m:
            break
        holes.append((float(m.group(1)), float(m.group(2))))
    assert path["holes_total"] == len(holes)
    got = np.array(path["holes"])
    assert np.allclose(got[:, :2], np.array(holes)[: len(got)]) and np.allclose(got[:, 2], bottom)


def test_tool_table_lists_the_offsets_each_tool_used() -> None:
    from tests.backends.timing_pages import shop_program

    # the generator: T1 with G43 H1, T2 with G43 H2 and G41 D2 (its contour), T3 with G43 H3
    page = compile_text(shop_program(2000), emit="timing", report_format="html", opt_level=1).output
    tools = page[page.index("<h2>Tools</h2>"):page.index("<h2>The ")]
    assert "<td class=l>T1</td><td class=l>–</td><td class=l>H1</td>" in tools
    assert "<td class=l>T2</td><td class=l>D2</td><td class=l>H2</td>" in tools
    assert "<td class=l>T3</td><td class=l>D2</td><td class=l>H3</td>" in tools  # D stays selected after G40
