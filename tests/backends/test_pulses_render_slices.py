"""The VCD and CSV writers render their text a slice of ``RENDER_ROWS`` events at a time (bounded
memory: the byte matrices of a whole 2^18-step chunk took ~80 MB), and the text is the same as
one rendering of the whole chunk (VCD) or as Python's own formatting of every event (CSV, the
per-row writer it replaces), with direction, backlash and step events and chunk boundaries."""

from __future__ import annotations

import io

import pytest

from cncc.backends.pulses import text, vcd, write, write_pulses
from cncc.backends.pulses.events import KIND_BACKLASH, KIND_DIR, ordered_events
from tests.backends.test_pulses_writers import chunks_of

SLICE = 37


def _spy(monkeypatch: pytest.MonkeyPatch, module: object, name: str, seen: list[int]) -> None:
    real = getattr(text, name)

    def counting(*args: object, **kw: object) -> object:
        seen.append(len(args[0]) if name == "stamped" else len(args[0][0].data))  # type: ignore[index, arg-type]
        return real(*args, **kw)

    monkeypatch.setattr(module, name, counting)


def test_vcd_rendered_in_slices_is_the_whole_chunk_text(monkeypatch: pytest.MonkeyPatch) -> None:
    chunks = chunks_of(400)
    whole = io.StringIO()
    monkeypatch.setattr(vcd, "RENDER_ROWS", 1 << 40)
    write_pulses(iter(chunks), "vcd", whole)
    seen: list[int] = []
    _spy(monkeypatch, vcd, "stamped", seen)
    monkeypatch.setattr(vcd, "RENDER_ROWS", SLICE)
    sliced = io.StringIO()
    write_pulses(iter(chunks), "vcd", sliced)
    assert sliced.getvalue() == whole.getvalue()
    assert max(seen) <= SLICE and len(seen) > 10  # really a slice at a time


def test_csv_rendered_in_slices_is_python_formatting(monkeypatch: pytest.MonkeyPatch) -> None:
    chunks = chunks_of(400)
    names = {KIND_DIR: "dir", KIND_BACKLASH: "backlash"}
    want = ["t_ns,axis,event,dir_level\n"]
    for layout, ev in ordered_events(iter(chunks), with_falls=False):
        want += [f"{t},{layout.axes[a]},{names.get(k, 'step')},{lv}\n" for t, a, k, lv in zip(
            ev["t_ns"].tolist(), ev["axis"].tolist(), ev["kind"].tolist(), ev["level"].tolist(), strict=True)]
    kinds = {r.split(",")[2] for r in want[1:]}
    assert kinds == {"step", "dir", "backlash"}  # every kind of event is written
    seen: list[int] = []
    _spy(monkeypatch, write.text, "render", seen)
    monkeypatch.setattr(write, "RENDER_ROWS", SLICE)
    out = io.StringIO()
    write_pulses(iter(chunks), "csv", out)
    assert out.getvalue() == "".join(want)
    assert max(seen) <= SLICE and len(seen) > 10
