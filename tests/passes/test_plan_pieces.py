"""Issue 14: the planner streams -- ``plan_pieces`` yields each run's rows as soon as the run
is planned, reading the commands lazily, so a consumer that handles one piece at a time
keeps the planner's memory to the longest run, not the program."""

from __future__ import annotations

import tracemalloc
from collections.abc import Iterator

import numpy as np
import pytest

from cncc.api import compile_commands
from cncc.ir.commands import Command
from cncc.machines import load_machine
from cncc.passes.plan import plan_commands, plan_pieces
from cncc.passes.planning.emit import assemble

MACHINE = load_machine("generic-mill")


def _program(runs: int) -> list[Command]:
    """``runs`` zig-zags of 40 G1 moves, each ended by a dwell (a stop: one run each)."""
    lines = ["G21 G90 G17 G94", "G0 X10 Y10 Z2", "G1 Z-1 F600"]
    for r in range(runs):
        y = 10.0 + 3.0 * r
        lines += [f"G1 X{10 + 2 * i + 2:.3f} Y{y + (1.5 if i % 2 == 0 else 0.0):.3f} F3000" for i in range(40)]
        lines += ["G4 P0.01", f"G1 X10 Y{y + 3:.3f}"]
    lines += ["M30"]
    cmds, result = compile_commands("\n".join(lines) + "\n", emit="timing", dialect="linuxcnc")
    assert not result.sink.has_errors
    return list(cmds)


@pytest.mark.parametrize("level", [1, 2])
def test_pieces_assemble_to_the_plan(level: int) -> None:
    cmds = _program(6)
    whole = plan_commands(cmds, MACHINE, level)
    pieces = list(plan_pieces(cmds, MACHINE, level))
    assert len(pieces) >= 6  # one per dwell-separated run at least
    joined = assemble(pieces)
    assert joined.phase_count == whole.phase_count
    for name in ("t0_s", "duration_s", "p0_mm", "v0_mm_s", "a0_mm_s2", "j_mm_s3", "cmd_index", "limit"):
        np.testing.assert_array_equal(getattr(joined, name), getattr(whole, name))
    for piece in pieces:  # each piece starts and ends at rest, times local to it
        assert piece.t0[0] == 0.0
        assert np.abs(piece.v0[0]).max() == 0.0


def test_pieces_arrive_before_the_program_is_read() -> None:
    cmds = _program(8)
    read = [0]

    def lazily() -> Iterator[Command]:
        for c in cmds:
            read[0] += 1
            yield c

    first = next(plan_pieces(lazily(), MACHINE, 2))  # type: ignore[arg-type]
    assert first.t0.size > 0
    assert read[0] < len(cmds) / 4  # only the first run (and the command that closed it) was read


def _peak_mb(cmds: list[Command]) -> float:
    tracemalloc.start()
    try:
        for piece in plan_pieces(iter(cmds), MACHINE, 2):  # type: ignore[arg-type]
            del piece  # a streaming consumer: nothing kept
        return tracemalloc.get_traced_memory()[1] / 1e6
    finally:
        tracemalloc.stop()


def test_streamed_planner_memory_is_bounded_by_the_longest_run() -> None:
    small, large = _program(10), _program(40)
    _peak_mb(small)  # warm the lazy imports and caches outside the measurement
    peak_small, peak_large = _peak_mb(small), _peak_mb(large)
    whole_large = plan_commands(large, MACHINE, 2)
    kept_mb = sum(getattr(whole_large, n).nbytes for n in ("p0_mm", "v0_mm_s", "a0_mm_s2", "j_mm_s3")) / 1e6
    assert peak_large < 1.15 * peak_small + 0.02, (peak_small, peak_large)  # flat in the number of runs
    assert peak_large < kept_mb  # below what the whole trajectory's per-axis rows alone take
