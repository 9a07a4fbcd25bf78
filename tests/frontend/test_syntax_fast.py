"""-fsyntax-only's vectorised checker (cncc/frontend/syntax_fast.py, plainscan.py) must report exactly
what the front end and the path passes report: the same diagnostics (code, severity, span, message,
in the same order) and the same exit status, on the corpus, the examples and generated programs
with every kind of error, in every dialect with the fast path; and it must really be the one that
runs on a plain CAM file."""

from __future__ import annotations

import io
import math
import random
import re
import sys
from collections.abc import Iterator
from contextlib import contextmanager, redirect_stderr
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from cncc import cli, driver, fast_syntax
from cncc import diagnostics as dg
from cncc.dialects import load_dialect
from cncc.frontend import fastpath, plainscan, syntax_fast
from cncc.frontend.syntax_fast import applies

ROOT = Path(__file__).resolve().parents[2]
FAST_DIALECTS = ("syntec", "fanuc", "haas", "szgh")

Diag = tuple[str, str, int, int, int, str]


@contextmanager
def slow_path(monkeypatch: pytest.MonkeyPatch) -> Iterator[None]:
    """The whole front end, as before the vectorised checker."""
    with monkeypatch.context() as m:
        m.setattr(driver, "fast_syntax_only", lambda *a, **k: False)
        yield


@pytest.fixture(autouse=True)
def small_programs_too(monkeypatch: pytest.MonkeyPatch) -> None:
    """The checker skips programs under 64 KB (numpy's import costs more); these tests are smaller."""
    monkeypatch.setattr(fast_syntax, "FAST_SYNTAX_MIN_CHARS", 0)


def check(path: Path, dialect: str | None, monkeypatch: pytest.MonkeyPatch,
          **options: Any) -> tuple[list[Diag], bool, list[Any]]:
    """Diagnostics and error status of -fsyntax-only on ``path``, and the walks that ran."""
    walks: list[Any] = []
    real = syntax_fast.lower_for_check

    def spy(*a: Any, **k: Any) -> Any:
        return real(*a, **{**k, "walks": walks})

    with monkeypatch.context() as m:
        m.setattr(syntax_fast, "lower_for_check", spy)
        o = driver.Options(inputs=[str(path)], dialect=dialect, syntax_only=True, **options)
        r = driver.compile_files(o)
    return [(d.code, d.severity.name, d.span.source_id, d.span.start, d.span.end, d.message) for d in r.sink], \
        r.sink.has_errors, walks


def reference(path: Path, dialect: str | None, monkeypatch: pytest.MonkeyPatch,
              **options: Any) -> tuple[list[Diag], bool]:
    with slow_path(monkeypatch):
        diags, errors, walks = check(path, dialect, monkeypatch, **options)
    assert walks == []
    return diags, errors


def assert_same(path: Path, dialect: str | None, monkeypatch: pytest.MonkeyPatch, **options: Any) -> list[Any]:
    fast, fast_err, walks = check(path, dialect, monkeypatch, **options)
    slow, slow_err = reference(path, dialect, monkeypatch, **options)
    assert fast == slow, path
    assert fast_err == slow_err, path
    return walks


# ---- generated programs --------------------------------------------------------------------------
INJECTED = [
    "G1 X1.2.3 Y1", "G1 X. Y2", "G1 X- Y1", "G1 X1234567890123 Y1", "G01 X5 F0", "G1 X1 F0.0", "G7 X1",
    "G2 X5 Y5", "G3 X1 Y1 I0 J0", "G2 X10 Y0 I3 J0", "G1 X1 Y2 (comment)", "(full comment)", "/G1 X3 Y3",
    "/2 G1 X3 Y3", "N10 G1 X3 Y4", "G1 X1 Y1;", "G1 X2 Y2 ;", "x1 y1", "G1 X1 Y2 A3", "G91", "G90",
    "G91 G1 X1 Y1", "G18", "G17", "G20", "G21", "G81 X1 Y1 Z-1 R1 F100", "G80", "X2 Y2", "G94", "G95",
    "G1 X1 F100", "M30", "G54", "G55", "G1 X3 Y3 Z3 I1 J1", "G2 X1 Y1 I1 J1 Z1", "G2 X4 Y0 I2", "G3 X0 Y4 J2",
    "G1 Y3 X2", "G1 X" + "9" * 12, "G1 X" + "9" * 13, "G1 X+1.5 Y-.5", "G1 X1.5 Y2.5 Z-.25 F1000", "G00 Z5",
    "G0 X0 Y0", "G1 X1 Y1 F", "F200", "G1", "N20", "G1 X1 Y1 Fabc", "G1 X1\tY1", "G1 X1 Y1 \u00e9",
    "G1  X1  Y1  ", " G1 X1", "G1 X1 Y1 ; comment", "G2 X2 Y2 R1", "G68 X0 Y0 R30", "G69", "G41 D1", "G40",
    "G52 X10 Y10", "G52 X0 Y0", "G92 X0 Y0", "G28 X0 Y0", "G4 X1", "G2 X10 Y0.001 I5 J0", "G2 X10.02 Y0 I5 J0",
    "G2 X10.0283 Y0 I5 J0", "G2 X10.0284 Y0 I5 J0", "G1 X1e5", "G01X1Y1", "G00001 X1", "G04 P1", "T1 M06",
    "G43 H1", "G49", "M5", "G1 Z-1 F50", "G1 X1 Y" + "1" * 100_001, "G1 X1 Y1 %", "G1 X99999999.999",
    "G1 X1 Y1 Z1 F1 N5", "G4.5 X1", "G01.1 X1", "G1 X-0 Y-0.0", "G10 L2 P1 X0", "G50", "G51 X0 Y0 P2",
]
MACRO = ["#1=5", "G1 X#1", "M98 P100", "G65 P9000", "WHILE [#1 LT 3] DO1", "IF [#1 GT 2] GOTO 10", "G1 X[1+2]"]


def program(seed: int, n: int = 400, crlf: bool = False, macro_at: int = -1, share: float = 0.07) -> str:
    """A raster with arcs (right and slightly or badly wrong radii), injected error and mode lines."""
    rnd = random.Random(seed)
    lines = ["%", "O1000 (generated)", "G90 G17 G21 G94", "G00 X0.0 Y0.0 Z5.0", "S1000 M03"]
    x = y = 0.0
    feed_set = False
    for k in range(n):
        r = rnd.random()
        if r < share:
            lines.append(rnd.choice(INJECTED))
        elif r < share + 0.06:
            rad = rnd.choice([1.0, 2.5, 0.5, 1e-3])
            off = rnd.choice([0.0, 0.0, 0.0, 0.02, 0.03, 0.0283, 0.02828, 0.05, 1e-10])
            code = rnd.choice(["G2", "G3", "G02", "G03"])
            lines.append(f"{code} X{x + 2 * rad + off:.5f} Y{y:.4f} I{rad:.4f} J0.0" +
                         (" F800" if rnd.random() < 0.2 else ""))
            x += 2 * rad + off
        else:
            x = round(x + rnd.uniform(-2, 2), 3)
            y = round(y + rnd.uniform(-2, 2), 3)
            parts = []
            if rnd.random() < 0.1:
                parts.append(f"N{k}")
            if rnd.random() < 0.3:
                parts.append(rnd.choice(["G1", "G01", "G0", "G00"]))
            parts.append(f"X{x:.3f}" if rnd.random() < 0.9 else f"X{int(x * 1000)}")  # LIU integers too
            if rnd.random() < 0.8:
                parts.append(f"Y{y:.3f}")
            if rnd.random() < 0.3:
                parts.append(f"Z{rnd.uniform(-1, 1):.3f}")
            if rnd.random() < 0.05 or (not feed_set and rnd.random() < 0.5):
                parts.append(f"F{rnd.choice([100, 500, 1500])}")
                feed_set = True
            lines.append(rnd.choice([" ", " ", " ", ""]).join(parts))
        if rnd.random() < 0.01:
            lines.append("")
        if k == macro_at:
            lines.append(rnd.choice(MACRO))
    lines += ["G00 Z5", "M05", "M30", "%"]
    nl = "\r\n" if crlf else "\n"
    return nl.join(lines) + nl


@pytest.mark.parametrize("dialect", FAST_DIALECTS)
def test_generated_programs_with_errors_agree(dialect: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    assert applies(load_dialect(dialect))
    monkeypatch.setattr(syntax_fast, "CHUNK_BYTES", 2048)  # many chunk boundaries
    vectorised = 0
    for seed in range(10):
        path = tmp_path / f"p{seed}.nc"
        path.write_bytes(program(seed + 100 * FAST_DIALECTS.index(dialect), crlf=seed % 4 == 3).encode())
        walks = assert_same(path, dialect, monkeypatch)
        vectorised += sum(w.vectorised for w in walks)
    assert vectorised > 1000  # the runs between the errors were decided with arrays


def test_modes_every_few_blocks_agree(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(syntax_fast, "CHUNK_BYTES", 4096)
    for seed in range(4):
        path = tmp_path / f"m{seed}.nc"
        path.write_text(program(seed, n=1500, share=0.3))
        assert_same(path, "syntec", monkeypatch)
        assert_same(path, "syntec", monkeypatch, policy=dg.WarningPolicy(max_errors=3))


def test_a_macro_line_after_many_chunks_starts_again(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(syntax_fast, "CHUNK_BYTES", 1024)
    for seed, at in ((1, 10), (2, 300), (3, 590)):
        path = tmp_path / f"macro{seed}.nc"
        path.write_text(program(seed, n=600, macro_at=at))
        assert_same(path, "fanuc", monkeypatch)


def test_non_ascii_and_latin1_offsets_agree(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(syntax_fast, "CHUNK_BYTES", 1024)
    base = program(5, n=300)
    lines = base.splitlines()
    for k in range(10, len(lines), 37):
        lines[k] = f"(op\u00e9ration \u00fc\u20ac {k})"  # a comment with multi-byte characters
    lines.insert(len(lines) // 2, "G1 X1 Y1 F0")
    text = "\n".join(lines) + "\n"
    (tmp_path / "utf8.nc").write_text(text, encoding="utf-8")
    assert_same(tmp_path / "utf8.nc", "syntec", monkeypatch)
    latin = text.replace("\u20ac", "e")
    (tmp_path / "latin1.nc").write_bytes(latin.encode("latin-1"))
    assert_same(tmp_path / "latin1.nc", "syntec", monkeypatch)


def test_options_that_change_the_checks_agree(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    path = tmp_path / "o.nc"
    path.write_text(program(9, n=800))
    assert_same(path, "syntec", monkeypatch, repair_arcs=True)
    assert_same(path, "syntec", monkeypatch, block_delete=False)
    assert_same(path, "syntec", monkeypatch, strict=True)
    assert_same(path, "syntec", monkeypatch, werror=True)
    assert_same(path, "syntec", monkeypatch, policy=dg.WarningPolicy(max_errors=1))
    assert_same(path, "syntec", monkeypatch, dialect_options={"arc_radius_tolerance_mm": 0.05})
    assert_same(path, None, monkeypatch)  # the dialect guessed from the file


def test_offsets_transforms_and_inch_agree(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A work offset, a rotation and inch units: the rest of the file is the fast path's own."""
    body = program(11, n=500).splitlines()
    for k, head in ((3, "G55"), (200, "G68 X0 Y0 R15"), (320, "G69"), (330, "G20"), (420, "G21")):
        body.insert(k, head)
    path = tmp_path / "t.nc"
    path.write_text("\n".join(body) + "\n")
    offsets = tmp_path / "offsets.toml"
    offsets.write_text('units = "mm"\n[work.G55]\nX = 100.5\nY = -20.25\nZ = 3.0\n')
    assert_same(path, "syntec", monkeypatch, offsets_file=str(offsets))
    assert_same(path, "syntec", monkeypatch)


def test_incremental_runs_agree(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    rnd = random.Random(4)
    lines = ["G91 G17 G71 G94", "G01 F500"]
    for k in range(3000):
        if k % 97 == 0:
            lines.append(f"G02 X{2 * rnd.choice([1.0, 1.01, 1.02]):.4f} Y0 I1.0 J0")
        elif k % 97 == 1:
            lines.append(f"G01 X{rnd.uniform(-1, 1):.4f}")
        else:
            lines.append(f"X{rnd.uniform(-1, 1):.4f} Y{rnd.uniform(-1, 1):.4f}")
    path = tmp_path / "inc.nc"
    path.write_text("\n".join(lines) + "\nG90\nM30\n")
    walks = assert_same(path, "syntec", monkeypatch)
    assert sum(w.vectorised for w in walks) > 2500


@pytest.mark.parametrize("group", ["corpus", "examples"])
def test_corpus_and_examples_agree(group: str, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(syntax_fast, "CHUNK_BYTES", 2048)
    files = sorted((ROOT / "tests" / "corpus").rglob("*.*")) if group == "corpus" else \
        sorted((ROOT / "examples").glob("*.*"))
    checked = 0
    for path in files:
        if path.suffix in (".py", ".toml", ".md") or not path.is_file():
            continue
        dialect = path.parent.name if group == "corpus" else None
        for d in ([dialect] if dialect in FAST_DIALECTS else [None, "fanuc"]):
            assert_same(path, d, monkeypatch)
            checked += 1
    assert checked >= 8


# ---- the plain CAM file is checked with arrays -----------------------------------------------------
def cam_file(n_lines: int, arcs: bool) -> str:
    """The bench's raster (bench/pipeline.py): G1 steps, with ``arcs`` G2/G3 turnarounds."""
    sys.path.insert(0, str(ROOT / "bench"))
    import pipeline  # type: ignore[import-not-found]

    text: str = pipeline.program("arcs" if arcs else "plain", n_lines)
    return text


@pytest.mark.parametrize("arcs", [False, True])
def test_the_plain_cam_file_is_vectorised(arcs: bool, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    path = tmp_path / "cam.nc"
    path.write_text(cam_file(20_000, arcs))

    def refuse(*a: Any, **k: Any) -> Any:
        raise AssertionError("lower_straight ran: the checker fell back to the fast path")

    with monkeypatch.context() as m:
        m.setattr(syntax_fast, "lower_straight", refuse)
        m.setattr(fastpath, "lower_straight", refuse)
        diags, errors, walks = check(path, "syntec", monkeypatch)
    assert diags == [] and not errors
    assert len(walks) == 1
    assert walks[0].vectorised >= 20_000 - 20  # every motion block but the header's
    assert walks[0].slow <= 1  # the first move, which names the axes that held their place


def test_bad_arcs_in_a_plain_file_are_reported_by_the_arc_check(tmp_path: Path,
                                                                 monkeypatch: pytest.MonkeyPatch) -> None:
    lines = cam_file(5000, True).splitlines()
    bad = [k for k, line in enumerate(lines) if line.startswith("G03")][3:6]
    for k in bad:
        lines[k] = re.sub(r"J([\d.]+)", lambda m: f"J{float(m.group(1)) + 0.2:.3f}", lines[k])
    path = tmp_path / "bad.nc"
    path.write_text("\n".join(lines) + "\n")
    walks = assert_same(path, "syntec", monkeypatch)
    diags, _, _ = check(path, "syntec", monkeypatch)
    assert [d[0] for d in diags] == [dg.ARC_RADIUS] * 3
    assert [d[3] for d in diags] == [sum(len(line) + 1 for line in lines[:k]) for k in bad]
    assert walks[0].vectorised > 4900


def test_exit_status_and_stderr_agree(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    good = tmp_path / "good.nc"
    good.write_text(cam_file(3000, True))
    bad = tmp_path / "bad.nc"
    bad.write_text(program(3, n=600))

    def run(args: list[str]) -> tuple[int, str]:
        err = io.StringIO()
        with redirect_stderr(err):
            code = cli.main(args)
        return code, err.getvalue()

    for path in (good, bad):
        args = ["-x", "syntec", "-fsyntax-only", str(path)]
        fast = run(args)
        with slow_path(monkeypatch):
            slow = run(args)
        assert fast == slow
    assert run(["-x", "syntec", "-fsyntax-only", str(good)])[0] == 0
    assert run(["-x", "syntec", "-fsyntax-only", str(bad)])[0] == 1


# ---- the scanner against CAM_LINE and float() ---------------------------------------------------------
def oracle(line: str) -> tuple[bool, list[tuple[str, float]]]:
    """Plain per fastpath.CAM_LINE with a word, numbers float() reads, and ';' only at the very end."""
    m = fastpath.CAM_LINES.fullmatch(line)
    if m is None or line == "":
        return False, []
    if ";" in line and not re.search(r";\r?$", line):
        return False, []
    words: list[tuple[str, str]] = re.findall(r"([NGXYZIJF])([-+]?[\d.]+)", line)
    if not words:  # ';' or '\r' alone: the fast path finds no word and sends it to the general path
        return False, []
    try:
        out = [(a, float(v)) for a, v in words]
    except ValueError:
        return False, []
    return True, out


def test_the_scanner_reads_lines_as_cam_line_and_float_do() -> None:
    rnd = random.Random(3)
    alphabet = ["G", "G0", "G1", "G01", "G2", "G03", "G4", "N7", "X", "Y", "Z", "I", "J", "F", "1", "0", ".", "-",
                "+", " ", ";", "\r", "A", "(", "x", "12.5", "-0.25", ".5", "5.", "000", "3", "99999999999"]
    lines = []
    for _ in range(20_000):
        if rnd.random() < 0.5:  # mostly well-formed words, in and out of order
            words = [f"{a}{rnd.choice(['1', '-2.5', '.125', '0', '12345678.901', '+3', '1.2.3', '.', '-'])}"
                     for a in rnd.sample("NGXYZIJF", rnd.randint(1, 5))]
            if rnd.random() < 0.7:
                words.sort(key=lambda w: "NGXYZIJF".index(w[0]))
            line = rnd.choice([" ", "", "  "]).join(words) + rnd.choice(["", "", ";", " ", "\r", ";\r"])
        else:
            line = "".join(rnd.choice(alphabet) for _ in range(rnd.randint(0, 8)))
        lines.append(line.replace("\n", ""))
    data = ("\n".join(lines)).encode()
    ch = plainscan.scan_chunk(data, 0, len(data))
    assert len(ch.kind) == len(lines)
    for k, line in enumerate(lines):
        plain, read = oracle(line)
        expect = plainscan.EMPTY if line == "" else (plainscan.PLAIN if plain else plainscan.GENERAL)
        assert ch.kind[k] == expect, repr(line)
        if plain:
            for a, value in read:
                w = int(ch.tok["NGXYZIJF".index(a), k])
                assert w >= 0, (line, a)
                if a not in "NG":
                    got = float(plainscan.values(ch, np.array([w]))[0])
                    assert got == value and math.copysign(1, got) == math.copysign(1, value), (line, a)


def test_values_are_exactly_float() -> None:
    rnd = random.Random(8)
    nums = []
    for _ in range(5000):
        digits = "".join(rnd.choice("0123456789") for _ in range(rnd.randint(1, 11)))
        cut = rnd.randint(0, len(digits))
        nums.append(rnd.choice(["", "-", "+"]) + digits[:cut] + "." + digits[cut:] if rnd.random() < 0.8
                    else rnd.choice(["", "-"]) + digits)
    line = " ".join(f"X{n}" for n in nums[:1]) + "\n" + "\n".join(f"X{n}" for n in nums[1:]) + "\n"
    data = line.encode()
    ch = plainscan.scan_chunk(data, 0, len(data))
    words = ch.tok[plainscan.X]
    assert (words >= 0).all()
    got = plainscan.values(ch, words.astype(np.int64))
    want = np.array([float(n) for n in nums])
    assert np.array_equal(got, want)
    assert np.array_equal(np.signbit(got), np.signbit(want))


@pytest.mark.parametrize("dialect", ["syntec", "fanuc", "haas", "szgh", "grbl", "linuxcnc", "series8"])
def test_the_tape_mark_reads_as_the_grammar_reads_it(dialect: str) -> None:
    """A '%' line skips the grammar (its first use costs ~50 ms at start-up); the block is the grammar's."""
    from cncc.diagnostics import DiagnosticSink
    from cncc.frontend.parser import ParseOptions, Parser
    from cncc.source import SourceMap

    parser = Parser(load_dialect(dialect), DiagnosticSink(), ParseOptions())
    for line in ("%", "%\r"):
        src = SourceMap().add("t.nc", "G1\n" + line + "\n")
        assert list(parser.blocks_of_line(src, 3, 3 + len(line), 2)) == list(parser._lark_blocks(src, line, 3, 2))


def test_small_programs_skip_the_checker(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(fast_syntax, "FAST_SYNTAX_MIN_CHARS", 1 << 16)
    small = tmp_path / "small.nc"
    small.write_text(cam_file(1000, False))
    assert check(small, "syntec", monkeypatch)[2] == []
    big = tmp_path / "big.nc"
    big.write_text(cam_file(5000, False))
    assert len(big.read_text()) >= 1 << 16
    assert len(check(big, "syntec", monkeypatch)[2]) == 1


def test_a_line_longer_than_a_scan_chunk_leaves_it_to_the_front_end(tmp_path: Path,
                                                                     monkeypatch: pytest.MonkeyPatch) -> None:
    lines = program(6, n=300).splitlines()
    lines.insert(100, "G1 X1 (" + "y" * (plainscan.MAX_CHUNK + 10) + ")")
    path = tmp_path / "long.nc"
    path.write_text("\n".join(lines) + "\n")
    walks = assert_same(path, "syntec", monkeypatch)
    assert len(walks) == 1 and walks[0].vectorised == 0
    diags, _, _ = check(path, "syntec", monkeypatch)
    assert dg.LINE_TOO_LONG in [d[0] for d in diags]
