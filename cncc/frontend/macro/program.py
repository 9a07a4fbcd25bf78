"""Program units: a parsed file with its labels, O sections and loop structure.

A :class:`Unit` holds the blocks of one source file (main program or a file found
on the ``-I`` path) with the indexes the executor jumps by:

* ``labels``: sequence number -> block indexes (``N100`` ...);
* ``sections``: program name -> index of its ``O`` block (``O1000`` -> "1000");
* ``loop_end`` / ``loop_start``: matching ``WHILE ... DO n`` and ``END n``;
* ``if_next`` / ``if_end``: the next branch and the ``ENDIF`` of block IFs (SZGH).

Structure errors (loops that cross, END without DO ...) are found once, when the
file is loaded, and reported as diagnostics.

:class:`ProgramLibrary` finds called programs: first an ``O`` section of the
calling file, then the other loaded files, then files in the ``-I`` folders
(``O1234.nc``, ``O1234``, ``1234``, ``1234.nc``, a named file, ``sub/1390``).
"""

from __future__ import annotations

import bisect
import itertools
import os
from collections.abc import Callable
from dataclasses import dataclass, field

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink
from cncc.frontend.syntax import Block, Else, ElseIf, EndIf, EndLoop, IfBlock, While
from cncc.source import SourceFile, Span

MAX_LOOP_NESTING = 3


def program_key(value: float | str) -> str:
    """The lookup key of a program: numbers without leading zeros, names upper-case."""
    if isinstance(value, str):
        text = value.strip()
        if text.upper().startswith("O") and text[1:].isdigit():
            text = text[1:]
        return str(int(text)) if text.isdigit() else text.upper()
    return str(int(value))


@dataclass(slots=True)
class Unit:
    source: SourceFile
    blocks: list[Block]
    labels: dict[int, list[int]] = field(default_factory=dict)
    sections: dict[str, int] = field(default_factory=dict)
    section_starts: list[int] = field(default_factory=list)
    loop_end: dict[int, int] = field(default_factory=dict)
    loop_start: dict[int, int] = field(default_factory=dict)
    if_next: dict[int, int] = field(default_factory=dict)  # IF/ELIF/ELSE index -> next branch or ENDIF
    if_end: dict[int, int] = field(default_factory=dict)  # IF/ELIF/ELSE index -> its ENDIF
    bad_loops: set[int] = field(default_factory=set)  # END blocks without a matching DO

    def span(self, start: int, end: int) -> Span:
        return Span(self.source.source_id, start, end)

    def section_range(self, index: int) -> tuple[int, int]:
        """The [first, last) block range of the O section containing block ``index``."""
        starts = self.section_starts
        k = bisect.bisect_right(starts, index) - 1
        first = starts[k] if k >= 0 else 0
        last = starts[k + 1] if k + 1 < len(starts) else len(self.blocks)
        return first, last

    def find_label(self, n: int, current: int) -> int | None:
        """Block of ``N n``: forward from ``current`` in its section, then from the
        section start, then anywhere in the file (the first one)."""
        found = self.labels.get(n)
        if not found:
            return None
        first, last = self.section_range(current)
        for i in found:
            if current <= i < last:
                return i
        for i in found:
            if first <= i < last:
                return i
        return found[0]


def _n_value(block: Block) -> int | None:
    for w in block.words:
        if w.letter == "N" and w.expr is None:
            return int(w.value)
    return None


def _o_value(block: Block) -> str | None:
    for w in block.words:
        if w.letter == "O" and w.expr is None:
            return program_key(w.value)
    return None


def build_unit(source: SourceFile, blocks: list[Block], sink: DiagnosticSink) -> Unit:
    """Index ``blocks`` and check their loop and IF structure."""
    unit = Unit(source, blocks)
    for i, b in enumerate(blocks):
        n = _n_value(b)
        if n is not None:
            unit.labels.setdefault(n, []).append(i)
        o = _o_value(b)
        if o is not None:
            unit.sections.setdefault(o, i)
            unit.section_starts.append(i)
    bounds = [0, *unit.section_starts, len(blocks)]
    for first, last in itertools.pairwise(bounds):
        _check_loops(unit, first, last, sink)
        _check_ifs(unit, first, last, sink)
    return unit


def _check_loops(unit: Unit, first: int, last: int, sink: DiagnosticSink) -> None:
    stack: list[tuple[int, int, int, int]] = []  # (loop id, block index, start, end)
    for i in range(first, last):
        for st in unit.blocks[i].statements:
            if isinstance(st, While):
                if not 1 <= st.loop_id <= MAX_LOOP_NESTING:
                    sink.emit(dg.MACRO_LOOP_MISMATCH, unit.span(st.start, st.end),
                              f"loop number DO {st.loop_id} is out of range (1 to {MAX_LOOP_NESTING})")
                if len(stack) >= MAX_LOOP_NESTING:
                    sink.emit(dg.MACRO_LOOP_MISMATCH, unit.span(st.start, st.end),
                              f"WHILE loops nested deeper than {MAX_LOOP_NESTING}")
                stack.append((st.loop_id, i, st.start, st.end))
            elif isinstance(st, EndLoop):
                ids = [s[0] for s in stack]
                if stack and stack[-1][0] == st.loop_id:
                    _, w, _, _ = stack.pop()
                    unit.loop_end[w] = i
                    unit.loop_start[i] = w
                elif st.loop_id in ids:
                    k = len(ids) - 1 - ids[::-1].index(st.loop_id)
                    inner = stack[-1]
                    sink.emit(dg.MACRO_LOOP_MISMATCH, unit.span(st.start, st.end),
                              f"END {st.loop_id} closes DO {st.loop_id} while the inner DO {inner[0]} is still open "
                              f"(loops must not cross)")
                    _, w, _, _ = stack[k]
                    unit.loop_end[w] = i
                    unit.loop_start[i] = w
                    del stack[k:]
                else:
                    unit.bad_loops.add(i)
                    sink.emit(dg.MACRO_END_WITHOUT_DO, unit.span(st.start, st.end),
                              f"END {st.loop_id} has no WHILE ... DO {st.loop_id} before it")
    for loop_id, _, start, end in stack:
        sink.emit(dg.MACRO_LOOP_MISMATCH, unit.span(start, end), f"DO {loop_id} has no END {loop_id}")


def _check_ifs(unit: Unit, first: int, last: int, sink: DiagnosticSink) -> None:
    stack: list[list[int]] = []  # branch block indexes of each open IF
    for i in range(first, last):
        for st in unit.blocks[i].statements:
            if isinstance(st, IfBlock):
                stack.append([i])
            elif isinstance(st, ElseIf | Else):
                if not stack:
                    name = "ELSE" if isinstance(st, Else) else "ELIF"
                    sink.emit(dg.MACRO_IF_STRUCTURE, unit.span(st.start, st.end), f"{name} without IF")
                    continue
                stack[-1].append(i)
            elif isinstance(st, EndIf):
                if not stack:
                    sink.emit(dg.MACRO_IF_STRUCTURE, unit.span(st.start, st.end), "ENDIF without IF")
                    continue
                branches = stack.pop()
                for a, b in zip(branches, [*branches[1:], i], strict=True):
                    unit.if_next[a] = b
                    unit.if_end[a] = i
    for branches in stack:
        blk = unit.blocks[branches[0]]
        sink.emit(dg.MACRO_IF_STRUCTURE, unit.span(blk.start, blk.end), "IF without ENDIF")


Loader = Callable[[str], SourceFile | None]


@dataclass(slots=True)
class ProgramLibrary:
    """The loaded units and the ``-I`` search path."""

    parse: Callable[[SourceFile], list[Block]]
    sink: DiagnosticSink
    include_dirs: tuple[str, ...] = ()
    extensions: tuple[str, ...] = (".nc",)
    load_source: Loader | None = None
    units: list[Unit] = field(default_factory=list)
    files_used: list[str] = field(default_factory=list)
    run_files: tuple[str, ...] = ()  # the run's other inputs, searched after the -I folders
    _by_path: dict[str, Unit | None] = field(default_factory=dict)

    def add(self, source: SourceFile) -> Unit:
        unit = build_unit(source, self.parse(source), self.sink)
        self.units.append(unit)
        return unit

    def find(self, key: str, caller: Unit, text: str = "") -> tuple[Unit, int] | None:
        """The unit and first block index of program ``key`` (see :func:`program_key`);
        ``text`` is the name as written (file names keep their case)."""
        if key in caller.sections:
            return caller, caller.sections[key]
        for unit in self.units:
            if key in unit.sections:
                return unit, unit.sections[key]
        for path in self._candidates(key, text or key):
            loaded = self._load(path)
            if loaded is not None:
                return loaded, loaded.sections.get(key, 0)
        here = os.path.realpath(caller.source.name)
        for path in self.run_files:
            if path == "-" or not os.path.isfile(path) or os.path.realpath(path) == here:
                continue
            loaded = self._load(path)
            if loaded is not None and key in loaded.sections:
                return loaded, loaded.sections[key]
        return None

    def _candidates(self, key: str, text: str) -> list[str]:
        names: list[str] = []
        if key.isdigit():
            n = int(key)
            bases = [f"O{n:04d}", f"O{n}", f"{n:04d}", f"{n}", f"o{n:04d}"]
        else:
            bases = [text, key, text.lower()]
        for base in dict.fromkeys(bases):
            names.append(base)
            names.extend(base + ext for ext in self.extensions if ext)
        out = []
        for folder in self.include_dirs:
            for name in names:
                path = os.path.join(folder, *name.split("/"))
                if os.path.isfile(path):
                    out.append(path)
        return out

    def _load(self, path: str) -> Unit | None:
        real = os.path.realpath(path)
        if real in self._by_path:
            return self._by_path[real]
        unit: Unit | None = None
        if self.load_source is not None:
            src = self.load_source(path)
            if src is not None:
                unit = self.add(src)
                self.files_used.append(path)
        self._by_path[real] = unit
        return unit
