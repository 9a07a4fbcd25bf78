"""Incremental analysis (issue 20): after an edit, a resumed analysis (re-run from the last
checkpoint before the change until the state meets the old run's) gives exactly what a full
analysis of the new text gives -- commands, diagnostics, line times -- and re-runs few lines."""

from __future__ import annotations

import random
import sys
from pathlib import Path

import pytest

from cncc.diagnostics import Diagnostic
from cncc.lsp.analysis import Analysis, Request, analyze, new_analysis
from cncc.lsp.config import Settings
from cncc.lsp.incremental import EVERY, Shifts, changed_range, materialize, resume

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bench"))
from gen import cam_program

MIXED = "".join([
    "%\nO1000 (mixed program)\nG90 G17 G21 G94\nG00 X0 Y0 Z5.\nG01 Z-1. F600.\n",
    *(f"G01 X{i % 17}.5 Y{i % 11}. (pass {i})\n" if i % 7 else f"G02 X{i % 17 + 2}.5 Y{i % 11}. I1. J0\n"
      for i in range(600)),
    "G91\n", *("G01 X0.5 Y-0.25\n" for _ in range(200)), "G90\n",
    *(f"G00 X{i}. Y{i}.\nG01 Z-2. F300.\nG00 Z5.\n" for i in range(100)),
    "G01 X1. Q\n",  # an error (a value missing) far down
    "M30\n%\n",
])


def full(text: str, dialect: str = "syntec") -> Analysis:
    a = new_analysis(Request("file:///p.nc", "/p.nc", 1, text, dialect, Settings()))
    analyze(a, lambda: None)
    return a


def resumed(old: Analysis, text: str) -> Analysis | None:
    a = new_analysis(Request("file:///p.nc", "/p.nc", 2, text, old.request.dialect, Settings()), old)
    return a if resume(old, a, lambda: None) else None


def assert_same(a: Analysis, b: Analysis) -> None:
    assert materialize(a.commands, a.shifts) == materialize(b.commands, b.shifts)
    def key(d: Diagnostic) -> tuple[str, int, int, int, str]:
        return (d.code, d.span.source_id, d.span.start, d.span.end, d.message)

    assert sorted(map(key, a.diagnostics)) == sorted(map(key, b.diagnostics))
    assert a.line_time_s == b.line_time_s
    assert a.index._starts == b.index._starts


def random_edit(rnd: random.Random, text: str) -> str:
    at = rnd.randrange(len(text))
    kind = rnd.choice(["replace", "insert", "delete", "line"])
    if kind == "replace":
        return text[:at] + rnd.choice("0123456789 XYG.") + text[at + 1:]
    if kind == "insert":
        return text[:at] + rnd.choice("0123456789XY.\n") + text[at:]
    if kind == "delete":
        return text[:at] + text[at + 1:]
    return text[:at] + "\nG01 X1. Y2. Z-1.\n" + text[at:]


@pytest.mark.parametrize(("name", "text"), [("cam", cam_program(3000)), ("mixed", MIXED)], ids=["cam", "mixed"])
def test_resumed_analysis_equals_the_full_one_after_random_edits(name: str, text: str) -> None:
    rnd = random.Random(20)
    old = full(text)
    assert old.memory is not None and old.memory.light and len(old.memory.checkpoints) > 5
    resumed_count = 0
    for _ in range(30):
        text = random_edit(rnd, text)
        ref = full(text)
        got = resumed(old, text)
        if got is not None:
            resumed_count += 1
            assert_same(got, ref)
            old = got  # chain the resumes: the shifts pile up
        else:
            old = ref
    assert resumed_count >= 25  # nearly every edit of a plain program resumes


def test_a_one_digit_edit_reruns_about_one_checkpoint_interval() -> None:
    text = cam_program(20_000)
    old = full(text)
    lines = text.split("\n")
    line = 10_000
    col = lines[line].find(".") + 1
    lines[line] = lines[line][:col] + ("1" if lines[line][col] != "1" else "2") + lines[line][col + 1:]
    got = resumed(old, "\n".join(lines))
    assert got is not None and got.resumed is not None
    first, last = got.resumed
    assert first <= line < last and last - first <= 2 * EVERY + 2
    assert_same(got, full("\n".join(lines)))


def test_an_edit_that_adds_a_frame_transform_runs_in_full() -> None:
    old = full(MIXED)
    text = MIXED.replace("G01 Z-1. F600.\n", "G01 Z-1. F600.\nG68 X0 Y0 R30.\n", 1)
    assert resumed(old, text) is None


def test_macro_programs_are_not_resumed() -> None:
    old = full("#1=5\nG01 X#1 F100.\nM30\n", "fanuc")
    assert old.memory is None or not old.memory.light
    assert resumed(old, "#1=6\nG01 X#1 F100.\nM30\n") is None


def test_changed_range() -> None:
    assert changed_range("abcdef", "abXdef") == (2, 3)
    assert changed_range("abc", "abc") == (3, 0)
    assert changed_range("aaaa", "aaaaa") == (4, 0)  # prefix and suffix never overlap
    long = "x" * 10_000
    assert changed_range(long + "a" + long, long + "bb" + long) == (10_000, 10_000)


def test_shifts_compose() -> None:
    s = Shifts().spliced(10, 12, 3, 5)  # items 10, 11 replaced by 3 new ones, text after +5
    assert [s.delta_at(k) for k in (9, 10, 12, 13, 100)] == [0, 0, 0, 5, 5]
    t = s.spliced(2, 4, 1, -1)  # earlier splice: the old +5 tail moves down one index, now +4
    assert [t.delta_at(k) for k in (1, 2, 3, 11, 12, 99)] == [0, 0, -1, -1, 4, 4]


@pytest.mark.parametrize("encoding", ["utf-16", "utf-8", "utf-32"])
def test_fast_document_changes_like_pygls(encoding: str) -> None:
    from lsprotocol import types as lsp
    from pygls.workspace import PositionCodec, TextDocument

    from cncc.lsp.documents import FastTextDocument

    rnd = random.Random(7)
    text = "G01 X1. (é 😀)\r\nG02 X2. Y3.\n\nM30\n" * 20
    ref = TextDocument("file:///a.nc", text, position_codec=PositionCodec(encoding))
    fast = FastTextDocument("file:///a.nc", text, position_codec=PositionCodec(encoding))
    def boundaries(line: str) -> list[int]:
        """Valid columns of a line (its ends of characters, in code units; not past its end)."""
        out, units = [0], 0
        for ch in line.rstrip("\r"):
            units += len(ch.encode("utf-16-le")) // 2 if encoding == "utf-16" else \
                len(ch.encode("utf-8")) if encoding == "utf-8" else 1
            out.append(units)
        return out

    for _ in range(300):
        lines = ref.source.split("\n")
        l1 = rnd.randrange(len(lines))
        l2 = min(len(lines) - 1, l1 + rnd.choice([0, 0, 1, 3]))
        c1 = rnd.choice(boundaries(lines[l1]))
        c2 = rnd.choice([c for c in boundaries(lines[l2]) if l2 > l1 or c >= c1])
        change = lsp.TextDocumentContentChangePartial(
            range=lsp.Range(start=lsp.Position(line=l1, character=c1), end=lsp.Position(line=l2, character=c2)),
            text=rnd.choice(["", "X", "7", "\n", "G1 X2.\nY3."]))
        ref.apply_change(change)
        fast.apply_change(change)
        assert fast.source == ref.source


def test_the_dialect_guess_is_kept_only_across_number_edits() -> None:
    from cncc.lsp.server import number_edit

    assert number_edit("G1 X1.5 Y2", "G1 X1.55 Y2") and number_edit("F100", "F1000")
    assert not number_edit("G2 X1", "G21 X1")  # G21 is a mark the guess reads (units + macro B)
    assert not number_edit("#1=5", "#1=55") and not number_edit("G1 X1.5", "G1 X1.5 1")


def test_line_index_after_an_edit_equals_a_fresh_one() -> None:
    from cncc.lsp.positions import LineIndex

    rnd = random.Random(3)
    text = "G01 X1.\r\nG02 X2. Y3.\n\nM30\n" * 50
    index = LineIndex(text)
    for _ in range(400):
        a = rnd.randrange(len(text) + 1)
        b = min(len(text), a + rnd.choice([0, 0, 1, 5, 40]))
        new = text[:a] + rnd.choice(["", "X", "\n", "7\n8", "\r\n", "\n\n"]) + text[b:]
        prefix, suffix = changed_range(text, new)
        index = LineIndex.after_edit(index, new, prefix, suffix)
        assert index._starts == LineIndex(new)._starts
        text = new
