"""Aggregate trajectories and events into a :class:`TimingReport`.

Consumes the command list the planner saw (``Trajectory.cmd_index`` indexes it), the
source map, and one :class:`Run` per column; produces per-line, per-tool and
per-category times in integer nanoseconds.  Phase ``k`` is charged the time from its
start ``t0_s[k]`` to the next phase's start (the last phase up to the trajectory's
end), so phase times add up to ``Trajectory.duration_total_s`` exactly after
rounding each boundary once.  A command with no phase is an event
(:mod:`.events`); a command the planner gave phases (e.g. a dwell planned as a
standstill) is timed by its phases only, never twice.  The reversal pauses of a run
(:attr:`Run.reversals`) are events of their own category, charged to the motion
command in which the axis reverses.

:func:`event_pauses` gives the same event times to the driver, which passes them to
the pulse backend so that the pulse time line pauses where the report counts time.
"""

from __future__ import annotations

import re
from collections.abc import Iterator, Sequence

from cncc import diagnostics as dg
from cncc.backends.timing.events import CATEGORIES, EVENT_TYPES, Event, EventTimer
from cncc.backends.timing.model import (
    LIMIT_KEYS,
    MAX_S,
    MOTION_LIMITS,
    NS_PER_S,
    Column,
    LineRow,
    LineTable,
    ProgramIndex,
    Run,
    TimingReport,
    to_ns,
)
from cncc.backends.timing.progress import track
from cncc.diagnostics import DiagnosticSink
from cncc.ir import Arc, Command, Linear, Rapid, ToolChange
from cncc.ir.machine import MachineModel
from cncc.source import NO_SPAN, SourceMap

MAX_NS = to_ns(MAX_S)
_N_WORD = re.compile(r"\s*/?\s*([Nn]\s*\d+)")
_EVENT_LIMIT = {"dwell": "program", "tool_change": "machine", "spindle": "machine", "wait": "operator",
                "reversal": "machine"}
_MOTION_CAT = {Rapid: 0, Linear: 1, Arc: 2}
_ZERO_MACHINE = MachineModel("categories only", (), tool_change_s=0.0, spindle_ramp_s=0.0)


def build_index(cmds: Sequence[Command]) -> ProgramIndex:
    """Line, tool and category of every command (one pass over the commands)."""
    import numpy as np

    n = len(cmds)
    cmd_line = np.zeros(n, dtype=np.int64)
    cmd_tool = np.full(n, -1, dtype=np.int64)
    cmd_cat = np.full(n, -1, dtype=np.int64)
    keys: dict[tuple[int, int], int] = {}
    event_cmds: list[int] = []
    probe = EventTimer(_ZERO_MACHINE)
    tool = -1
    last_start = (-2, -1)
    line_id = 0
    for i, c in enumerate(track(cmds, n, "indexing blocks")):
        span = c.span
        if (span.source_id < 0 or span.start < 0) and keys:
            pass  # a generated command without a real span: charge it to the block before it
        elif (span.source_id, span.start) != last_start:  # consecutive commands often share a start
            last_start = (span.source_id, span.start)
            line_id = keys.setdefault((span.source_id, span.start), len(keys))
        cmd_line[i] = line_id
        if isinstance(c, ToolChange):
            tool = c.tool
        cmd_tool[i] = tool
        cat = _MOTION_CAT.get(type(c))
        if cat is None and isinstance(c, EVENT_TYPES):
            event_cmds.append(i)
            ev = probe.event(c)
            cat = CATEGORIES.index(ev.category) if ev is not None else None
        cmd_cat[i] = -1 if cat is None else cat
    return ProgramIndex(list(keys), cmd_line, cmd_tool, cmd_cat, event_cmds)


def _span_starts_to_lines(index: ProgramIndex, sources: SourceMap) -> None:
    """Turn the (source, span start) keys into (source, line) keys, merging same-line spans."""
    import numpy as np

    keys = np.asarray(index.line_keys, dtype=np.int64).reshape(-1, 2)
    line = np.zeros(len(keys), dtype=np.int64)
    for sid in np.unique(keys[:, 0]).tolist():  # one sorted search per source file, not one per key
        src = sources.get(sid)
        if src is None:
            continue
        mine = keys[:, 0] == sid
        starts = np.asarray(src.line_starts, dtype=np.int64)
        line[mine] = np.searchsorted(starts, keys[mine, 1], side="right")
    remap: dict[tuple[int, int], int] = {}
    new_id = np.fromiter((remap.setdefault(k, len(remap)) for k in zip(keys[:, 0].tolist(), line.tolist(),
                                                                          strict=True)),
                         np.int64, len(keys))
    index.line_keys = list(remap)
    index.cmd_line = new_id[index.cmd_line] if len(index.cmd_line) else index.cmd_line


def phase_ns(run: Run) -> tuple[int, object, bool]:
    """(trajectory duration in ns, per-phase ns array, clamped?) with exact telescoping sums."""
    import numpy as np

    traj = run.trajectory
    total_s = traj.duration_total_s
    total_ns = to_ns(total_s)
    clamped = not 0.0 <= total_s <= MAX_S
    if traj.phase_count == 0:
        return total_ns, np.zeros(0, dtype=np.int64), clamped
    t0 = np.nan_to_num(traj.t0_s, nan=0.0, posinf=MAX_S, neginf=0.0)
    clamped = clamped or bool((t0 > MAX_S).any()) or not np.isfinite(traj.t0_s).all()
    bounds = np.rint(np.clip(t0, 0.0, MAX_S) * NS_PER_S).astype(np.int64)
    bounds[0] = 0
    return total_ns, np.diff(np.append(np.minimum(bounds, total_ns), total_ns)), clamped


def column(run: Run, cmds: Sequence[Command], index: ProgramIndex) -> Column:
    import numpy as np

    n_lines, n_cmds = len(index.line_keys), len(cmds)
    traj = run.trajectory
    motion_ns, dur_ns, clamped = phase_ns(run)
    clamped_cmd = int(traj.cmd_index[0]) if clamped and traj.phase_count else -1
    dur = np.asarray(dur_ns, dtype=np.int64)
    ci = traj.cmd_index.astype(np.int64)
    cmd_ns = np.zeros(n_cmds, dtype=np.int64)
    line_ns = np.zeros(n_lines, dtype=np.int64)
    line_limit = np.zeros((n_lines, len(LIMIT_KEYS)), dtype=np.int64)
    np.add.at(cmd_ns, ci, dur)
    limit = np.clip(traj.limit.astype(np.int64), 0, len(MOTION_LIMITS) - 1)
    np.add.at(line_limit, (index.cmd_line[ci], limit), dur)
    covered = np.zeros(n_cmds, dtype=bool)
    covered[ci] = True
    cat_of_phase = np.where(index.cmd_cat[ci] >= 0, index.cmd_cat[ci], 1)  # a phase of a timeless command: feed
    tools = sorted({int(t) for t in np.unique(index.cmd_tool)}) if n_cmds else []
    tool_pos = {t: k for k, t in enumerate(tools)}
    tool_cat = np.zeros((len(tools), len(CATEGORIES)), dtype=np.int64)
    if len(ci):
        tool_idx = np.searchsorted(np.asarray(tools, dtype=np.int64), index.cmd_tool[ci])
        np.add.at(tool_cat, (tool_idx, cat_of_phase), dur)
    events, event_ns, operator_ns = [], 0, 0
    for i, ns, ev, cut in timed_events(cmds, index.event_cmds, covered, run.machine, run.reversals):
        if cut:
            clamped_cmd = i if clamped_cmd < 0 else clamped_cmd
        events.append((i, ns, ev.category, ev.operator_dependent, ev.what))
        event_ns += ns
        operator_ns += ns if ev.operator_dependent else 0
        cmd_ns[i] += ns
        line_limit[index.cmd_line[i], LIMIT_KEYS.index(_EVENT_LIMIT[ev.category])] += ns
        tool_cat[tool_pos[int(index.cmd_tool[i])], CATEGORIES.index(ev.category)] += ns
        if ev.operator_dependent:
            index.op_dependent_lines.add(int(index.cmd_line[i]))
    np.add.at(line_ns, index.cmd_line, cmd_ns)
    category_ns = {cat: int(tool_cat[:, k].sum()) for k, cat in enumerate(CATEGORIES)}
    tool_ns = {t: {cat: int(tool_cat[k, j]) for j, cat in enumerate(CATEGORIES)} for t, k in tool_pos.items()}
    return Column(run, motion_ns, event_ns, line_ns, line_limit, cmd_ns, category_ns, tool_ns, operator_ns, events,
                  clamped or clamped_cmd >= 0, clamped_cmd)


def timed_events(cmds: Sequence[Command], event_cmds: Sequence[int], covered: object, machine: MachineModel,
                 reversals: Sequence[tuple[int, int, str]] = ()) -> Iterator[tuple[int, int, Event, bool]]:
    """``(command index, ns, event, clamped)`` of every event a column counts, in command order.

    ``event_cmds``: the commands that may be events, in order; ``covered[i]``: command ``i``
    has phases (then its phases are its time).  The events' sum is kept within ``MAX_S``.
    """
    timer = EventTimer(machine)
    found: list[tuple[int, int, Event]] = []
    for i in event_cmds:
        ev = timer.event(cmds[i])
        if ev is not None and not covered[i]:  # type: ignore[index]
            found.append((i, -1, ev))
    found += [(i, ns, Event(ns / NS_PER_S, "reversal", what=what)) for i, ns, what in reversals
              if 0 <= i < len(cmds)]
    found.sort(key=lambda e: e[0])
    total = 0
    for i, given_ns, ev in found:
        want = given_ns if given_ns >= 0 else to_ns(ev.seconds)
        ns = max(min(want, MAX_NS - total), 0)  # the events' sum stays within MAX_S too
        total += ns
        yield i, ns, ev, ns < want or (given_ns < 0 and not 0.0 <= ev.seconds <= MAX_S)


def event_pauses(cmds: Sequence[Command], cmd_index: object, machine: MachineModel) -> list[tuple[int, int]]:
    """``(command index, ns)`` of the events with time that a column of a trajectory with
    ``cmd_index`` counts (reversal pauses aside): where the pulse time line must pause."""
    import numpy as np

    covered = np.zeros(len(cmds), dtype=bool)
    ci = np.asarray(cmd_index, dtype=np.int64)
    covered[ci[(ci >= 0) & (ci < len(cmds))]] = True
    event_cmds = [i for i, c in enumerate(cmds) if isinstance(c, EVENT_TYPES)]
    return [(i, ns) for i, ns, _ev, _cut in timed_events(cmds, event_cmds, covered, machine) if ns > 0]


def _dominant_index(ns: object) -> object:
    """Per row of ``ns`` (shape ``(L, K)``), the column with the most time (-1 if none)."""
    import numpy as np

    arr = np.asarray(ns)
    if arr.shape[0] == 0:
        return np.zeros(0, dtype=np.int64)
    return np.where(arr.max(axis=1) > 0, arr.argmax(axis=1), -1).astype(np.int64)


def line_table(columns: list[Column], index: ProgramIndex, sources: SourceMap) -> LineTable:
    """The per-line arrays of the report (texts and N words read once per source file)."""
    import numpy as np

    primary = columns[0]
    n_lines = len(index.line_keys)
    line_end = np.zeros(n_lines, dtype=np.int64)
    np.maximum.at(line_end, index.cmd_line, np.cumsum(primary.cmd_ns))
    cat_ns = np.zeros((n_lines, len(CATEGORIES)), dtype=np.int64)
    has_cat = index.cmd_cat >= 0
    np.add.at(cat_ns, (index.cmd_line[has_cat], index.cmd_cat[has_cat]), primary.cmd_ns[has_cat])
    files: dict[str, int] = {}
    split: dict[int, list[str]] = {}
    file_of = np.zeros(n_lines, dtype=np.int64)
    texts: list[str] = []
    numbers: list[str] = []
    match = _N_WORD.match
    for k, (sid, line) in enumerate(index.line_keys):
        src = sources.get(sid)
        file_of[k] = files.setdefault(src.name if src is not None else "<generated>", len(files))
        lines = split.get(sid)
        if lines is None:
            lines = split[sid] = src.text.split("\n") if src is not None else []
        raw = lines[line - 1].rstrip("\r") if 1 <= line <= len(lines) else ""
        m = match(raw)
        numbers.append(m.group(1).replace(" ", "").upper() if m else "")
        texts.append(raw.strip())
    op = np.zeros(n_lines, dtype=bool)
    op[[k for k in index.op_dependent_lines if 0 <= k < n_lines]] = True
    times = np.stack([c.line_ns for c in columns], axis=1) if n_lines else np.zeros((0, len(columns)), np.int64)
    return LineTable(
        files=list(files), file_of=file_of,
        line=np.asarray([line for _sid, line in index.line_keys], dtype=np.int64).reshape(-1),
        n=numbers, text=texts, times_ns=times.astype(np.int64), category=_dominant_index(cat_ns),  # type: ignore[arg-type]
        limited_by=_dominant_index(primary.line_limit_ns),  # type: ignore[arg-type]
        limits_ns=primary.line_limit_ns, elapsed_ns=line_end, operator_dependent=op, categories=CATEGORIES)


def line_rows(columns: list[Column], index: ProgramIndex, sources: SourceMap) -> list[LineRow]:
    """The per-line rows as objects (tests and small reports; the report itself keeps a :class:`LineTable`)."""
    return list(line_table(columns, index, sources))


def build_report(cmds: Sequence[Command], runs: Sequence[Run], sources: SourceMap, file: str, dialect: str,
                 top_n: int = 10, sink: DiagnosticSink | None = None) -> TimingReport:
    """The report for ``runs`` (the first is the primary column) over ``cmds``."""
    index = build_index(cmds)
    _span_starts_to_lines(index, sources)
    columns = [column(run, cmds, index) for run in runs]
    for col in columns:
        if col.clamped and sink is not None:
            span = cmds[col.clamped_cmd].span if 0 <= col.clamped_cmd < len(cmds) else NO_SPAN
            sink.emit(dg.TIME_CLAMPED, span, f"timing {col.run.label}: a time is too long or not finite; the "
                      f"report counts at most {MAX_S:g} s of motion and {MAX_S:g} s of events")
    nominal = next((k for k, r in enumerate(runs) if r.nominal), None)
    return TimingReport(file, dialect, columns, nominal, line_table(columns, index, sources), index, top_n)

