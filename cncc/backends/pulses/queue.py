"""Compressed step queue: (interval, count, add) commands with a bounded timing error.

As Klipper's ``stepcompress``: per axis, ``queue_step AXIS I C A`` stands for ``C``
steps, step ``k`` (1-based) at ``last + k I + A k (k - 1) / 2`` where ``last`` is the
reproduced time of the axis' previous step (0 at the start).  Every reproduced step
is at most ``max_error_ns`` early and never late (``t - e <= r <= t``); the
intervals stay positive.  ``set_next_step_dir AXIS LEVEL`` precedes the first step
after a change of the (electrical) direction level.  Times are in nanoseconds.

The compressor keeps only a tail of each axis' steps between chunks, so a 10^9-step
program streams through in bounded memory.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterable
from typing import TextIO

import numpy as np
import numpy.typing as npt

from cncc.backends.pulses.chunk import StepChunk
from cncc.backends.pulses.events import step_levels

I64 = npt.NDArray[np.int64]
DEFAULT_MAX_ERROR_NS = 25_000
MAX_WINDOW = 1 << 16
MIN_WINDOW = 32


def _count_for(rel_t: I64, e: int, a: int) -> tuple[int, int]:
    """Longest prefix of steps (times relative to ``last``) that one ``(I, C, a)`` reproduces."""
    k = rel_t.shape[0]
    j = np.arange(1, k + 1, dtype=np.int64)
    q = a * (j * (j - 1) // 2)
    i_min = -((q - (rel_t - e)) // j)  # ceil((t - e - q) / j)
    i_max = (rel_t - q) // j  # floor((t - q) / j)
    lo = np.maximum.accumulate(np.maximum(i_min, 1))
    hi = np.minimum.accumulate(i_max)
    feasible = lo <= hi
    if a < 0:  # the last interval I + a (c - 1) must stay >= 1
        feasible &= lo + a * (j - 1) >= 1
    c = int(np.argmin(feasible)) if not feasible.all() else k
    if c == 0:
        return 0, 0
    return c, int(lo[c - 1])


def _adds(rel_t: I64, c0: int) -> list[int]:
    """Candidate ``add`` values: least-squares fits over growing windows."""
    out: list[int] = []
    n = rel_t.shape[0]
    w = max(2 * c0, 8)
    while w <= n and len(out) < 12:
        j = np.arange(1, w + 1, dtype=np.float64)
        cols = np.stack([j, j * (j - 1) / 2], axis=1)
        sol = np.linalg.lstsq(cols, rel_t[:w].astype(np.float64), rcond=None)[0]
        a = round(float(sol[1]))
        out += [a, a - 1, a + 1]
        w *= 2
    return out


def compress_run(t: I64, last: int, e: int, final: bool) -> tuple[list[tuple[int, int, int]], int, int]:
    """Commands covering a prefix of ``t`` (one direction); returns (commands, new last, steps used).

    When not ``final``, a command whose run reaches the end of ``t`` is left for later
    (more steps may extend it).
    """
    cmds: list[tuple[int, int, int]] = []
    i = 0
    n = t.shape[0]
    while i < n:
        window = MIN_WINDOW
        while True:
            rel = t[i:i + window] - last
            best_c, best_i = _count_for(rel, e, 0)
            best_a = 0
            if best_c < rel.shape[0]:
                for a in _adds(rel, best_c):
                    c, iv = _count_for(rel, e, a)
                    if c > best_c:
                        best_c, best_i, best_a = c, iv, a
            if best_c < rel.shape[0] or i + window >= n or window >= MAX_WINDOW:
                break
            window *= 2
        if not final and i + best_c >= n:
            break
        if best_c == 0:  # cannot happen for increasing times; guard against a stall
            best_c, best_i, best_a = 1, max(int(t[i]) - last, 1), 0
        cmds.append((best_i, best_c, best_a))
        last += best_c * best_i + best_a * (best_c * (best_c - 1) // 2)
        i += best_c
    return cmds, last, i


class QueueWriter:
    """Streams chunks into ``queue_step`` text lines."""

    def __init__(self, out: TextIO, max_error_ns: int = DEFAULT_MAX_ERROR_NS) -> None:
        self.out = out
        self.e = int(max_error_ns)
        self.started = False
        self.names: tuple[str, ...] = ()
        self.buf_t: list[I64] = []
        self.buf_lv: list[npt.NDArray[np.uint8]] = []
        self.last: list[int] = []
        self.level_out: list[int] = []  # level last announced
        self.level_in: list[int] = []  # level in force at the end of the data seen

    def feed(self, chunk: StepChunk, final: bool = False) -> None:
        if not self.started:
            self._start(chunk)
        lines: list[str] = []
        for i, name in enumerate(self.names):
            lv = step_levels(chunk.layout, i, chunk, self.level_in[i])
            a = chunk.axes[i]
            if a.dir_level.size:
                self.level_in[i] = int(a.dir_level[-1])
            t = np.concatenate([self.buf_t[i], a.t_ns])
            lvs = np.concatenate([self.buf_lv[i], lv])
            used = self._axis(i, name, t, lvs, final, lines)
            self.buf_t[i], self.buf_lv[i] = t[used:], lvs[used:]
        self.out.write("".join(lines))

    def _start(self, chunk: StepChunk) -> None:
        layout = chunk.layout
        self.names = layout.axes
        m = len(self.names)
        self.buf_t = [np.zeros(0, np.int64) for _ in range(m)]
        self.buf_lv = [np.zeros(0, np.uint8) for _ in range(m)]
        self.last = [0] * m
        self.level_out = [layout.initial_dir_level(i) for i in range(m)]
        self.level_in = list(self.level_out)
        self.out.write(f"# cncc step queue 1; time unit 1 ns; each step at most {self.e} ns early, never late\n"
                       "# queue_step AXIS I C A: step k=1..C at last + k*I + A*k*(k-1)/2\n"
                       f"axes {' '.join(self.names)}\n")
        self.out.write("".join(f"set_next_step_dir {n} {lv}\n" for n, lv in zip(self.names, self.level_out,
                                                                                 strict=True)))
        self.started = True

    def _axis(self, i: int, name: str, t: I64, lv: npt.NDArray[np.uint8], final: bool, lines: list[str]) -> int:
        """Compress axis ``i``'s buffered steps; returns how many were consumed."""
        if t.size == 0:
            return 0
        cuts = np.flatnonzero(lv[1:] != lv[:-1]) + 1
        bounds = [0, *cuts.tolist(), t.shape[0]]
        for b0, b1 in itertools.pairwise(bounds):
            last_run = b1 == t.shape[0]
            cmds, last, used = compress_run(t[b0:b1], self.last[i], self.e, final or not last_run)
            if cmds and int(lv[b0]) != self.level_out[i]:
                self.level_out[i] = int(lv[b0])
                lines.append(f"set_next_step_dir {name} {self.level_out[i]}\n")
            lines.extend(f"queue_step {name} {iv} {c} {a}\n" for iv, c, a in cmds)
            self.last[i] = last
            if b0 + used < b1:
                return int(b0 + used)
        return int(t.shape[0])


def write_queue(chunks: Iterable[StepChunk], out: TextIO, max_error_ns: int = DEFAULT_MAX_ERROR_NS) -> None:
    w = QueueWriter(out, max_error_ns)
    prev: StepChunk | None = None
    for chunk in chunks:
        if prev is not None:
            w.feed(prev)
        prev = chunk
    if prev is not None:
        w.feed(prev, final=True)


def read_queue(lines: Iterable[str]) -> dict[str, tuple[I64, npt.NDArray[np.uint8]]]:
    """Decode a step queue: per axis, the reproduced step times and direction levels."""
    last: dict[str, int] = {}
    level: dict[str, int] = {}
    times: dict[str, list[I64]] = {}
    levels: dict[str, list[npt.NDArray[np.uint8]]] = {}
    for raw in lines:
        f = raw.split()
        if not f or f[0].startswith("#"):
            continue
        if f[0] == "axes":
            for n in f[1:]:
                last[n], level[n], times[n], levels[n] = 0, 1, [], []
        elif f[0] == "set_next_step_dir":
            level[f[1]] = int(f[2])
        elif f[0] == "queue_step":
            n, iv, c, a = f[1], int(f[2]), int(f[3]), int(f[4])
            k = np.arange(1, c + 1, dtype=np.int64)
            r = last[n] + k * iv + a * (k * (k - 1) // 2)
            times[n].append(r)
            levels[n].append(np.full(c, level[n], np.uint8))
            last[n] = int(r[-1])
    return {n: (np.concatenate(times[n]) if times[n] else np.zeros(0, np.int64),
                np.concatenate(levels[n]) if levels[n] else np.zeros(0, np.uint8)) for n in times}
