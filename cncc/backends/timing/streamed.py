"""The ``-O0`` timing report made while the commands stream past: no command list, no trajectory.

Consumes the items of the path passes (commands and :class:`~cncc.ir.batch.MoveBatch` runs, in
machine coordinates) and a machine model; produces the :class:`TimingReport` that
:func:`cncc.backends.timing.aggregate.build_report` makes from the command list and the
nominal trajectory of :func:`cncc.backends.nominal.nominal_trajectory` -- the same numbers to
the nanosecond, which ``tests/timing/test_streamed.py`` checks on the corpus and generated
programs.

How it stays equal: the trajectory's phase start ``t0`` is a running float sum of the phase
durations in order, and a phase's nanoseconds are the difference of its rounded start and the
next one's; so each command keeps only the rounded start of its first phase (its time is the
next such start minus its own, the last one's the rounded total), each batch's durations come
from :func:`cncc.backends.nominal.batch_phases_s` (the per-command float operations) and are
summed by ``np.cumsum`` from the running total (sequential, as the trajectory's is).  Events go
through the same :class:`EventTimer` (and the same zero-time probe that gives a line its
category).  At the end the per-line, per-limit, per-category and per-tool sums are
``np.bincount`` over per-command arrays of a few bytes each; the report's line texts and N
words are read from the source when written (:mod:`.linecols`).

Memory: the per-command arrays (about 20 bytes a move; a batch's F words are not kept, they
take no time and share their move's line) and the per-line arrays; no command objects.
"""

from __future__ import annotations

import bisect
import math
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from cncc import diagnostics as dg
from cncc.backends import nominal
from cncc.backends.timing.events import CATEGORIES, EVENT_TYPES, EventTimer
from cncc.backends.timing.linecols import KeyView, LineStarts, SourceLines, SparseRows
from cncc.backends.timing.model import (
    LIMIT_KEYS,
    MAX_S,
    NS_PER_S,
    Column,
    LineTable,
    ProgramIndex,
    Run,
    TimingReport,
    to_ns,
)
from cncc.diagnostics import DiagnosticSink
from cncc.ir import Arc, Command, Linear, Rapid, ToolChange
from cncc.ir.batch import MoveBatch
from cncc.ir.machine import MachineModel, RapidMode
from cncc.source import NO_SPAN, SourceMap, Span

if TYPE_CHECKING:
    import numpy as np
    import numpy.typing as npt

    I64 = npt.NDArray[np.int64]
    F64 = npt.NDArray[np.float64]

MAX_NS = to_ns(MAX_S)
PLANNER = "nominal: length / feed"
_RAPID_LIMIT, _FEED_LIMIT = LIMIT_KEYS.index("rapid"), LIMIT_KEYS.index("feed")
_EVENT_LIMIT = {"dwell": "program", "tool_change": "machine", "spindle": "machine", "wait": "operator",
                "reversal": "machine"}
_MOTION_CAT = {Rapid: 0, Linear: 1, Arc: 2}
_ZERO_MACHINE = MachineModel("categories only", (), tool_change_s=0.0, spindle_ramp_s=0.0)
_NONE, _PHASES, _EVENT = 0, 1, 2  # what a command's kept value is: nothing, its first phase's start, its event ns
_FLUSH = 8192  # commands buffered as Python lists before they become arrays
_DTYPES = ("int32", "int64", "int8", "int8", "int8", "int8", "int32")  # of the kept per-command columns


def _bound_ns(t0_s: float) -> int:
    """A phase start in integer ns, as :func:`aggregate.phase_ns` rounds it."""
    if math.isnan(t0_s):
        return 0
    return round(min(max(t0_s, 0.0), MAX_S) * NS_PER_S)


def _bounds_ns(t0_s: F64) -> I64:
    import numpy as np

    clipped = np.clip(np.nan_to_num(t0_s, nan=0.0, posinf=MAX_S, neginf=0.0), 0.0, MAX_S)
    return np.rint(clipped * NS_PER_S).astype(np.int64)


def _sum_by(group: Any, value: I64, size: int) -> I64:
    """``out[g] = sum(value[group == g])``, exactly (integers)."""
    import numpy as np

    out = np.zeros(size, dtype=np.int64)
    np.add.at(out, group, value)
    return out


def _line_entries(n_lines: int, line: Any, col: Any, value: I64) -> tuple[Any, Any, I64, Any]:
    """The non-zero sums of ``value`` per (line, col) as entries ``(line, col, sum)`` sorted by line
    and col, and per line the col with the largest positive sum (ties: the lowest col; -1: none).

    Most lines get time from one col only: they are summed per line; the few lines with several
    cols go through ``np.unique`` of ``(line, col)`` codes."""
    import numpy as np

    lo = np.full(n_lines, 127, dtype=np.int8)
    hi = np.full(n_lines, -1, dtype=np.int8)
    np.minimum.at(lo, line, col)
    np.maximum.at(hi, line, col)
    total = _sum_by(line, value, n_lines)
    dominant = np.where((lo == hi) & (total > 0), lo, np.int8(-1))
    single = np.flatnonzero((lo == hi) & (total != 0)).astype(np.int32)
    rows, cols, sums = single, lo[single], total[single]
    del total
    mixed = lo < hi
    if mixed.any():
        on_mixed = mixed[line]
        code = line[on_mixed].astype(np.int64) * 128 + col[on_mixed]
        uniq, inv = np.unique(code, return_inverse=True)
        msum = _sum_by(inv.reshape(-1), value[on_mixed], len(uniq))
        keep = msum != 0
        mrow, mcol, msum = (uniq[keep] // 128).astype(np.int32), (uniq[keep] % 128).astype(np.int8), msum[keep]
        order = np.lexsort((mcol, -msum, mrow))
        first = np.ones(len(order), dtype=bool)
        first[1:] = mrow[order][1:] != mrow[order][:-1]
        best = order[first]
        dominant[mrow[best]] = np.where(msum[best] > 0, mcol[best], -1)
        rows, cols, sums = (np.concatenate((rows, mrow)), np.concatenate((cols, mcol)),
                            np.concatenate((sums, msum)))
        order = np.argsort(rows.astype(np.int64) * 128 + cols, kind="stable")
        rows, cols, sums = rows[order], cols[order], sums[order]
    return rows, cols, sums, dominant


class NominalStream:
    """Accumulates the ``-O0`` report of one program (see the module docstring)."""

    def __init__(self, machine: MachineModel, sources: SourceMap) -> None:
        self.machine, self.sources = machine, sources
        self.timer, self.probe = EventTimer(machine), EventTimer(_ZERO_MACHINE)
        self.starts = LineStarts(sources)
        self.t_s = 0.0  # the running sum of the phase durations (the trajectory's t0 of the next phase)
        self.phases = 0
        self.t0_bad = False  # some phase starts later than MAX_S or at a non-finite time
        self.first_phase = -1  # the command of the first phase, and its span
        self.first_phase_span = NO_SPAN
        self.tool = -1
        self.tools: set[int] = set()
        self.event_ns = 0
        self.operator_ns = 0
        self.events: list[tuple[int, int, str, bool, str]] = []
        self.event_cmds: list[int] = []
        self.cut = -1  # the first event cut to keep the events' sum within MAX_S
        self.cut_span = NO_SPAN
        self.op_lines: set[int] = set()
        self.n_cmds = 0
        self.line_id = 0
        self.n_keys = 0
        self._ids: dict[int, I64] = {}
        self._key_sid: list[Any] = []
        self._key_line: list[Any] = []
        self._new_keys: list[tuple[int, int]] = []  # keys of the commands since the last flush
        self._buf: list[list[int]] = [[], [], [], [], [], [], []]  # line, value, kind, cat, time cat, limit, tool
        self._chunks: list[list[Any]] = [[], [], [], [], [], [], []]  # the same, as arrays

    # ---- lines -------------------------------------------------------------------------
    def _line_of(self, sid: int, start: int) -> int:
        starts = self.starts.of(sid)
        if starts is None:
            return 0
        return bisect.bisect_right(starts, start) if len(starts) < 64 else int(starts.searchsorted(start, "right"))

    def _ids_of(self, sid: int) -> I64:
        import numpy as np

        got = self._ids.get(sid)
        if got is None:
            starts = self.starts.of(sid)
            got = self._ids[sid] = np.full(len(starts) + 1 if starts is not None else 1, -1, dtype=np.int64)
        return got

    def _line_id(self, span: Span) -> int:
        """The report line of a command (first-use order; a generated command: the line before)."""
        if (span.source_id < 0 or span.start < 0) and self.n_keys:
            return self.line_id
        line = self._line_of(span.source_id, span.start)
        ids = self._ids_of(span.source_id)
        k = int(ids[line])
        if k < 0:
            k = ids[line] = self.n_keys
            self.n_keys += 1
            self._new_keys.append((span.source_id, line))
        self.line_id = k
        return k

    # ---- commands ----------------------------------------------------------------------
    def _phases_of(self, c: Command) -> list[float]:
        """The phase durations of a motion, as :func:`nominal.nominal_trajectory` makes them."""
        m = self.machine
        if isinstance(c, Rapid):
            if m.rapid_mode is RapidMode.INDEPENDENT:
                return nominal.independent_rapid_phases_s(c.start, c.end, m)
            durs = [nominal.rapid_time_s(c.start, c.end, m)]
        elif isinstance(c, Linear):
            durs = [nominal.linear_time_s(c)]
        else:
            assert isinstance(c, Arc)
            sweep = nominal.arc_sweep_rad(c)
            n = nominal.arc_chords(sweep)
            durs = [nominal.feed_time_s(nominal.arc_length_mm(c), c.feed_mm_min) / n] * n
        return [d for d in durs if not d <= 0.0]

    def command(self, c: Command) -> None:
        i = self.n_cmds
        line = self._line_id(c.span)
        if isinstance(c, ToolChange):
            self.tool = c.tool
        self.tools.add(self.tool)
        kind, value, cat, tcat, limit = _NONE, 0, -1, -1, 0
        motion_cat = _MOTION_CAT.get(type(c))
        if motion_cat is not None:
            cat = tcat = motion_cat
            limit = _RAPID_LIMIT if motion_cat == 0 else _FEED_LIMIT
            durs = self._phases_of(c)
            if durs:
                kind, value = _PHASES, _bound_ns(self.t_s)
                if self.first_phase < 0:
                    self.first_phase, self.first_phase_span = i, c.span
                for d in durs:
                    self.t0_bad = self.t0_bad or not -math.inf < self.t_s <= MAX_S
                    self.t_s += d
                self.phases += len(durs)
        elif isinstance(c, EVENT_TYPES):
            self.event_cmds.append(i)
            probe = self.probe.event(c)
            cat = CATEGORIES.index(probe.category) if probe is not None else -1
            ev = self.timer.event(c)
            if ev is not None:
                want = to_ns(ev.seconds)
                ns = max(min(want, MAX_NS - self.event_ns), 0)
                if (ns < want or not 0.0 <= ev.seconds <= MAX_S) and self.cut < 0:
                    self.cut, self.cut_span = i, c.span
                self.event_ns += ns
                kind, value = _EVENT, ns
                tcat = CATEGORIES.index(ev.category)
                limit = LIMIT_KEYS.index(_EVENT_LIMIT[ev.category])
                self.events.append((i, ns, ev.category, ev.operator_dependent, ev.what))
                if ev.operator_dependent:
                    self.operator_ns += ns
                    self.op_lines.add(line)
        for column, v in zip(self._buf, (line, value, kind, cat, tcat, limit, self.tool), strict=True):
            column.append(v)
        self.n_cmds += 1
        if len(self._buf[0]) >= _FLUSH:
            self._flush()

    def _flush(self) -> None:
        import numpy as np

        if self._buf[0]:
            self._store(*(np.asarray(col) for col in self._buf))
            self._buf = [[], [], [], [], [], [], []]
        if self._new_keys:
            keys = np.asarray(self._new_keys, dtype=np.int32).reshape(-1, 2)
            self._key_sid.append(keys[:, 0])
            self._key_line.append(keys[:, 1])
            self._new_keys = []

    def _store(self, *columns: Any) -> None:
        for chunks, col, dtype in zip(self._chunks, columns, _DTYPES, strict=True):
            chunks.append(col.astype(dtype))

    def batch(self, b: MoveBatch) -> None:
        import numpy as np

        sid = b.source_id
        timed = nominal.batch_phases_s(b, self.machine)
        starts = self.starts.of(sid)
        lines = starts.searchsorted(b.span_start, "right") if starts is not None else None
        has_f = b.feed_start >= 0
        if (timed is None or starts is None or lines is None or bool((b.span_start < 0).any())
                or (has_f.any() and not np.array_equal(starts.searchsorted(b.feed_start[has_f], "right"),
                                                       lines[has_f]))):
            for c in b.commands():  # an F word on another line than its move, or constant surface speed
                self.command(c)
            return
        self._flush()
        dur, counts = timed
        ids = self._ids_of(sid)
        line_id = ids[lines]
        new = line_id < 0
        if new.any():
            uniq, first = np.unique(lines[new], return_index=True)
            fresh = uniq[np.argsort(first, kind="stable")]
            ids[fresh] = np.arange(self.n_keys, self.n_keys + len(fresh))
            self.n_keys += len(fresh)
            self._key_sid.append(np.full(len(fresh), sid, dtype=np.int32))
            self._key_line.append(fresh.astype(np.int32))
            line_id = ids[lines]
        n = len(b)
        value = np.zeros(n, dtype=np.int64)
        has = counts > 0
        if len(dur):
            run = np.cumsum(np.concatenate(([self.t_s], dur)))
            t0 = run[:-1]
            self.t0_bad = self.t0_bad or not bool(((t0 > -math.inf) & (t0 <= MAX_S)).all())
            self.t_s = float(run[-1])
            self.phases += len(dur)
            first_phase = (np.cumsum(counts) - counts)[has]
            value[has] = _bounds_ns(t0[first_phase])
            if self.first_phase < 0:
                r = int(np.flatnonzero(has)[0])
                self.first_phase = self.n_cmds + r
                self.first_phase_span = Span(sid, int(b.span_start[r]), int(b.span_end[r]))
        self.tools.add(self.tool)
        cat = b.kind.astype(np.int64)
        limit = np.where(cat == 0, _RAPID_LIMIT, _FEED_LIMIT)
        self._store(line_id, value, np.where(has, _PHASES, _NONE), cat, cat, limit, np.full(n, self.tool))
        self.n_cmds += n
        self.line_id = int(line_id[-1])

    def feed(self, items: Iterable[Command | MoveBatch]) -> None:
        for x in items:
            if type(x) is MoveBatch:
                self.batch(x)
            else:
                self.command(x)  # type: ignore[arg-type]

    # ---- the report --------------------------------------------------------------------
    def report(self, file: str, dialect: str, top_n: int = 10, sink: DiagnosticSink | None = None) -> TimingReport:
        import numpy as np

        from cncc.ir.frame import AXES
        from cncc.ir.trajectory import Trajectory

        self._flush()
        empty = np.zeros(0, dtype=np.int32)
        line, value, kind, cat, tcat, limit, tool = (np.concatenate(c) if c else empty for c in self._chunks)
        self._chunks = [[], [], [], [], [], [], []]
        n_lines = self.n_keys
        total_s = self.t_s if self.phases else 0.0
        motion_ns = to_ns(total_s)
        clamped = self.phases > 0 and (not 0.0 <= total_s <= MAX_S or self.t0_bad)
        cmd_ns = np.where(kind == _EVENT, value, 0)
        ph = np.flatnonzero(kind == _PHASES)
        if len(ph):
            b = np.minimum(value[ph], motion_ns)
            cmd_ns[ph] = np.diff(b, append=motion_ns)
            del b
        del value, kind, ph
        line_ns = _sum_by(line, cmd_ns, n_lines)
        nz = np.flatnonzero(cmd_ns)
        lim_row, lim_col, lim_ns, limited_by = _line_entries(n_lines, line[nz], limit[nz], cmd_ns[nz])
        del limit
        has_cat = nz[cat[nz] >= 0]
        category = _line_entries(n_lines, line[has_cat], cat[has_cat], cmd_ns[has_cat])[3]
        tools = sorted(self.tools) if len(line) else []
        tool_arr = np.asarray(tools, dtype=np.int64)
        timed = nz[tcat[nz] >= 0]
        code = np.searchsorted(tool_arr, tool[timed]) * len(CATEGORIES) + tcat[timed]
        tool_cat = _sum_by(code, cmd_ns[timed], len(tools) * len(CATEGORIES)).reshape(len(tools), len(CATEGORIES))
        del nz, has_cat, timed, code, tcat
        line_end = np.zeros(n_lines, dtype=np.int64)
        np.maximum.at(line_end, line, np.cumsum(cmd_ns))
        key_sid = np.concatenate(self._key_sid) if self._key_sid else empty
        key_line = np.concatenate(self._key_line) if self._key_line else empty
        files: dict[str, int] = {}
        name_of: dict[int, int] = {}
        uniq, first = np.unique(key_sid, return_index=True)
        for sid in uniq[np.argsort(first, kind="stable")].tolist():
            src = self.sources.get(sid)
            name_of[sid] = files.setdefault(src.name if src is not None else "<generated>", len(files))
        file_of = np.asarray([name_of[s] for s in uniq.tolist()], dtype=np.int32)[np.searchsorted(uniq, key_sid)] \
            if len(uniq) else empty
        op = np.zeros(n_lines, dtype=bool)
        op[sorted(self.op_lines)] = True
        limits = SparseRows(n_lines, len(LIMIT_KEYS), lim_row, lim_col, lim_ns, ordered=True)
        table = LineTable(
            files=list(files), file_of=file_of, line=key_line,
            n=SourceLines(self.starts, key_sid, key_line, "n"),
            text=SourceLines(self.starts, key_sid, key_line, "text"),
            times_ns=line_ns.reshape(-1, 1), category=category, limited_by=limited_by, limits_ns=limits,
            elapsed_ns=line_end,
            operator_dependent=op, categories=CATEGORIES)
        clamped_cmd = self.first_phase if clamped else self.cut
        if clamped_cmd >= 0 and sink is not None:
            sink.emit(dg.TIME_CLAMPED, self.first_phase_span if clamped else self.cut_span,
                      f"timing O0: a time is too long or not finite; the report counts at most {MAX_S:g} s of "
                      f"motion and {MAX_S:g} s of events")
        run = Run("O0", self.machine, 0, Trajectory.empty(AXES), PLANNER, nominal=True, phases=self.phases)
        category_ns = {c: int(tool_cat[:, k].sum()) for k, c in enumerate(CATEGORIES)}
        tool_ns = {t: {c: int(tool_cat[k, j]) for j, c in enumerate(CATEGORIES)} for k, t in enumerate(tools)}
        col = Column(run, motion_ns, self.event_ns, line_ns, limits, cmd_ns, category_ns, tool_ns,
                     self.operator_ns, self.events, clamped or clamped_cmd >= 0, clamped_cmd)
        index = ProgramIndex(KeyView(key_sid, key_line), line.astype(np.int64), tool, cat, self.event_cmds,
                             self.op_lines)
        return TimingReport(file, dialect, [col], 0, table, index, top_n)


def streamed_report(items: Iterable[Command | MoveBatch], machine: MachineModel, sources: SourceMap, file: str,
                    dialect: str, top_n: int = 10, sink: DiagnosticSink | None = None) -> TimingReport:
    """The ``-O0`` report of ``items`` (one nominal column), made as they stream."""
    acc = NominalStream(machine, sources)
    acc.feed(items)
    return acc.report(file, dialect, top_n, sink)
