"""The Python API for pipelines: compile programs without the command line (docs/api.md).

:func:`compile` (and its helpers :func:`translate` and :func:`time`) take program text
or a file, guess the dialect when none is given, read ``cncc.toml`` and the modeline as
the command line does, and return a typed :class:`CompileResult`.  :func:`compile_text`
and :func:`compile_commands` are the low-level entry points the tests use.

>>> from cncc.api import compile_text
>>> r = compile_text("G01 X10. F100", dialect="syntec", emit="canon")
>>> r.ok
True
>>> [ln for ln in r.output.splitlines() if "STRAIGHT_FEED" in ln]
[' N..... STRAIGHT_FEED(10.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)']
"""

from __future__ import annotations

import io
import json
import os
from dataclasses import dataclass, field
from typing import Any

from cncc.driver import Options, Result, compile_files


def compile_text(text: str, *, dialect: str = "syntec", emit: str = "canon", **options: Any) -> Result:
    """Compile ``text`` as if it were a file given on the command line.

    ``options`` are fields of :class:`cncc.driver.Options` (``machine``, ``opt_level``,
    ``strict``, ``dialect_options`` ...).  The result carries the diagnostics
    (``result.sink``), the sources and the output text.
    """
    opts = Options(inputs=["-"], dialect=dialect, emit=emit, **options)
    return compile_files(opts, stdin=io.StringIO(text))


def compile_commands(text: str, *, dialect: str = "syntec", **options: Any) -> tuple[list[Any], Result]:
    """The IR commands after the path passes (program coordinates), and the result."""
    from cncc.diagnostics import DiagnosticSink
    from cncc.driver import front_end, path_passes, resolve_dialect, resolve_machine
    from cncc.source import SourceMap

    opts = Options(inputs=["-"], dialect=dialect, **options)
    sink = DiagnosticSink(werror=opts.werror)
    sources = SourceMap()
    result = Result(sink, sources)
    d = resolve_dialect(opts, sink)
    m = resolve_machine(opts.machine, sink)
    if d is None or m is None:
        return [], result
    src = sources.add("<text>", text)
    cmds = list(path_passes(front_end(src, d, m, opts, sink), d, m, opts, sink))
    return cmds, result


# ---- the typed API ----------------------------------------------------------------------------
@dataclass(frozen=True, slots=True)
class Location:
    """A place in a program: 1-based line and column (characters); ``end_*`` just after the span."""

    file: str | None
    line: int | None
    column: int | None
    end_line: int | None = None
    end_column: int | None = None


@dataclass(frozen=True, slots=True)
class Diagnostic:
    """One diagnostic: ``severity`` is ``"error"``, ``"warning"`` or ``"note"``; ``code`` as in
    docs/diagnostics.md.  ``file``/``line``/``column`` are ``None`` for the command line."""

    file: str | None
    line: int | None
    column: int | None
    end_line: int | None
    end_column: int | None
    severity: str
    code: str
    message: str
    related: tuple[tuple[Location, str], ...] = ()

    def __str__(self) -> str:
        where = f"{self.file}:{self.line}:{self.column}" if self.file is not None else "cncc"
        return f"{where}: {self.severity}: {self.message} [{self.code}]"


@dataclass(frozen=True, slots=True)
class LineTime:
    """The time of one source line (primary column): ``category`` is the kind with the most time."""

    file: str
    line: int
    time_s: float
    category: str
    text: str


@dataclass(frozen=True, slots=True)
class Timing:
    """The cycle time (``--emit=timing``'s primary column, e.g. -O2 on the machine)."""

    total_s: float
    per_line: tuple[LineTime, ...]
    per_tool: dict[int | None, float]  # tool number (None: before the first tool) -> s
    per_category: dict[str, float]  # rapid, feed, arc, dwell, tool_change, spindle, wait, reversal -> s
    nominal_s: float | None  # the -O0 estimate (length / feed), when the report has it
    planner: str
    report: dict[str, Any] = field(repr=False)  # the whole JSON report (cncc/backends/timing/schema.json)

    @staticmethod
    def from_report(doc: dict[str, Any]) -> Timing:
        cols = doc["columns"]
        nominal = doc.get("nominal_column")
        return Timing(
            total_s=float(doc["total_s"]),
            per_line=tuple(LineTime(r["file"], r["line"], r["times_s"][0], r["category"], r["text"])
                           for r in doc["lines"]),
            per_tool={t["tool"]: t["times_s"][0] for t in doc["by_tool"]},
            per_category={k: v["time_s"] for k, v in cols[0]["by_category"].items()},
            nominal_s=None if nominal is None else float(cols[nominal]["total_s"]),
            planner=str(cols[0]["planner"]),
            report=doc)


@dataclass(slots=True)
class CompileResult:
    """What :func:`compile` made.  ``output`` is the emitted text (canon trace, IR, G-code, the
    JSON timing report ...); ``gcode`` the G-code for ``emit="gcode"``; ``timing`` and
    ``trajectory`` (the planned :class:`cncc.ir.trajectory.Trajectory`: numpy arrays, one row
    per constant-jerk phase; ``.sample(t_s)``) for ``emit="timing"``."""

    ok: bool
    diagnostics: list[Diagnostic]
    output: str
    dialect: str | None
    gcode: str | None = None
    timing: Timing | None = None
    trajectory: Any = None
    raw: Result | None = field(default=None, repr=False)  # the driver's result (sink, sources)
    pass_report: str = ""  # print_after dumps and the time_passes table (docs/api.md)

    @property
    def errors(self) -> list[Diagnostic]:
        return [d for d in self.diagnostics if d.severity == "error"]


def _is_path(text_or_path: str | os.PathLike[str]) -> bool:
    if isinstance(text_or_path, os.PathLike):
        return True
    return "\n" not in text_or_path and len(text_or_path) < 4096 and os.path.isfile(text_or_path)


def _diagnostics(result: Result) -> list[Diagnostic]:
    from cncc.diagout import place
    from cncc.render import by_position

    out = []
    for d in by_position(result.sink):
        p = place(result.sources, d.span)
        related = tuple((Location(*_fields(place(result.sources, r.span))), r.message) for r in d.related)
        out.append(Diagnostic(p.file, p.line, p.column, p.end_line, p.end_column, d.severity.label, d.code,
                              d.message, related))
    return out


def _fields(p: Any) -> tuple[Any, ...]:
    return (p.file, p.line, p.column, p.end_line, p.end_column)


def compile(text_or_path: str | os.PathLike[str], dialect: str | None = None, machine: str | None = None,
            emit: str = "canon", **options: Any) -> CompileResult:
    """Compile a program (its text, or a file: a :class:`os.PathLike`, or a ``str`` naming an
    existing file) and return a :class:`CompileResult`.

    ``dialect=None`` guesses it (a modeline and a ``cncc.toml`` beside the file count first,
    as on the command line); ``machine=None`` is ``cncc.toml``'s machine or ``generic-mill``.
    ``emit``: ``canon``, ``ir``, ``gcode``, ``timing`` or ``none``.  ``options`` are fields of
    :class:`cncc.driver.Options` (``target``, ``opt_level``, ``dialect_options``,
    ``include_dirs`` ...).  Never raises on a bad program: look at ``diagnostics``.
    Numerical warnings (numpy) become ``W0909`` diagnostics.
    """
    from cncc.driver import DEFAULT_MACHINE
    from cncc.numwarn import recorded, to_diagnostics

    path = os.fspath(text_or_path) if _is_path(text_or_path) else None
    given = {name for name, value in (("dialect", dialect), ("machine", machine)) if value is not None}
    given |= {k for k in ("target", "opt_level", "offsets_file", "tools_file", "ini_file", "dialect_options")
              if k in options}
    fmt = options.pop("report_format", "json")
    opts = Options(inputs=[path or "-"], dialect=dialect, machine=machine or DEFAULT_MACHINE, emit=emit,
                   project_config=True, given=frozenset(given), keep_trajectory=True,
                   report_format="json" if emit == "timing" else fmt, **options)
    stdin = None if path is not None else io.StringIO(os.fspath(text_or_path))
    with recorded() as caught:
        result = compile_files(opts, stdin=stdin)
    to_diagnostics(caught, result.sink)
    out = CompileResult(ok=result.ok, diagnostics=_diagnostics(result), output=result.output,
                        dialect=next(iter(result.dialects.values()), dialect), raw=result,
                        pass_report=result.pass_report)
    if emit == "gcode":
        out.gcode = result.output
    if emit == "timing" and result.runs and result.output.lstrip().startswith("{"):
        out.timing = Timing.from_report(json.loads(result.output))
        out.trajectory = result.runs[0].trajectory
    return out


def translate(text_or_path: str | os.PathLike[str], target: str, dialect: str | None = None,
              **options: Any) -> CompileResult:
    """The program written in the dialect ``target`` (``result.gcode``; docs/translation.md)."""
    return compile(text_or_path, dialect=dialect, emit="gcode", target=target, **options)


def time(text_or_path: str | os.PathLike[str], dialect: str | None = None, machine: str | None = None,
         opt_level: int = 2, **options: Any) -> CompileResult:
    """The cycle time on ``machine`` at planner level ``opt_level`` (``result.timing``,
    ``result.trajectory``; docs/timing.md)."""
    return compile(text_or_path, dialect=dialect, machine=machine, emit="timing", opt_level=opt_level, **options)
