"""The LinuxCNC executor's plain-move fast path (cncc/frontend/linuxcnc/fastblock.py) changes nothing:
every program gives the same canon trace and diagnostics with the fast path on and off."""

from __future__ import annotations

from pathlib import Path

import pytest

from cncc.api import compile_text
from cncc.frontend.linuxcnc import executor
from tests.oracle.cases import CASES
from tests.oracle.programs import FEATURES, generate

CORPUS = Path(__file__).resolve().parents[1] / "corpus" / "linuxcnc"
EXAMPLES = Path(__file__).resolve().parents[2] / "examples"

_EXTRA = {
    "held_axes_z_never_named": "G21 F100\nG1 X1 Y2\nG0 X3\nG91 G1 X1\nG90 G1 Z2 F50\nM2\n",
    "after_g80": "G21 F100\nG0 Z5\nG81 X1 Y1 Z-1 R1\nG80\nX5\nG1 X2\nM2\n",
    "f0_and_no_feed": "G21\nG1 X1\nF0\nG1 X2\nM2\n",
    "inverse_time": "G21 F100\nG93 G1 X1 F2\nG1 X2\nG94 F10\nG1 X3\nM2\n",
    "rotated": "G21 F100\nG10 L2 P1 R30\nG1 X1\nG0 Y4\nM2\n",
    "comp": "G21 F100\nT1 M6\nG41.1 D2 G1 X1 Y0\nG1 X10\nG1 Y10\nG40 G1 X0\nM2\n",
    "repeated_axis": "G21 F100\nG1 X1 X2\nG0 G1 X3\nM2\n",
    "g53": "G21\nG53 G0 X1\nG0 X2\nM2\n",
    "expressions": "G21 F100\n#1=3\nG1 X[#1*2] Y#1\nG0 X[#1] F[#1+1]\nM2\n",
    "inch": "G20 F10\nG1 X1 Y2\nG91 G1 X1\nG90 G0 Z1\nM2\n",
}


def _programs() -> dict[str, str]:
    progs = {f"case:{k}": (v if isinstance(v, str) else v[0]) for k, v in CASES.items()}
    progs.update({f"extra:{k}": v for k, v in _EXTRA.items()})
    for feature in sorted(FEATURES):
        for i, p in enumerate(generate(feature, 8, seed=7)):
            progs[f"{feature}:{i}"] = p.text
    for folder in (CORPUS, EXAMPLES):
        for path in sorted(folder.glob("*.ngc")):
            progs[f"file:{path.name}"] = path.read_text()
    return progs


def _run(text: str, fast: bool, monkeypatch: pytest.MonkeyPatch) -> tuple[str, list[tuple[str, int, str]]]:
    monkeypatch.setattr(executor, "FAST_MOVES", fast)
    r = compile_text(text, dialect="linuxcnc", emit="canon")
    return r.output, [(d.code, d.span.start, d.message) for d in r.sink]


def test_fast_path_changes_no_trace(monkeypatch: pytest.MonkeyPatch) -> None:
    progs = _programs()
    assert len(progs) > 150
    for name, text in progs.items():
        assert _run(text, True, monkeypatch) == _run(text, False, monkeypatch), name


def test_fast_path_is_taken(monkeypatch: pytest.MonkeyPatch) -> None:
    # The path must be exercised at all: count the blocks it lowers on a plain program.
    from cncc.frontend.linuxcnc import fastblock

    taken = []
    real = fastblock.run_plain

    def spy(*args: object) -> object:
        got = real(*args)  # type: ignore[arg-type]
        taken.append(got is not None)
        return got

    monkeypatch.setattr(executor, "run_plain", spy)
    compile_text("G21 F100\nG1 X1 Y2\nG0 X3\nG1 X[1+1]\nG2 X0 Y0 I1\nM2\n", dialect="linuxcnc", emit="canon")
    assert taken == [False, True, True, True, False, False]
