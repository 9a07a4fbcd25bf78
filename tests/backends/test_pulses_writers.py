"""Writers: VCD read back by an independent reader (vcdvcd), CSV, NPZ, and the compressed queue."""

from __future__ import annotations

import io
import itertools
from pathlib import Path

import numpy as np
import vcdvcd
from hypothesis import given, settings
from hypothesis import strategies as st

from cncc.backends.pulses import generate_pulses, read_queue, write_pulses
from cncc.backends.pulses.chunk import AxisSteps, PulseLayout, StepChunk
from cncc.backends.pulses.queue import DEFAULT_MAX_ERROR_NS
from cncc.backends.pulses.spec import axis_spec
from cncc.ir.machine import Axis, BacklashMode, MachineModel, StepOutput
from tests.backends.pulse_trajectories import NAN, build

STEP = StepOutput(steps_per_mm=400.0, pulse_width_ns=2500, dir_setup_ns=3000, direction_invert=False)
MACHINE = MachineModel("w", (
    Axis("X", step=STEP),
    Axis("Y", step=StepOutput(steps_per_mm=250.0, direction_invert=True, backlash_mm=0.02,
                              backlash_mode=BacklashMode.B)),
))


def traj2() -> object:
    rows = [
        (0.03, [0.0, 0.0], [0.0, 0.0], [20000.0, -15000.0]),
        (0.03, [NAN, NAN], [600.0, -450.0], [-40000.0, 30000.0]),
        (0.05, [NAN, NAN], [-600.0, 450.0], [0.0, 0.0]),
        (0.03, [NAN, NAN], [-600.0, 450.0], [20000.0, -15000.0]),
    ]
    return build(rows, [0.0, 3.0], ("X", "Y"))


def chunks_of(chunk_steps: int = 50) -> list[StepChunk]:
    return list(generate_pulses(traj2(), MACHINE, chunk_steps=chunk_steps))  # type: ignore[arg-type]


def expected(chunks: list[StepChunk], i: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    t = np.concatenate([c.axes[i].t_ns for c in chunks])
    dt = np.concatenate([c.axes[i].dir_t_ns for c in chunks])
    lv = np.concatenate([c.axes[i].dir_level for c in chunks])
    return t, dt, lv


def test_vcd_read_back_by_vcdvcd(tmp_path: Path) -> None:
    chunks = chunks_of()
    path = tmp_path / "p.vcd"
    stats = write_pulses(iter(chunks), "vcd", path)
    assert stats.chunks == len(chunks) > 3
    vcd = vcdvcd.VCDVCD(str(path))
    layout = chunks[0].layout
    for i, name in enumerate(layout.axes):
        t, dir_t, dir_lv = expected(chunks, i)
        tv = vcd[f"cncc.{name}_step"].tv
        rises = [tt for tt, v in tv if v == "1"]
        falls = [tt for tt, v in tv if v == "0" and tt > 0]
        assert rises == t.tolist()
        assert falls == (t + layout.specs[i].pulse_width_ns).tolist()
        dv = vcd[f"cncc.{name}_dir"].tv
        assert dv[0] == (0, str(layout.initial_dir_level(i)))
        assert [tt for tt, _ in dv[1:]] == dir_t.tolist()
        assert [int(v) for _, v in dv[1:]] == dir_lv.tolist()


def test_csv_rows_in_time_order() -> None:
    chunks = chunks_of()
    buf = io.StringIO()
    write_pulses(iter(chunks), "csv", buf)
    lines = buf.getvalue().splitlines()
    assert lines[0] == "t_ns,axis,event,dir_level"
    rows = [ln.split(",") for ln in lines[1:]]
    times = [int(r[0]) for r in rows]
    assert times == sorted(times)
    for i, name in enumerate(chunks[0].layout.axes):
        t, dir_t, _ = expected(chunks, i)
        assert [int(r[0]) for r in rows if r[1] == name and r[2] in ("step", "backlash")] == t.tolist()
        assert [int(r[0]) for r in rows if r[1] == name and r[2] == "dir"] == dir_t.tolist()
    assert any(r[2] == "backlash" for r in rows)


def test_npz_round_trip(tmp_path: Path) -> None:
    chunks = chunks_of()
    path = tmp_path / "p.npz"
    write_pulses(iter(chunks), "npz", path)
    with np.load(path) as z:
        assert z["axes"].tolist() == ["X", "Y"]
        for i, name in enumerate(("X", "Y")):
            t, dir_t, lv = expected(chunks, i)
            assert np.array_equal(z[f"{name}_t_ns"], t)
            assert np.array_equal(z[f"{name}_dir_t_ns"], dir_t)
            assert np.array_equal(z[f"{name}_dir_level"], lv)
            assert z[f"{name}_dir"].dtype == np.int8


def test_queue_round_trip_of_generated_pulses() -> None:
    chunks = chunks_of(chunk_steps=40)
    buf = io.StringIO()
    write_pulses(iter(chunks), "queue", buf)
    got = read_queue(buf.getvalue().splitlines())
    for i, name in enumerate(chunks[0].layout.axes):
        t, dir_t, lv = expected(chunks, i)
        r, levels = got[name]
        assert r.size == t.size
        assert np.all(r <= t) and np.all(r >= t - DEFAULT_MAX_ERROR_NS) and np.all(np.diff(r) > 0)
        level_at = np.concatenate([[chunks[0].layout.initial_dir_level(i)], lv])[
            np.searchsorted(dir_t, t, side="right")]
        assert np.array_equal(levels, level_at)
    assert buf.getvalue().count("queue_step") < sum(c.step_count for c in chunks) / 4


def _chunks_from_times(times: list[np.ndarray], dirs: list[np.ndarray]) -> list[StepChunk]:
    layout = PulseLayout((axis_spec(Axis("X"))[0],), "exact")
    out = []
    last_dir = 1
    for k, (t, d) in enumerate(zip(times, dirs, strict=True)):
        prev = np.concatenate([[last_dir], d[:-1]])
        idx = np.flatnonzero(d != prev)
        last_dir = int(d[-1]) if d.size else last_dir
        ax = AxisSteps(t, d.astype(np.int8), np.zeros(t.size, np.int32), np.zeros(t.size, bool),
                       t[idx], (d[idx] > 0).astype(np.uint8))
        end = int(t[-1]) + 1 if t.size else 0
        out.append(StepChunk(layout, k, 0, end, end - 10, (ax,)))
    return out


@settings(max_examples=80, deadline=None)
@given(
    st.lists(st.integers(1, 200_000), min_size=1, max_size=400),
    st.lists(st.integers(0, 399), max_size=6),
    st.integers(1, 5),
    st.sampled_from([1, 1_000, 25_000, 100_000]),
)
def test_queue_reproduces_every_step_within_its_bound(gaps: list[int], flips: list[int], pieces: int,
                                                      e: int) -> None:
    t = np.cumsum(np.array(gaps, dtype=np.int64)) + 10
    d = np.ones(t.size, np.int64)
    for f in flips:
        d[f % t.size:] *= -1
    cuts = np.linspace(0, t.size, pieces + 1).astype(int)
    chunks = _chunks_from_times([t[a:b] for a, b in itertools.pairwise(cuts)],
                                [d[a:b] for a, b in itertools.pairwise(cuts)])
    buf = io.StringIO()
    write_pulses(iter(chunks), "queue", buf, max_error_ns=e)
    r, levels = read_queue(buf.getvalue().splitlines())["X"]
    assert r.size == t.size
    assert np.all(r <= t) and np.all(r >= t - e)
    assert np.all(np.diff(r) > 0)
    assert np.array_equal(levels, (d > 0).astype(np.uint8))


def test_queue_finds_one_command_for_a_constant_acceleration_run() -> None:
    # Klipper's bisection over 'add' must find the quadratic that fits the whole run
    k = np.arange(1, 301, dtype=np.int64)
    t = 5000 + k * 40_000 - 90 * (k * (k - 1) // 2)  # intervals shrink from 40 us by 90 ns a step
    chunks = _chunks_from_times([t], [np.ones(t.size, np.int64)])
    buf = io.StringIO()
    write_pulses(iter(chunks), "queue", buf, max_error_ns=1000)
    lines = [ln for ln in buf.getvalue().splitlines() if ln.startswith("queue_step")]
    assert len(lines) <= 2  # the first steps (after the 5 us offset) may stand apart
    assert lines[-1].split()[3:] == ["298", "-90"] or lines[-1].split()[3:] == ["300", "-90"]
    r, _ = read_queue(buf.getvalue().splitlines())["X"]
    assert np.all(r <= t) and np.all(r >= t - 1000)
