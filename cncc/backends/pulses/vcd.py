"""VCD (IEEE 1364 value change dump) writer for GTKWave and sigrok/PulseView.

One module ``cncc``; per axis two 1-bit wires, ``<axis>_step`` and ``<axis>_dir``.
Time scale 1 ns.  A step is a rising edge of ``_step`` at the step time and a
falling edge ``pulse_width_ns`` later; ``_dir`` carries the electrical direction
level (after ``direction_invert``).  Backlash pulses look like any other step (the
CSV and NPZ writers mark them).
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import TextIO

import numpy as np

from cncc.backends.pulses.chunk import PulseLayout, StepChunk
from cncc.backends.pulses.events import KIND_DIR, KIND_FALL, ordered_events
from cncc.backends.pulses.text import stamped

RENDER_ROWS = 1 << 16
"""Events rendered to text at a time: the byte matrix, its mask and the text of a slice, not of a
whole chunk (a chunk of 2^18 steps has about 5 x 10^5 events; their text and temporaries took ~80 MB)."""


def _ident(k: int) -> str:
    """VCD identifier number ``k``: printable ASCII 33..126, base 94."""
    s = ""
    k += 1
    while k:
        k, r = divmod(k - 1, 94)
        s += chr(33 + r)
    return s


def header(layout: PulseLayout, *, comment: str = "cncc step/dir pulses") -> str:
    lines = [f"$comment {comment} $end", "$timescale 1ns $end", "$scope module cncc $end"]
    for i, name in enumerate(layout.axes):
        lines.append(f"$var wire 1 {_ident(2 * i)} {name}_step $end")
        lines.append(f"$var wire 1 {_ident(2 * i + 1)} {name}_dir $end")
    lines += ["$upscope $end", "$enddefinitions $end", "#0", "$dumpvars"]
    for i in range(len(layout.axes)):
        lines.append(f"0{_ident(2 * i)}")
        lines.append(f"{layout.initial_dir_level(i)}{_ident(2 * i + 1)}")
    lines.append("$end")
    return "\n".join(lines) + "\n"


def write_vcd(chunks: Iterable[StepChunk], out: TextIO) -> None:
    """Write the pulses of ``chunks`` to ``out`` as VCD text (rendered by numpy, :mod:`.text`)."""
    started = False
    last_t = 0
    tokens: list[bytes] = []
    for layout, ev in ordered_events(chunks, with_falls=True):
        if not started:
            out.write(header(layout))
            m = len(layout.axes)
            names = [_ident(s) for s in range(2 * m)]
            width = max(len(n) for n in names)
            # one length for all tokens (more than 47 axes: two-character identifiers), so pad
            # the shorter ones with a trailing space, which VCD readers skip as a separator
            tokens = [f"{v}{n}".ljust(width + 1).encode("ascii") + b"\n" for n in names for v in (0, 1)]
            started = True
        if ev["t_ns"].size == 0:
            continue
        t = ev["t_ns"].astype(np.int64)
        axis = ev["axis"].astype(np.int64)
        kind = ev["kind"]
        sig = 2 * axis + (kind == KIND_DIR)
        value = np.where(kind == KIND_DIR, ev["level"], (kind != KIND_FALL).astype(np.uint8))
        new_t = np.empty(t.shape, dtype=bool)
        new_t[0] = int(t[0]) != last_t
        new_t[1:] = t[1:] != t[:-1]
        code = 2 * sig + value
        for lo in range(0, t.shape[0], RENDER_ROWS):  # the text of a slice at a time: bounded memory
            hi = lo + RENDER_ROWS
            out.write(stamped(t[lo:hi], new_t[lo:hi], tokens, code[lo:hi]).decode("ascii"))
        last_t = int(t[-1])
