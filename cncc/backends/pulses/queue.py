"""Compressed step queue: (interval, count, add) commands with a bounded timing error.

As Klipper's ``stepcompress``: per axis, ``queue_step AXIS I C A`` stands for ``C``
steps, step ``k`` (1-based) at ``last + k I + A k (k - 1) / 2`` where ``last`` is the
reproduced time of the axis' previous step (0 at the start).  Every reproduced step
is at most ``min(max_error_ns, half the gap to the previous step)`` early and never
late (``t - e <= r <= t``); the intervals stay positive.  Each command is found as
Klipper's ``compress_bisect_add`` does: the longest run with ``add = 0``, then a
bisection over ``add`` steered by the first step that no longer fits.
``set_next_step_dir AXIS LEVEL`` precedes the first step after a change of the
(electrical) direction level.  Times are in nanoseconds.

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
MAX_WINDOW = 0xFFFF
MIN_WINDOW = 32


QUADRATIC_DEV = 11  # Klipper: the largest deviation between two quadratic sequences, in units of e / count^2
ADD_MIN, ADD_MAX = -0x8000, 0x7FFF  # 'add' is a signed 16-bit field, as in Klipper
LONG_ENOUGH = 0x200  # a sequence this long is not improved by another 'add'


def _cdiv(n: int, d: int) -> int:
    return -((-n) // d)


_K = np.arange(1, 2 * MAX_WINDOW + 3, dtype=np.int64)  # windows double up to below 2 MAX_WINDOW
_TRI = _K * (_K - 1) // 2


def _longest(minp: I64, maxp: I64, add: int, outer: tuple[int, int]) -> tuple[int, int, int, int]:
    """Longest prefix one ``(interval, count, add)`` reproduces, starting from the interval range ``outer``.

    Returns ``(count, interval, lo, hi)`` where ``lo, hi`` is the interval range after the
    first point that fails (``count == len`` when none does).
    """
    n = minp.shape[0]
    k = _K[:n]
    if add:
        q = _TRI[:n] * add
        low = np.subtract(q, minp)
        high = np.subtract(maxp, q)
    else:
        low = np.negative(minp)
        high = maxp.copy()
    np.floor_divide(low, k, out=low)
    np.negative(low, out=low)  # ceil((minp - q) / k)
    if add < 0:  # the last interval, interval + add (count - 1), stays >= 1
        np.maximum(low, (1 + add) - _K[:n] * add, out=low)
    low[0] = max(int(low[0]), outer[0])  # the running maximum then starts from the outer range
    lo = np.maximum.accumulate(low)
    np.floor_divide(high, k, out=high)
    high[0] = min(int(high[0]), outer[1])
    hi = np.minimum.accumulate(high)
    bad = lo > hi
    c = int(bad.argmax())
    if c == 0 and not bad[0]:
        return n, int(hi[-1]), 0, 0
    return c, int(hi[c - 1]) if c else 0, int(lo[c]), int(hi[c])


def bisect_add(minp: I64, maxp: I64, e: int) -> tuple[int, int, int]:
    """One ``(interval, count, add)`` covering a prefix of the points: Klipper's ``compress_bisect_add``.

    Tries ``add = 0`` first, then bisects the range of ``add`` values that could still
    extend the sequence, using which side of its window the first failing point falls on.
    """
    outer_min, outer_max = max(int(minp[0]), 1), int(maxp[0])
    add, min_add, max_add = 0, ADD_MIN, ADD_MAX
    best = (0, 1, 1, -(1 << 62))  # interval, count, add, reach
    zero = (0, 0)
    n = minp.shape[0]
    while True:
        count, interval, next_lo, next_hi = _longest(minp, maxp, add, (outer_min, outer_max))
        if count == n:
            return interval, count, add
        reach = add * (count * (count - 1) // 2) + interval * count
        if reach > best[3] or (reach == best[3] and interval > best[0]):
            best = (interval, count, add, reach)
            if add == 0:
                zero = (interval, count)
            if count > LONG_ENOUGH:
                break
        nc = count + 1
        nf = nc * (nc - 1) // 2
        point_min, point_max = int(minp[count]), int(maxp[count])
        if add * nf + interval * nc < point_min:
            min_add, outer_max = add + 1, next_hi
        else:
            max_add, outer_min = add - 1, next_lo
        if count > 1:
            err = e * QUADRATIC_DEV // (count * count)
            min_add, max_add = max(min_add, add - err), min(max_add, add + err)
        min_add = max(min_add, _cdiv(point_min - outer_max * nc, nf))
        max_add = min(max_add, (point_max - outer_min * nc) // nf)
        if min_add > max_add or count == 0:
            break
        add = max_add - (max_add - min_add) // 4
    if zero[1] + zero[1] // 16 >= best[1]:
        return zero[0], zero[1], 0
    return best[0], best[1], best[2]


def compress_run(t: I64, last: int, e: int, final: bool) -> tuple[list[tuple[int, int, int]], int, int]:
    """Commands covering a prefix of ``t`` (one direction); returns (commands, new last, steps used).

    When not ``final``, a command whose run reaches the end of ``t`` is left for later
    (more steps may extend it).  The points are examined in growing windows (up to
    :data:`MAX_WINDOW`, Klipper's limit), so a short command does not cost a long scan.
    """
    cmds: list[tuple[int, int, int]] = []
    i = 0
    n = t.shape[0]
    window = MIN_WINDOW
    # the lower bounds of _bounds once for the whole run: t - min(gap / 2, e) with the gap to the
    # previous step; only a window's first gap (to ``last``) differs, and is patched per window
    early = np.empty_like(t)
    if n > 1:
        np.subtract(t[1:], t[:-1], out=early[1:])
        early[1:] //= 2
        np.minimum(early[1:], e, out=early[1:])
    t_min = t - early
    while i < n:
        while True:
            maxp = t[i:i + window] - last
            minp = t_min[i:i + window] - last
            first = int(maxp[0])
            minp[0] = first - min(first // 2, e)
            iv, c, add = bisect_add(minp, maxp, e)
            if c < minp.shape[0] or i + window >= n or window >= MAX_WINDOW:
                break
            window *= 2
        if not final and i + c >= n:
            break
        if c == 0:  # cannot happen for increasing times; guard against a stall
            iv, c, add = max(int(t[i]) - last, 1), 1, 0
        cmds.append((iv, c, add))
        last += c * iv + add * (c * (c - 1) // 2)
        i += c
        window = max(MIN_WINDOW, min(MAX_WINDOW, 2 * c))
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
