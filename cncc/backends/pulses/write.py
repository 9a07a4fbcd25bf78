"""Pulse writers: CSV, NPZ, and the dispatch :func:`write_pulses` (VCD and queue live beside).

* ``csv``: ``t_ns,axis,event,dir_level`` rows in time order; ``event`` is ``step``,
  ``backlash`` or ``dir``; ``dir_level`` is the direction line's electrical level at
  the event (for ``dir`` rows, its new level).
* ``npz``: per axis ``<A>_t_ns`` (int64), ``<A>_dir`` (int8, motor direction),
  ``<A>_backlash`` (bool), ``<A>_phase`` (int32), ``<A>_dir_t_ns``, ``<A>_dir_level``;
  plus ``axes``.  Streamed through temporary files, so memory stays bounded; the
  archive is written when the stream ends.
"""

from __future__ import annotations

import io
import os
import shutil
import tempfile
import zipfile
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import IO, TextIO

import numpy as np

from cncc.backends.pulses import text
from cncc.backends.pulses.chunk import StepChunk
from cncc.backends.pulses.events import KIND_BACKLASH, KIND_DIR, ordered_events
from cncc.backends.pulses.queue import DEFAULT_MAX_ERROR_NS, write_queue
from cncc.backends.pulses.vcd import RENDER_ROWS, write_vcd

FORMATS = ("vcd", "csv", "npz", "queue")
_NPZ_FIELDS = (("t_ns", np.int64), ("dir", np.int8), ("backlash", np.bool_), ("phase", np.int32),
               ("dir_t_ns", np.int64), ("dir_level", np.uint8))


@dataclass(slots=True)
class WriteStats:
    """What was written: steps per axis, chunks, the end time, the reversal and event pauses in it."""

    steps: dict[str, int] = field(default_factory=dict)
    chunks: int = 0
    end_ns: int = 0
    pause_ns: int = 0
    event_ns: int = 0


def _counting(chunks: Iterable[StepChunk], stats: WriteStats) -> Iterable[StepChunk]:
    for c in chunks:
        for name, a in zip(c.layout.axes, c.axes, strict=True):
            stats.steps[name] = stats.steps.get(name, 0) + a.count
        stats.chunks += 1
        stats.end_ns = c.t_end_ns
        stats.pause_ns = c.pause_ns
        stats.event_ns = c.event_ns
        yield c


def write_csv(chunks: Iterable[StepChunk], out: TextIO) -> None:
    out.write("t_ns,axis,event,dir_level\n")
    for layout, ev in ordered_events(chunks, with_falls=False):
        axes = [f",{n},".encode("ascii") for n in layout.axes]
        kinds = [b"step,", b"dir,", b"backlash,"]  # KIND_FALL is not in a CSV (with_falls=False)
        kind = np.where(ev["kind"] == KIND_DIR, 1, np.where(ev["kind"] == KIND_BACKLASH, 2, 0))
        t_ns, axis = ev["t_ns"].astype(np.int64), ev["axis"].astype(np.int64)
        for lo in range(0, t_ns.shape[0], RENDER_ROWS):  # rendered by numpy, a slice at a time
            sl = slice(lo, lo + RENDER_ROWS)
            n = t_ns[sl].shape[0]
            out.write(text.render([text.signed(t_ns[sl]), text.choice(axes, axis[sl]),
                                   text.choice(kinds, kind[sl]), text.decimal(ev["level"][sl].astype(np.int64)),
                                   text.literal(b"\n", n)]).decode("ascii"))


def write_npz(chunks: Iterable[StepChunk], out: IO[bytes]) -> None:
    with tempfile.TemporaryDirectory(prefix="cncc-pulses-") as tmp:
        files: dict[str, IO[bytes]] = {}
        counts: dict[str, int] = {}
        names: tuple[str, ...] = ()
        for chunk in chunks:
            names = chunk.layout.axes
            for name, a in zip(names, chunk.axes, strict=True):
                cols: tuple[np.ndarray, ...] = (
                    a.t_ns, a.direction, a.backlash, a.phase, a.dir_t_ns, a.dir_level)
                for (fname, dtype), arr in zip(_NPZ_FIELDS, cols, strict=True):
                    key = f"{name}_{fname}"
                    if key not in files:
                        files[key] = open(os.path.join(tmp, key), "wb")  # noqa: SIM115 - closed below
                        counts[key] = 0
                    files[key].write(np.ascontiguousarray(arr, dtype=dtype).tobytes())
                    counts[key] += int(arr.shape[0])
        for f in files.values():
            f.close()
        with zipfile.ZipFile(out, "w", compression=zipfile.ZIP_STORED, allowZip64=True) as zf:
            with zf.open("axes.npy", "w") as member:
                np.lib.format.write_array(member, np.array(names, dtype=str))
            for name in names:
                for fname, dtype in _NPZ_FIELDS:
                    key = f"{name}_{fname}"
                    hdr = {"descr": np.lib.format.dtype_to_descr(np.dtype(dtype)), "fortran_order": False,
                           "shape": (counts.get(key, 0),)}
                    with zf.open(f"{key}.npy", "w", force_zip64=True) as member:
                        np.lib.format.write_array_header_1_0(member, hdr)
                        if key in files:
                            with open(os.path.join(tmp, key), "rb") as src:
                                shutil.copyfileobj(src, member, 1 << 20)


def write_pulses(chunks: Iterable[StepChunk], fmt: str, out: str | Path | IO[bytes] | TextIO, *,
                 max_error_ns: int = DEFAULT_MAX_ERROR_NS) -> WriteStats:
    """Write a chunk stream in ``fmt`` (one of :data:`FORMATS`) to a path or an open stream.

    Text formats accept a text or binary stream; ``npz`` needs a binary one (or a path).
    """
    if fmt not in FORMATS:
        raise ValueError(f"pulse format must be one of {FORMATS}, not {fmt!r}")
    stats = WriteStats()
    counted = _counting(chunks, stats)
    if isinstance(out, (str, Path)):
        if fmt == "npz":
            with open(out, "wb") as fb:
                write_npz(counted, fb)
        else:
            with open(out, "w", encoding="ascii", newline="\n") as ft:
                _write_text(counted, fmt, ft, max_error_ns)
        return stats
    if fmt == "npz":
        if isinstance(out, io.TextIOBase):
            write_npz(counted, out.buffer)
        else:
            write_npz(counted, out)  # type: ignore[arg-type]
        return stats
    if isinstance(out, io.TextIOBase) or hasattr(out, "encoding"):
        _write_text(counted, fmt, out, max_error_ns)  # type: ignore[arg-type]
    else:
        wrapper = io.TextIOWrapper(out, encoding="ascii", newline="\n")
        try:
            _write_text(counted, fmt, wrapper, max_error_ns)
        finally:
            wrapper.flush()
            wrapper.detach()
    return stats


def _write_text(chunks: Iterable[StepChunk], fmt: str, out: TextIO, max_error_ns: int) -> None:
    if fmt == "vcd":
        write_vcd(chunks, out)
    elif fmt == "csv":
        write_csv(chunks, out)
    else:
        write_queue(chunks, out, max_error_ns)
