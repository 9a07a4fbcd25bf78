"""Time-ordered events across axes, for the writers that interleave axes (VCD, CSV).

Consumes :class:`StepChunk`; produces batches of events sorted by time.  Events of
one chunk at or after its ``horizon_ns`` are held back and merged with the next
chunk's, so the output is sorted across chunk boundaries as well.

An event batch is a dict of equal-length arrays: ``t_ns`` (int64), ``axis``
(int16), ``kind`` (int8, one of the ``KIND_*`` values below) and ``level`` (uint8:
the step line's new level for edges, the direction line's level otherwise).
At equal times, events sort by kind: direction changes, then falling step edges,
then rising ones.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator

import numpy as np
import numpy.typing as npt

from cncc.backends.pulses.chunk import PulseLayout, StepChunk

KIND_DIR = 0
KIND_FALL = 1
KIND_STEP = 2
KIND_BACKLASH = 3

Events = dict[str, npt.NDArray[np.generic]]
COLUMNS = ("t_ns", "axis", "kind", "level")


def _empty() -> Events:
    return {"t_ns": np.zeros(0, np.int64), "axis": np.zeros(0, np.int16),
            "kind": np.zeros(0, np.int8), "level": np.zeros(0, np.uint8)}


def step_levels(layout: PulseLayout, i: int, chunk: StepChunk, last_level: int) -> npt.NDArray[np.uint8]:
    """Electrical direction level in force at each step of axis ``i``."""
    a = chunk.axes[i]
    if a.dir_t_ns.size == 0:
        return np.full(a.count, last_level, np.uint8)
    change_at = np.searchsorted(a.dir_t_ns, a.t_ns, side="right")
    levels = np.concatenate([[last_level], a.dir_level]).astype(np.uint8)
    return levels[change_at]


def chunk_events(chunk: StepChunk, levels: list[int], with_falls: bool) -> Events:
    """All events of one chunk (unsorted); updates ``levels`` (per-axis DIR level)."""
    parts: list[Events] = []
    layout = chunk.layout
    for i, a in enumerate(chunk.axes):
        if a.count == 0 and a.dir_t_ns.size == 0:
            continue
        lv = step_levels(layout, i, chunk, levels[i])
        kind = np.where(a.backlash, KIND_BACKLASH, KIND_STEP).astype(np.int8)
        parts.append({"t_ns": a.t_ns, "axis": np.full(a.count, i, np.int16), "kind": kind, "level": lv})
        if with_falls:
            w = layout.specs[i].pulse_width_ns
            parts.append({"t_ns": a.t_ns + w, "axis": np.full(a.count, i, np.int16),
                          "kind": np.full(a.count, KIND_FALL, np.int8), "level": lv})
        parts.append({"t_ns": a.dir_t_ns, "axis": np.full(a.dir_t_ns.size, i, np.int16),
                      "kind": np.full(a.dir_t_ns.size, KIND_DIR, np.int8), "level": a.dir_level})
        if a.dir_level.size:
            levels[i] = int(a.dir_level[-1])
    return concat(parts)


def concat(parts: list[Events]) -> Events:
    if not parts:
        return _empty()
    return {c: np.concatenate([p[c] for p in parts]) for c in COLUMNS}


def take(ev: Events, idx: npt.NDArray[np.intp] | npt.NDArray[np.bool_]) -> Events:
    return {c: ev[c][idx] for c in COLUMNS}


def ordered_events(chunks: Iterable[StepChunk], *, with_falls: bool) -> Iterator[tuple[PulseLayout, Events]]:
    """Batches of events in time order, one per chunk (the last one flushes everything)."""
    held = _empty()
    levels: list[int] | None = None
    layout: PulseLayout | None = None
    for chunk in chunks:
        if levels is None:
            layout = chunk.layout
            levels = [layout.initial_dir_level(i) for i in range(len(layout.specs))]
        ev = concat([held, chunk_events(chunk, levels, with_falls)])
        order = np.lexsort((ev["kind"], ev["t_ns"]))
        ev = take(ev, order)
        cut = int(np.searchsorted(ev["t_ns"], chunk.horizon_ns, side="left"))
        held = take(ev, slice(cut, None))  # type: ignore[arg-type]
        yield chunk.layout, take(ev, slice(0, cut))  # type: ignore[arg-type]
    if layout is not None and held["t_ns"].size:
        yield layout, held
