"""Translation keeps the motion: for every corpus program and every target dialect,
compile(source) and compile(translate(source, target), dialect=target) make the same
moves in the same order with the same feeds and dwells (1 um, 0.01 % of feed).

The corpus is ``tests/translate/corpus/<dialect>/*.nc`` plus ``examples/*.nc`` (SYNTEC).
Targets are every file in ``cncc/dialects``: a new dialect is tested when it lands.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from cncc.api import compile_commands, compile_text
from cncc.dialects import available
from tests.translate.motion import difference, motion

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "translate"
TABLES = {"tools_file": str(DATA / "tools.toml"), "offsets_file": str(DATA / "offsets.toml")}


def corpus() -> list[tuple[str, Path]]:
    out = [(d.name, p) for d in sorted((DATA / "corpus").iterdir()) if d.is_dir() for p in sorted(d.glob("*.nc"))]
    for p in sorted((ROOT / "examples").glob("*.nc")):  # examples/DIALECT_name.nc; contour.nc is SYNTEC
        prefix = p.stem.split("_")[0]
        out.append((prefix if prefix in available() else "syntec", p))
    return out


PROGRAMS = corpus()
TARGETS = available()


def translate(text: str, source: str, target: str, **opts: object) -> str:
    r = compile_text(text, dialect=source, emit="gcode", target=target, **TABLES, **opts)  # type: ignore[arg-type]
    errors = [(d.code, d.message) for d in r.sink if d.severity.name == "ERROR"]
    assert not errors, errors
    return r.output


def source_motion(text: str, dialect: str) -> list[tuple[object, ...]]:
    cmds, r = compile_commands(text, dialect=dialect, **TABLES)  # type: ignore[arg-type]
    assert r.ok, [(d.code, d.message) for d in r.sink]
    return motion(cmds)


def check(text: str, source: str, target: str, tol_mm: float = 1e-3, **opts: object) -> str:
    out = translate(text, source, target, **opts)
    want = source_motion(text, source)
    got = source_motion(out, target)
    assert want, "the program has no motion to compare"
    why = difference(want, got, tol_mm)
    assert not why, f"{why}\n--- translation to {target}:\n{out}"
    return out


def test_corpus_is_not_empty() -> None:
    assert len(PROGRAMS) >= 10 and {"syntec", "szgh"} <= set(TARGETS)


@pytest.mark.parametrize("target", TARGETS)
@pytest.mark.parametrize(("source", "path"), PROGRAMS, ids=[f"{s}/{p.stem}" for s, p in PROGRAMS])
def test_translation_keeps_motion(source: str, path: Path, target: str) -> None:
    text = path.read_text()
    inch = "G70" in text or "G20" in text
    # 4 decimals in inch resolve 2.54 um: the written value is within half of it
    check(text, source, target, tol_mm=1.3e-3 if inch else 1e-3)


@pytest.mark.parametrize("target", TARGETS)
def test_inch_program_within_one_micron_with_five_decimals(target: str) -> None:
    text = (DATA / "corpus" / "syntec" / "inch.nc").read_text()
    check(text, "syntec", target, decimals_inch=5)


SPINDLE_ENDS = [
    "G21 G90 G17\nS1000 M03\nG00 X10 Y10\nG01 X20 Y20 F100\nM02\n",  # the stop M02 implies
    "G21 G90 G17\nS1000 M03\nG00 X10 Y10\nG01 X20 Y20 F100\nM05\nM30\n",  # stopped, then the end
    "G21 G90 G17\nS1000 M03\nG01 X20 F100\nM05\nG00 Z10\nM05\nS800 M04\nG01 X5\nM02\n",
]


@pytest.mark.parametrize("target", TARGETS)
@pytest.mark.parametrize("text", SPINDLE_ENDS)
def test_translating_a_translation_changes_nothing(text: str, target: str) -> None:
    """A second translation is a fixed point: the spindle stop that M02/M30 implies (which the
    front end spells out, as rs274 does) is not written again after the M05 the first one wrote."""
    once = translate(text, "linuxcnc", target)
    twice = translate(once, target, target)
    assert twice == once
    assert translate(twice, target, target) == once
    stops = [ln for ln in once.splitlines() if ln.split(";")[0].split("(")[0].strip() in ("M05", "M5")]
    assert 1 <= len(stops) <= text.count("M05") + 1
