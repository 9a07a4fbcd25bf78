"""Incremental first phase: after an edit, re-run the program only where it changed.

A full analysis of a straight-line program (the front end's fast path, no frame
transforms: what CAM output is) keeps a :class:`Checkpoint` of the interpreter's
state every :data:`EVERY` lines (:class:`cncc.frontend.fastpath.Checkpoints`; the
state is frozen records -- modal state, frame, position -- plus a few small values,
so a checkpoint is a shallow copy).  After an edit, :func:`resume`

1. finds the changed characters (common prefix and suffix of the two texts);
2. restores the interpreter from the last checkpoint at or before the first changed
   line and runs the new text from there, through the same light passes;
3. stops at the first line past the change where the state equals the old run's
   checkpoint at the corresponding line (the program from there on is the same text
   run from the same state, so it gives the same commands and diagnostics, shifted);
4. splices: the old results before the restart line, the re-run region, the old
   results after the meeting point with their offsets and lines shifted.

A one-character edit in a CAM file thus re-runs a few lines: the next block that
writes every axis brings the state back.  Commands after the meeting point are not
copied: their shift is kept as segments (:class:`Shifts`) and applied when a code
action asks for them.  Anything the resume cannot handle (a frame transform in the
region, a program that is not straight-line, a target check) returns None and the
server runs the full analysis.  ``tests/lsp/test_incremental.py`` compares resumed
and full analyses after random edits.
"""

from __future__ import annotations

import bisect
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

from cncc.diagnostics import Diagnostic, DiagnosticSink
from cncc.ir import Command
from cncc.source import SourceMap, Span

if TYPE_CHECKING:
    from cncc.dialects import Dialect
    from cncc.frontend.interp import Interpreter
    from cncc.lsp.analysis import Analysis

EVERY = 128  # lines between two checkpoints of a full run
MAX_REGION_LINES = 20_000  # a resume that re-runs more than this gives up (the full run is as fast)


@dataclass(frozen=True, slots=True)
class Checkpoint:
    offset: int  # where the line starts
    state: dict[str, Any]  # the interpreter's state before the line runs
    last: tuple[float, ...] | None  # where the previous motion ended (the relink's memory)


def state_of(it: Interpreter) -> dict[str, Any]:
    """The interpreter's run state (every field but its fixed parts), copied."""
    return it.run_state()


def restore(it: Interpreter, state: dict[str, Any]) -> None:
    it.restore_run_state(state)


class Shifts:
    """Offset shifts of a command list: from index ``k`` on (until the next segment) every
    span is ``delta`` characters later than the command object says."""

    def __init__(self, segments: list[tuple[int, int]] | None = None) -> None:
        self.segments = segments or []  # (first index, delta), sorted by index

    def delta_at(self, k: int) -> int:
        i = bisect.bisect_right(self.segments, (k, float("inf"))) - 1
        return self.segments[i][1] if i >= 0 else 0

    def __bool__(self) -> bool:
        return any(d for _, d in self.segments)

    def spliced(self, i: int, j: int, region: int, delta: int) -> Shifts:
        """The shifts after ``items[i:j]`` is replaced by ``region`` new items and the text after
        it moved by ``delta``."""
        out = [(k, d) for k, d in self.segments if k < i]
        out.append((i, 0))
        moved = i + region - j
        out.append((i + region, self.delta_at(j) + delta))
        out += [(k + moved, d + delta) for k, d in self.segments if k > j]
        return Shifts(out)


def start_of(commands: list[Command], shifts: Shifts, k: int) -> int:
    return commands[k].span.start + shifts.delta_at(k)


def first_at(commands: list[Command], shifts: Shifts, offset: int) -> int:
    """Index of the first command that starts at or after ``offset``."""
    lo, hi = 0, len(commands)
    while lo < hi:
        mid = (lo + hi) // 2
        if start_of(commands, shifts, mid) < offset:
            lo = mid + 1
        else:
            hi = mid
    return lo


def shifted(c: Command, delta: int) -> Command:
    if not delta:
        return c
    s = c.span
    return replace(c, span=Span(s.source_id, s.start + delta, s.end + delta))


def materialize(commands: list[Command], shifts: Shifts, lo: int = 0, hi: int | None = None) -> list[Command]:
    """``commands[lo:hi]`` with their spans where the text has them now."""
    hi = len(commands) if hi is None else hi
    return [shifted(commands[k], shifts.delta_at(k)) for k in range(lo, hi)]


# ---- the full run keeps checkpoints --------------------------------------------------------
def eligible(text: str, dialect: Dialect) -> bool:
    """Whether ``lower`` takes the straight-line fast path for this program (so checkpoints and
    resumes follow the very path the compiler takes)."""
    from cncc.frontend.fastpath import is_straight_line
    from cncc.frontend.macro.remap import remaps_cycles
    from cncc.frontend.plugins import front_end

    if not front_end(dialect).fast_path:
        return False
    return is_straight_line(text, dialect) and not remaps_cycles(dialect)


@dataclass(slots=True)
class Memory:
    """What a full or resumed run keeps for the next edit."""

    checkpoints: dict[int, Checkpoint] = field(default_factory=dict)  # line -> checkpoint
    last: tuple[float, ...] | None = None  # end of the last motion seen (offsets applied)
    light: bool = True  # no frame needed the frame passes


def keep_checkpoints(src: Any, dialect: Dialect, sink: DiagnosticSink, iopts: Any,
                     memory: Memory) -> Iterator[Command]:
    """The front end of a full run (the compiler's fast path), keeping checkpoints in ``memory``."""
    from cncc.frontend.fastpath import Checkpoints, lower_straight

    def on_line(line: int, offset: int, it: Interpreter) -> None:
        memory.checkpoints[line] = Checkpoint(offset, state_of(it), memory.last)

    return lower_straight(src, dialect, sink, iopts, Checkpoints(on_line, every=EVERY))


# ---- resume ----------------------------------------------------------------------------------
class _Met(Exception):
    """The resumed run has met the old one (raised from the checkpoint callback)."""

    def __init__(self, line: int, offset: int) -> None:
        super().__init__(line, offset)
        self.line = line
        self.offset = offset


class _GiveUp(Exception):
    """The resume cannot handle this edit: the caller runs the full analysis."""


def changed_range(old: str, new: str) -> tuple[int, int]:
    """(common prefix length, common suffix length) of two texts, not overlapping."""
    n = min(len(old), len(new))
    lo, step = 0, 4096
    while lo < n:  # slices compare in C: find the first differing chunk, then the character
        hi = min(n, lo + step)
        if old[lo:hi] == new[lo:hi]:
            lo = hi
            step *= 2
            continue
        if hi - lo <= 64:
            while lo < hi and old[lo] == new[lo]:
                lo += 1
            break
        step = max(64, (hi - lo) // 2)
    prefix = min(lo, n)
    room = n - prefix
    s, step = 0, 4096
    while s < room:
        t = min(room, s + step)
        if old[len(old) - t:len(old) - s] == new[len(new) - t:len(new) - s]:
            s = t
            step *= 2
            continue
        if t - s <= 64:
            while s < t and old[len(old) - s - 1] == new[len(new) - s - 1]:
                s += 1
            break
        step = max(64, (t - s) // 2)
    return prefix, min(s, room)


def resume(old: Analysis, a: Analysis, check: Callable[[], None]) -> bool:
    """Fill the new analysis ``a`` from ``old`` by re-running only the changed region; False
    (``a`` left for the full run) when the edit needs the full run."""
    from cncc.lsp.analysis import MAX_COMMANDS

    memory, req = old.memory, a.request
    if (memory is None or not memory.light or old.stopped or old.dialect is None or old.machine is None
            or old.request.dialect != req.dialect or old.request.settings != req.settings
            or req.settings.target or old.request.path != req.path or len(old.commands) >= MAX_COMMANDS):
        return False
    t0 = time.perf_counter()
    try:
        _resume(old, a, check)
    except _GiveUp:
        a.dialect = a.machine = None
        return False
    a.elapsed_s = time.perf_counter() - t0
    return True


def _resume(old: Analysis, a: Analysis, check: Callable[[], None]) -> None:
    from cncc.frontend.fastpath import Checkpoints, lower_straight
    from cncc.frontend.interp import Interpreter
    from cncc.lsp.pipeline import compile_options, interp_options, light_passes, transforms

    memory = old.memory
    assert memory is not None and old.dialect is not None and old.machine is not None
    old_text, text = old.text, a.text
    prefix, suffix = changed_range(old_text, text)
    # the old text took the fast path; the new one does iff its changed lines do (the marks that
    # send a program down the general path -- '#', keywords, call codes -- never span lines)
    lo_line = text.rfind("\n", 0, prefix) + 1
    hi_line = text.find("\n", len(text) - suffix)
    if not eligible(text[lo_line:hi_line if hi_line >= 0 else len(text)], old.dialect):
        raise _GiveUp
    d_chars = len(text) - len(old_text)
    d_lines = text.count("\n", prefix, len(text) - suffix) - old_text.count("\n", prefix, len(old_text) - suffix)
    first_line = a.index.line_of(prefix)
    lines = sorted(memory.checkpoints)
    at = bisect.bisect_right(lines, first_line) - 1
    if at < 0:
        raise _GiveUp
    start_line = lines[at]
    start = memory.checkpoints[start_line]
    end_new = len(text) - suffix  # the changed region ends here in the new text
    last_line = a.index.line_of(end_new)

    a.dialect, a.machine = old.dialect, old.machine
    sink = DiagnosticSink(max_count=5000)
    sources = SourceMap()
    src = sources.add(a.request.path or a.request.uri, text)
    opts = compile_options(a.request, old.dialect)
    iopts = interp_options(opts, old.machine, DiagnosticSink())
    it = Interpreter(old.dialect, sink, 0, iopts)
    restore(it, start.state)
    new_mem = Memory({ln: cp for ln, cp in memory.checkpoints.items() if ln <= start_line})
    new_mem.last = start.last
    relink_mem = Memory(last=start.last)

    def on_line(line: int, offset: int, interp: Interpreter) -> None:
        if line > last_line and offset >= end_new:
            old_cp = memory.checkpoints.get(line - d_lines)
            if old_cp is not None and old_cp.offset == offset - d_chars and old_cp.last == relink_mem.last \
                    and state_of(interp) == old_cp.state:
                raise _Met(line, offset)
        if line - start_line > MAX_REGION_LINES:
            raise _GiveUp
        if line % EVERY == 0 and line > start_line:
            new_mem.checkpoints[line] = Checkpoint(offset, state_of(interp), relink_mem.last)

    cps = Checkpoints(on_line, every=1, interp=it, start=start.offset, line=start_line)
    cmds = lower_straight(src, old.dialect, sink, iopts, cps)

    def plain(cs: Iterator[Command]) -> Iterator[Command]:
        for c in cs:
            if transforms(c.frame):
                raise _GiveUp
            yield c

    stream = light_passes(plain(cmds), old.dialect, old.machine, opts, sink, relink_mem)
    region, times, met = _run_region(stream, check, old.machine, a.index.line_of)
    # ---- splice
    lo = start.offset  # the same in both texts (before the change)
    hi_new = met.offset if met is not None else len(text)
    hi_old = hi_new - d_chars if met is not None else len(old_text)
    i = first_at(old.commands, old.shifts, lo)
    j = first_at(old.commands, old.shifts, hi_old) if met is not None else len(old.commands)
    a.commands = old.commands[:i] + region + old.commands[j:]
    a.shifts = old.shifts.spliced(i, j, len(region), d_chars)
    met_line_old = met.line - d_lines if met is not None else old.index.line_count
    a.line_time_s = _spliced_times(old.line_time_s, times, start_line, met, d_lines)
    a.diagnostics = _spliced_diagnostics(old.diagnostics, list(sink), lo, hi_old, met, d_chars)
    if met is not None:
        for ln, cp in memory.checkpoints.items():
            if ln >= met_line_old:
                new_mem.checkpoints[ln + d_lines] = Checkpoint(cp.offset + d_chars, cp.state, cp.last)
        new_mem.last = memory.last
    else:
        new_mem.last = relink_mem.last
    a.memory = new_mem
    a.sources = sources
    a.reached = hi_new if met is not None else (region[-1].span.start if region else lo)
    if met is not None and old.reached >= hi_old:
        a.reached = old.reached + d_chars
    a.resumed = (start_line, met.line if met is not None else a.index.line_count)
    a.region = (lo, hi_new, hi_old)


def _run_region(stream: Iterator[Command], check: Callable[[], None], machine: Any, line_of: Callable[[int], int]
                ) -> tuple[list[Command], dict[int, float], _Met | None]:
    """Run the re-lowered region until its state meets the old run's: its commands, the
    nominal time per line, and where it met (None: it ran to the end)."""
    from cncc.backends.nominal import command_time_s

    region: list[Command] = []
    times: dict[int, float] = {}
    n = 0
    try:
        for c in stream:
            n += 1
            if n % 256 == 0:
                check()
            region.append(c)
            t, cat = command_time_s(c, machine)
            if cat and t > 0.0:
                ln = line_of(c.span.start)
                times[ln] = times.get(ln, 0.0) + t
    except _Met as m:
        return region, times, m
    return region, times, None


def _spliced_times(old_times: dict[int, float], times: dict[int, float], start_line: int, met: _Met | None,
                   d_lines: int) -> dict[int, float]:
    """The line times: the old ones outside the region (moved by ``d_lines`` after it), the new inside."""
    if met is not None and d_lines == 0:  # the lines did not move: copy, then redo the region
        kept_times = dict(old_times)
        for ln in range(start_line, met.line):
            kept_times.pop(ln, None)
    else:
        kept_times = {ln: t for ln, t in old_times.items() if ln < start_line}
        if met is not None:
            met_line_old = met.line - d_lines
            kept_times.update((ln + d_lines, t) for ln, t in old_times.items() if ln >= met_line_old)
    kept_times.update(times)
    return kept_times


def _spliced_diagnostics(old: list[Diagnostic], new: list[Diagnostic], lo: int, hi_old: int, met: _Met | None,
                         d_chars: int) -> list[Diagnostic]:
    """The old diagnostics before the region and (shifted) after it, and the region's new ones."""
    diags: list[Diagnostic] = []
    for d in old:
        s = d.span
        if s.source_id != 0 or s.start < lo:
            diags.append(d)
        elif met is not None and s.start >= hi_old:
            diags.append(_shift_diag(d, d_chars))
    diags += new
    diags.sort(key=lambda d: (d.span.source_id != 0, d.span.start))
    return diags


def _shift_diag(d: Diagnostic, delta: int) -> Diagnostic:
    s = d.span
    related = tuple(replace(r, span=Span(r.span.source_id, r.span.start + delta, r.span.end + delta))
                    if r.span.source_id == 0 else r for r in d.related)
    return replace(d, span=Span(s.source_id, s.start + delta, s.end + delta), related=related)
