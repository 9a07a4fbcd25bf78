"""Bad input through the command line: mutated real programs never make a traceback.

The seeds are the programs of ``examples/`` and ``tests/corpus/``; a mutation deletes, inserts,
duplicates, swaps or truncates, or puts an odd number in place of one.  Each mutant is compiled
by ``cncc.cli.main`` (in-process, with ``CNCC_DEBUG=1`` so that an internal error raises instead of
becoming exit status 4) in a drawn dialect with ``-fsyntax-only``, ``--emit=canon`` or
``--emit=gcode -t grbl``.  The claims (docs/diagnostics.md, the project brief): exit status 0 or 1,
and every diagnostic about the program names ``file:line:col``.
"""

from __future__ import annotations

import contextlib
import io
import os
import re
import sys
import tempfile
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from cncc.cli import main
from cncc.dialects import available

ROOT = Path(__file__).parents[2]
SEEDS = sorted(p for d in (ROOT / "examples", ROOT / "tests" / "corpus") for p in d.rglob("*")
               if p.is_file() and p.suffix.lower() in (".nc", ".ngc", ".gcode", ".tap") and p.stat().st_size < 20_000)
DIALECTS = sorted(available())
MODES = (["-fsyntax-only"], ["--emit=canon"], ["--emit=gcode", "-t", "grbl"])
ODD_NUMBERS = ("1e400", "-0", "99999999999", ".", "-", "1.2.3", "0x10", "nan", "#", "[", "1E5", "+-1")
NUMBER = re.compile(r"(?<=[A-Za-z])[-+]?\d*\.?\d+")
DIAGNOSTIC = re.compile(r"^(?P<where>.*?): (?:fatal error|error|warning|note): ", re.MULTILINE)


@st.composite
def mutants(draw: st.DrawFn) -> str:
    text = draw(st.sampled_from(SEEDS)).read_text(encoding="utf-8", errors="replace")
    for _ in range(draw(st.integers(1, 4))):
        kind = draw(st.sampled_from(("delete", "insert", "duplicate", "swap", "truncate", "number")))
        n = len(text)
        at = draw(st.integers(0, n))
        if kind == "delete":
            text = text[:at] + text[at + draw(st.integers(1, 40)):]
        elif kind == "insert":
            text = text[:at] + draw(st.text(alphabet="GMXYZIJKRFPQLHDNOST#[]()=;%.-+0123456789 \n", max_size=20)) \
                + text[at:]
        elif kind in ("duplicate", "swap"):
            lines = text.splitlines(keepends=True)
            if len(lines) > 1:
                i, j = draw(st.integers(0, len(lines) - 1)), draw(st.integers(0, len(lines) - 1))
                if kind == "duplicate":
                    lines.insert(j, lines[i])
                else:
                    lines[i], lines[j] = lines[j], lines[i]
                text = "".join(lines)
        elif kind == "truncate":
            text = text[:at]
        else:
            found = list(NUMBER.finditer(text))
            if found:
                m = found[draw(st.integers(0, len(found) - 1))]
                text = text[:m.start()] + draw(st.sampled_from(ODD_NUMBERS)) + text[m.end():]
    return text


def run_cli(argv: list[str]) -> tuple[int, str]:
    """``cncc argv`` in this process: (exit status, stderr)."""
    out, err = io.TextIOWrapper(io.BytesIO(), encoding="utf-8"), io.StringIO()
    old = os.environ.get("CNCC_DEBUG")
    os.environ["CNCC_DEBUG"] = "1"
    stdin, sys.stdin = sys.stdin, io.StringIO("")
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            try:
                status = main(argv)
            except SystemExit as exc:  # argparse
                status = exc.code if isinstance(exc.code, int) else 2
    finally:
        sys.stdin = stdin
        if old is None:
            del os.environ["CNCC_DEBUG"]
        else:
            os.environ["CNCC_DEBUG"] = old
    return status, err.getvalue()


def check(text: str, dialect: str, mode: list[str]) -> None:
    with tempfile.TemporaryDirectory(prefix="cncc-mutant-") as tmp:
        path = Path(tmp) / "mutant.nc"
        path.write_text(text, encoding="utf-8")
        status, err = run_cli(["-x", dialect, "-fdiagnostics-color=never", *mode, str(path)])
    assert status in (0, 1), (status, err, text)
    for m in DIAGNOSTIC.finditer(err):
        where = m.group("where")
        if where.startswith("cncc"):  # about the run, not the program (e.g. "-t grbl has no ...")
            continue
        # the mutant, or a program it calls (an SZGH library cycle, a subprogram): file:line:col either way
        assert re.fullmatch(r".+:\d+:\d+", where), (where, err, text)


@pytest.mark.parametrize("mode", MODES, ids=lambda m: m[0].lstrip("-"))
@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(text=mutants(), dialect=st.sampled_from(DIALECTS))
def test_mutated_programs_get_diagnostics_not_tracebacks(mode: list[str], text: str, dialect: str) -> None:
    check(text, dialect, mode)


def test_the_seeds_are_found() -> None:
    assert len(SEEDS) >= 20 and {"linuxcnc", "fanuc", "grbl"} <= set(DIALECTS)
