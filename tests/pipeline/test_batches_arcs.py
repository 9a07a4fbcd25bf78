"""Arcs in the vectorised G-code segments (cncc/backends/gcode/batch.py) write what the emitter writes.

The segment writes runs of rapids, lines and one-block arcs as byte matrices; every other arc
(helices, multi-turn, targets that split arcs) goes through :meth:`GcodeEmitter._arc`.  Generated
programs mix lines and arcs of every sweep (full circles too), in the three planes, with helical
rises, feed changes, unit and plane switches every few blocks; the batch path and the command path
must print the same G-code and the same diagnostics for every target.
"""

from __future__ import annotations

import math
import random
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from cncc.backends.gcode import emit as gcode_emit

sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_batches import agree, program

TARGETS = [["-t", "grbl"], ["-t", "fanuc"], ["-t", "linuxcnc"], ["-t", "series8"], ["-t", "haas"], []]
PLANES = {"G17": (0, 1, 2, "XYZ", "IJ"), "G18": (2, 0, 1, "ZXY", "KI"), "G19": (1, 2, 0, "YZX", "JK")}


def generated(seed: int) -> str:
    """Lines and arcs from the tracked position: centres exact to the written digits' rounding."""
    rnd = random.Random(seed)
    lines = ["G21 G17 G90 G94 F1000", "G0 X0 Y0 Z0"]
    pos = [0.0, 0.0, 0.0]
    plane = "G17"
    for _ in range(rnd.randint(20, 80)):
        r = rnd.random()
        if r < 0.08:
            plane = rnd.choice(list(PLANES))
            lines.append(plane)
            continue
        if r < 0.11:
            lines.append(rnd.choice(["G20", "G21", "F700", "F1234.5"]))
            continue
        i, j, n, letters, centre_letters = PLANES[plane]
        feed = rnd.choice(["", "", "", " F800", " F2500."])
        if r < 0.5:
            end = [round(v + rnd.uniform(-3, 3), 4) if rnd.random() < 0.7 else v for v in pos]
            code = rnd.choice(["G1", "G1", "G0"])
            words = " ".join(f"{a}{end[k]:.4f}" for k, a in enumerate("XYZ") if end[k] != pos[k] or rnd.random() < 0.2)
            lines.append(f"{code} {words or f'X{pos[0]:.4f}'}{feed if code == 'G1' else ''}")
            pos = end
            continue
        radius = rnd.choice([0.5, 1.0, 2.5, 0.0104])
        a0 = rnd.uniform(-math.pi, math.pi)
        ci, cj = pos[i] - radius * math.cos(a0), pos[j] - radius * math.sin(a0)
        sweep = rnd.choice([0.0, math.pi / 2, math.pi, 2.0, 5.0, 6.28, 0.001])  # 0: a full circle
        ccw = rnd.random() < 0.5
        a1 = a0 + (sweep if ccw else -sweep)
        end = list(pos)
        end[i] = round(ci + radius * math.cos(a1), 4)
        end[j] = round(cj + radius * math.sin(a1), 4)
        if rnd.random() < 0.25:
            end[n] = round(pos[n] + rnd.choice([-0.5, 0.2, 0.00004]), 4)
        code = "G3" if ccw else "G2"
        axes = " ".join(f"{letters[k]}{end[(i, j, n)[k]]:.4f}" for k in range(3)
                        if k < 2 or end[n] != pos[n])
        offs = f"{centre_letters[0]}{ci - pos[i]:.4f} {centre_letters[1]}{cj - pos[j]:.4f}"
        turns = " P2" if rnd.random() < 0.05 else ""
        lines.append(f"{code} {axes} {offs}{turns}{feed}")
        pos = end
    lines.append("M30")
    return "\n".join(lines) + "\n"


@pytest.mark.usefixtures("small_chunks")
@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.integers(0, 2**32), st.sampled_from(TARGETS), st.sampled_from(["syntec", "fanuc", "linuxcnc"]))
def test_generated_arcs(tmp_path_factory: pytest.TempPathFactory, monkeypatch: pytest.MonkeyPatch,
                        seed: int, target: list[str], dialect: str) -> None:
    path = tmp_path_factory.mktemp("arcs") / "arcs.nc"
    path.write_text(generated(seed))
    agree(path, ["-x", dialect, *target, "--emit=gcode"], monkeypatch)


@pytest.mark.parametrize("kind", ["arcs", "transformed"])
@pytest.mark.parametrize("target", TARGETS)
def test_bench_arcs_every_target(kind: str, target: list[str], tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    path = tmp_path / f"{kind}.nc"
    path.write_text(program(kind, 2000))
    tools = tmp_path / "tools.toml"
    tools.write_text('units = "mm"\n[tools.1]\nlength_mm = 2.5\nradius_mm = 0.2\n')
    agree(path, ["-x", "syntec", "--tools", str(tools), *target, "--emit=gcode"], monkeypatch)


def test_segments_take_the_arcs(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """On the 10 %-arcs raster, grbl's arcs are written by the segments, not one by one by the emitter
    (the differential tests above would pass with every arc through the emitter, as before)."""
    from test_batches import run

    path = tmp_path / "arcs.nc"
    path.write_text(program("arcs", 2000))
    arcs = sum(1 for line in path.read_text().splitlines() if line.startswith(("G02", "G03")))
    calls = []
    original = gcode_emit.GcodeEmitter._arc

    def counted(self: gcode_emit.GcodeEmitter, a: object) -> object:
        calls.append(a)
        return original(self, a)  # type: ignore[arg-type]

    monkeypatch.setattr(gcode_emit.GcodeEmitter, "_arc", counted)
    out, _ = run(path, ["-x", "syntec", "-t", "grbl", "--emit=gcode"], monkeypatch, True)
    written = sum(1 for line in out.splitlines() if line.startswith(("G02 ", "G03 ", "G2 ", "G3 ")))
    assert arcs > 90 and written == arcs
    assert len(calls) <= arcs // 10, len(calls)  # the first row of a batch goes through the emitter
