"""What the timing report is made of: the program index, one column per plan, line rows.

Times are integers in nanoseconds (``_ns``) so that sums are exact: a column's
total is its trajectory duration plus its event times, and the per-line, per-block,
per-tool and per-category times each add up to that total to the nanosecond.
Seconds (``_s``) are derived for display only.

Array shapes: ``n`` commands, ``L`` source lines that produced commands,
``K`` = ``len(LIMIT_KEYS)``.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, overload

from cncc.ir.machine import MachineModel

if TYPE_CHECKING:
    import numpy as np
    import numpy.typing as npt

    from cncc.backends.timing.linecols import SparseRows
    from cncc.ir.trajectory import Trajectory

    I64 = npt.NDArray[np.int64]
    Ints = npt.NDArray[np.integer[Any]]  # indices and small codes (int8 .. int64)

NS_PER_S = 1_000_000_000

MOTION_LIMITS: tuple[str, ...] = ("none", "feed", "accel", "jerk", "corner", "axis_velocity", "step_rate", "rapid",
                                  "centripetal")
"""Names of :class:`cncc.ir.trajectory.Limit` values, indexed by the value."""

EVENT_LIMITS: tuple[str, ...] = ("program", "machine", "operator")
"""What sets an event's time: the program (dwell), the machine model, an operator."""

LIMIT_KEYS: tuple[str, ...] = MOTION_LIMITS + EVENT_LIMITS


MAX_S = 1e8
"""Longest trajectory, and longest sum of events, a report counts (about three years): longer
or non-finite times (from absurd feeds or dwells) are clamped, so integer sums never overflow."""


def to_ns(t_s: float) -> int:
    """Seconds to integer nanoseconds, clamped to ``[0, MAX_S]`` (NaN counts as 0)."""
    if not t_s > 0.0:
        return 0
    return round(min(t_s, MAX_S) * NS_PER_S)


def to_s(t_ns: int) -> float:
    return t_ns / NS_PER_S


@dataclass(frozen=True, slots=True)
class Run:
    """One column of the report: a trajectory planned for a machine at a level."""

    label: str
    machine: MachineModel
    level: int
    trajectory: Trajectory
    planner: str = ""  # how it was produced, e.g. "nominal (length / feed)"
    nominal: bool = False
    reversals: tuple[tuple[int, int, str], ...] = ()
    """(command index, ns, what) of the reversal pauses (SZGH Axis P68) in this trajectory on this
    machine: the pulse backend's (``ReversalPauses.by_command``), passed in by the driver."""
    phases: int = -1
    """How many phases the trajectory has, when it was not kept (:mod:`.streamed`: ``trajectory``
    is then empty); -1: count ``trajectory``'s."""

    @property
    def phase_count(self) -> int:
        return self.phases if self.phases >= 0 else self.trajectory.phase_count


@dataclass(slots=True)
class ProgramIndex:
    """Column-independent facts about the commands: line, tool and category of each."""

    line_keys: Sequence[tuple[int, int]]  # (source_id, 1-based line) in first-use order
    cmd_line: I64  # (n,) index into line_keys
    cmd_tool: Ints  # (n,) tool in the spindle (-1: none yet)
    cmd_cat: Ints  # (n,) index into CATEGORIES (-1: no time)
    event_cmds: list[int]  # indices of commands that may be events
    op_dependent_lines: set[int] = field(default_factory=set)


@dataclass(slots=True)
class Column:
    """The times of one :class:`Run`, aggregated."""

    run: Run
    motion_ns: int
    event_ns: int
    line_ns: I64  # (L,)
    line_limit_ns: I64 | SparseRows  # (L, K)
    cmd_ns: I64  # (n,) motion + event time of each command
    category_ns: dict[str, int]
    tool_ns: dict[int, dict[str, int]]  # tool -> category -> ns
    operator_ns: int  # time of operator-dependent events (included in the total)
    event_list: list[tuple[int, int, str, bool, str]]  # (cmd, ns, category, operator-dependent, what)
    clamped: bool = False  # some time exceeded MAX_S or was not finite
    clamped_cmd: int = -1  # the first command concerned (-1: unknown)

    @property
    def total_ns(self) -> int:
        return self.motion_ns + self.event_ns


@dataclass(frozen=True, slots=True)
class LineRow:
    """One source line that produced commands (times of every column)."""

    index: int
    file: str
    line: int
    n: str  # the block's N word as written ("N010"), "" if none
    text: str
    times_ns: tuple[int, ...]  # one per column
    category: str  # the category with the most time (primary column)
    limited_by: str  # the LIMIT_KEYS entry with the most time (primary column)
    limits_ns: dict[str, int]  # primary column, non-zero entries
    elapsed_ns: int  # primary column: wall time at the end of this line's last command
    operator_dependent: bool


@dataclass(slots=True)
class LineTable:
    """The report's source lines as columns of arrays (``L`` lines, ``C`` report columns).

    A sequence of :class:`LineRow`: indexing, slicing and iteration build rows on demand,
    so a million-line report never holds a million row objects; the aggregations
    (:meth:`TimingReport.blocks`, :meth:`TimingReport.top`) and the JSON writer read the
    arrays directly.  ``category`` and ``limited_by`` index ``categories`` and
    ``LIMIT_KEYS`` (-1: none).
    """

    files: list[str]  # distinct file names
    file_of: Ints  # (L,) index into files
    line: Ints  # (L,) 1-based line number
    n: Sequence[str]  # (L,) the block's N word as written ("N010"), "" if none
    text: Sequence[str]  # (L,) the line's text, stripped
    times_ns: I64  # (L, C)
    category: Ints  # (L,) index into ``categories`` (-1: none)
    limited_by: Ints  # (L,) index into LIMIT_KEYS (-1: none)
    limits_ns: I64 | SparseRows  # (L, K) primary column (sparse in streamed reports)
    elapsed_ns: I64  # (L,) primary column: wall time at the end of the line's last command
    operator_dependent: npt.NDArray[np.bool_]  # (L,)
    categories: tuple[str, ...] = ()

    def __len__(self) -> int:
        return len(self.text)

    def row(self, k: int) -> LineRow:
        limits = self.limits_ns[k].tolist()
        cat, lim = int(self.category[k]), int(self.limited_by[k])
        return LineRow(
            index=k, file=self.files[int(self.file_of[k])], line=int(self.line[k]), n=self.n[k], text=self.text[k],
            times_ns=tuple(self.times_ns[k].tolist()), category=self.categories[cat] if cat >= 0 else "",
            limited_by=LIMIT_KEYS[lim] if lim >= 0 else "",
            limits_ns={key: v for key, v in zip(LIMIT_KEYS, limits, strict=True) if v},
            elapsed_ns=int(self.elapsed_ns[k]), operator_dependent=bool(self.operator_dependent[k]))

    @overload
    def __getitem__(self, k: int) -> LineRow: ...

    @overload
    def __getitem__(self, k: slice) -> list[LineRow]: ...

    def __getitem__(self, k: int | slice) -> LineRow | list[LineRow]:
        if isinstance(k, slice):
            return [self.row(i) for i in range(*k.indices(len(self)))]
        if k < 0:
            k += len(self)
        if not 0 <= k < len(self):
            raise IndexError(k)
        return self.row(k)

    def __iter__(self) -> Iterator[LineRow]:
        return (self.row(k) for k in range(len(self)))


@dataclass(slots=True)
class TimingReport:
    file: str
    dialect: str
    columns: list[Column]
    nominal: int | None  # index of the nominal column, if any
    lines: LineTable
    index: ProgramIndex
    top_n: int = 10

    @property
    def primary(self) -> Column:
        return self.columns[0]

    def blocks(self) -> list[tuple[str, tuple[int, ...]]]:
        """Time per ``N`` label (lines without one under ``""``), in first-use order."""
        import numpy as np

        group: dict[str, int] = {}
        names = self.lines.n
        of = np.zeros(len(names), dtype=np.int64)
        for lo in range(0, len(names), 4096):  # a chunk at a time: a streamed report reads its N words from the source
            of[lo:lo + 4096] = [group.setdefault(n, len(group)) for n in names[lo:lo + 4096]]
        times = self.lines.times_ns
        sums = np.zeros((len(group), times.shape[1] if times.ndim == 2 else 0), dtype=np.int64)
        np.add.at(sums, of, times)
        return [(n, tuple(v)) for n, v in zip(group, sums.tolist(), strict=True)]

    def top(self) -> list[LineRow]:
        """The ``top_n`` lines with the most primary-column time (ties: the earlier line first)."""
        import numpy as np

        if not len(self.lines):
            return []
        t = self.lines.times_ns[:, 0]
        order = np.lexsort((np.arange(t.size), -t))[: self.top_n]
        return [self.lines.row(int(k)) for k in order if t[k] > 0]


def hms(t_ns: int) -> str:
    """A duration as ``h:mm:ss`` (``mm:ss`` under an hour is still written ``0:mm:ss``), rounded to the second."""
    s = max(round(t_ns / NS_PER_S), 0)
    return f"{s // 3600}:{s // 60 % 60:02d}:{s % 60:02d}"
