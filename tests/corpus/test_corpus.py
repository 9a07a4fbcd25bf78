"""The shop corpus (issue 23): real-style programs for every dialect.

tests/corpus/<dialect>/ holds hand-written mains and macro libraries and the CAM-style
programs ``scripts/gen_corpus.py`` generates (thousands of lines each).  Must show:

* every program compiles with no error diagnostic under its dialect (the programs of a
  folder are compiled in one run, so a main's G65 call finds its library there);
* detection picks the folder's dialect for at least 95 % of the programs;
* the generated programs' feed moves end where the generator's geometry says
  (the independent expectation: :func:`gen_corpus.expected_feeds`).
"""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

import pytest

from cncc.diagnostics import Severity
from cncc.driver import Options, compile_files
from cncc.frontend.detect import detect
from tests.helpers import calls

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
DIALECTS = ("syntec", "szgh", "series8", "fanuc", "haas", "linuxcnc", "grbl")
PROGRAM_SUFFIXES = (".nc", ".ngc", ".gcode", ".tap")


def programs(dialect: str) -> list[Path]:
    return sorted(p for p in (HERE / dialect).iterdir() if p.suffix in PROGRAM_SUFFIXES)


def generator() -> ModuleType:
    spec = importlib.util.spec_from_file_location("gen_corpus", ROOT / "scripts" / "gen_corpus.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules["gen_corpus"] = module
    spec.loader.exec_module(module)
    return module


def test_every_dialect_has_programs() -> None:
    for d in DIALECTS:
        assert len(programs(d)) >= 2, d


def test_generated_programs_are_current() -> None:
    assert generator().main(["--check"]) == 0, "run python scripts/gen_corpus.py"


@pytest.mark.parametrize("dialect", DIALECTS)
def test_programs_compile_without_errors(dialect: str) -> None:
    files = [str(p) for p in programs(dialect)]
    r = compile_files(Options(inputs=files, dialect=dialect, emit="none"))
    bad = [(r.sources.get(d.span.source_id).name if r.sources.get(d.span.source_id) else "?", d.code, d.message)
           for d in r.sink if d.severity is Severity.ERROR]
    assert bad == []


def test_detection_picks_the_dialect_for_95_percent() -> None:
    total, wrong = 0, []
    for d in DIALECTS:
        for p in programs(d):
            total += 1
            found = detect(p.name, p.read_text(encoding="utf-8"))
            if found.dialect != d:
                wrong.append((p.name, d, found.dialect, found.explain()))
    assert total >= 20
    assert (total - len(wrong)) / total >= 0.95, wrong


@pytest.mark.parametrize("job", generator().JOBS, ids=lambda j: j.path)
def test_generated_motion_matches_the_geometry(job: object) -> None:
    gen = sys.modules["gen_corpus"]
    path = HERE / job.path  # type: ignore[attr-defined]
    r = compile_files(Options(inputs=[str(path)], dialect=job.dialect, emit="canon"))  # type: ignore[attr-defined]
    assert r.ok
    got = []
    for name, args in calls(r.output.splitlines(), "STRAIGHT_FEED", "ARC_FEED"):
        if name == "ARC_FEED":
            got.append((round(args[0], 3), round(args[1], 3), round(args[5], 3)))
        else:
            got.append((round(args[0], 3), round(args[1], 3), round(args[2], 3)))
    want = [tuple(round(v, 3) for v in p) for p in gen.expected_feeds(job)]
    assert len(got) == len(want)
    assert got == want
