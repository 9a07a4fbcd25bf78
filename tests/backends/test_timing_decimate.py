"""Decimation in the HTML timing page: no invented speed, true colours, raster passes kept."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from cncc.backends.timing import sampling
from cncc.backends.timing.decimate import douglas_peucker, speed_columns
from cncc.backends.timing.pagedata import MAX_VERTICES
from tests.backends.timing_pages import Built, arr, big, contour


def test_speed_columns_keep_every_columns_extremes_and_a_limit_that_occurs() -> None:
    rng = np.random.default_rng(7)
    t = np.sort(rng.uniform(0, 10, 5000))
    v = rng.uniform(0, 100, 5000)
    v[1234] = 5000.0  # one spike, one sample wide
    lim = rng.integers(0, 4, 5000)
    line = np.arange(5000)
    edges = np.linspace(0, 10, 301)
    c = speed_columns(t, v, lim, line, edges, 9)
    for k in range(300):  # brute force, column by column
        inside = (t >= edges[k]) & (t < edges[k + 1]) if k < 299 else (t >= edges[k])
        assert c.vmax[k] == v[inside].max() and c.vmin[k] == v[inside].min()
        assert c.limit[k] in set(lim[inside].tolist())
        assert v[c.line[k]] == c.vmax[k] and c.top_limit[k] == lim[c.line[k]]
        assert c.vlimit[k] == v[inside & (lim == c.limit[k])].max()
    assert c.vmax.max() == 5000.0


def _wall_shift(b: Built) -> np.ndarray:
    """Seconds of events before each command, from the report's event list (a loop, not pagedata)."""
    shift = np.zeros(len(b.cmds))
    for i, ns, *_ in b.rep.primary.event_list:
        shift[i + 1:] += ns / 1e9
    return shift


def _check_speed(b: Built, columns: np.ndarray | None, dense: int) -> None:
    """Page column maxima against an upper bound of the trajectory's speed in each column
    (dense samples plus the most a speed can grow between two of them: h·|a|max + h²·|j|max/2)."""
    d = b.data()
    traj = b.rep.primary.run.trajectory
    nc, end = d["columns"], d["end_s"]
    edges = np.linspace(0.0, end, nc + 1)
    vmax = arr(d["speed"]["vmax"], "f4").astype(float)
    lim = arr(d["speed"]["limit"], "i1")
    top_lim = arr(d["speed"]["top"], "i1")
    vlim = arr(d["speed"]["vlimit"], "f4").astype(float)
    shift = _wall_shift(b)
    # trajectory-time intervals of the chosen columns: invert wall = t + shift[cmd(t)] by sampling
    t_all = np.linspace(0.0, traj.duration_total_s, dense)
    h = t_all[1] - t_all[0]
    cmd, _ = sampling.at(traj, t_all)
    wall = t_all + shift[cmd]
    assert (np.diff(wall) >= 0).all()
    _, v, a, j = traj.sample(t_all)
    speed = np.linalg.norm(v[:, :3], axis=1) * 60
    margin = (h * np.linalg.norm(a[:, :3], axis=1).max() + h * h * np.linalg.norm(j[:, :3], axis=1).max() / 2) * 60
    col_a = np.clip(np.searchsorted(edges, wall, side="right") - 1, 0, nc - 1)
    col_b = np.clip(np.searchsorted(edges, wall + h, side="right") - 1, 0, nc - 1)
    ub = np.full(nc, -np.inf)
    np.maximum.at(ub, col_a, speed)
    np.maximum.at(ub, col_b, speed)
    lb = np.full(nc, -np.inf)
    np.maximum.at(lb, col_a, speed)
    ks = np.arange(nc) if columns is None else columns
    covered = np.isfinite(ub)
    top = speed.max()
    width = edges[1] - edges[0]
    bands = d["bands"] + [[traj.duration_total_s + shift[-1], end + width, "after the end"]]
    for k in ks[~covered[ks]]:  # no motion sample: inside an event (or past the trajectory's end)
        centre = (edges[k] + edges[k + 1]) / 2
        assert any(b0 - width <= centre <= b1 + width for b0, b1, _ in bands), k
    for k in ks:
        if vmax[k] < 0:
            continue
        if covered[k]:
            assert vmax[k] <= ub[k] + margin + 1e-6 * top, (k, vmax[k], ub[k])
            assert vmax[k] >= lb[k] - margin - 5e-3 * top, (k, vmax[k], lb[k])
        else:  # inside an event: the trajectory stands still at one instant
            near = ub[np.flatnonzero(covered)[np.abs(np.flatnonzero(covered) - k).argmin()]]
            assert vmax[k] <= near + margin + 1e-6 * top
    assert float(np.nanmax(np.where(vmax < 0, np.nan, vmax))) <= top + margin
    # the colour of a column is a limit some phase in that column has
    knots = sampling.knot_times(traj)
    for k in ks:
        if lim[k] < 0:
            continue
        i0, i1 = np.searchsorted(wall, edges[k]), np.searchsorted(wall, edges[k + 1])  # wall is monotone
        if i1 <= i0:
            continue
        t0, t1 = t_all[i0] - h, t_all[i1 - 1] + h
        ts = np.concatenate(([max(t0, 0.0)], knots[(knots >= t0) & (knots <= t1)]))
        held = set(sampling.at(traj, ts)[1].tolist())
        assert lim[k] in held and top_lim[k] in held, k
        assert vlim[k] <= vmax[k]


def test_contour_speed_columns_never_exceed_the_trajectory() -> None:
    _check_speed(contour(), None, 2_000_000)


@pytest.mark.slow
def test_100k_speed_columns_never_exceed_the_trajectory() -> None:
    b = big()
    nc = b.data()["columns"]
    _check_speed(b, np.random.default_rng(3).choice(nc, 300, replace=False), 4_000_000)


def _zigzag(passes: int, step: float, width: float, per_pass: int) -> np.ndarray:
    pts = []
    for k in range(passes):
        xs = np.linspace(0, width, per_pass) if k % 2 == 0 else np.linspace(width, 0, per_pass)
        pts += [(x, k * step, 0.0) for x in xs]
    return np.array(pts)


def test_douglas_peucker_keeps_raster_passes_parallel_and_the_path_within_tolerance() -> None:
    pts = _zigzag(60, 0.5, 100.0, 40)
    pts[:, 1] += np.random.default_rng(1).uniform(-1e-3, 1e-3, len(pts))
    tol = 0.05
    keep = douglas_peucker(pts, tol, np.zeros(len(pts), dtype=bool))
    kp = pts[keep]
    assert len(kp) <= 4 * 60  # straight passes collapse to their ends
    d = np.diff(kp, axis=0)
    horizontal = np.abs(d[:, 1]) <= 2 * tol
    vertical = np.abs(d[:, 0]) <= 2 * tol
    assert (horizontal | vertical).all()  # no chord across passes
    assert sorted({round(p) for p in kp[horizontal.nonzero()[0], 1] * 2}) == list(range(60))
    # every dropped point is within tol of the kept polyline (brute force)
    ki = np.flatnonzero(keep)
    for a, b in itertools.pairwise(ki):
        seg = pts[b] - pts[a]
        for p in pts[a + 1:b]:
            u = np.clip(np.dot(p - pts[a], seg) / max(np.dot(seg, seg), 1e-300), 0, 1)
            assert np.linalg.norm(p - (pts[a] + u * seg)) <= tol + 1e-12


def test_douglas_peucker_keeps_forced_vertices() -> None:
    pts = np.column_stack((np.linspace(0, 10, 101), np.zeros(101), np.zeros(101)))
    forced = np.zeros(101, dtype=bool)
    forced[[17, 50]] = True
    keep = douglas_peucker(pts, 0.1, forced)
    assert np.flatnonzero(keep).tolist() == [0, 17, 50, 100]


@pytest.mark.slow
def test_100k_page_raster_passes_stay_parallel() -> None:
    b = big()
    path = b.data()["path"]
    assert 0 < path["n"] <= MAX_VERTICES
    lo, hi = np.array(path["lo"]), np.array(path["hi"])
    q = arr(path["q"], "u2").reshape(-1, 3).astype(float)
    pos = lo + q / 65535 * (hi - lo)
    flags = arr(path["flags"], "u1")
    tool = np.array(path["tools"])[arr(path["tool"], "u1")]
    tol = path["tol_mm"] + float((hi - lo).max()) / 65535
    seg = np.flatnonzero((flags[:-1] & 1) & ~(flags[:-1] & 2) & (tool[:-1] == 1))  # drawn T1 feeds
    a, e = pos[seg], pos[seg + 1]
    flat = np.abs(a[:, 2] - e[:, 2]) <= tol
    dx, dy = np.abs(e[flat, 0] - a[flat, 0]), np.abs(e[flat, 1] - a[flat, 1])
    assert ((dx <= tol) | (dy <= tol)).all()  # along X (a pass) or along Y (the step over)
    ys = np.round(a[flat][dx > 1.0, 1] / 0.5).astype(int)
    assert set(ys.tolist()) == set(range(160))  # the generator's 80 mm pocket in 0.5 mm passes: all there
