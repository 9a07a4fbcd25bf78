"""Kept subprograms (``--keep-subprograms``): called programs written once and called.

Consumes the emitter's lines with marker lines where each run of a called program
began and ended (the macro executor's ``CallBoundary`` records,
passed through by the emitter); produces the program with each called program that
the target can call written once, as its own section, and called:

* a program is kept when every run of it wrote the same blocks (text equality after
  the programs it calls were themselves kept or flattened).  The blocks are what the
  flattened output would have had at each call, so replacing every run by a call of
  one copy moves the target exactly as the flattened program does.  A body whose
  blocks depend on where or how it is called (absolute coordinates that differ, a
  macro's arguments, a feed already in force at one call only) is written flattened
  with note N0808;
* the target's form: ``M98 P<n>`` and ``O<n> ... M99`` sections after the main
  program (the ``subprogram_call``/``subprogram_return`` codes of the target), or
  LinuxCNC's ``o<n> sub ... o<n> endsub`` before it (``[emit] subprogram_form =
  "oword"``); a target with neither (grbl) gets the flattened program and N0808;
* program numbers: the source's number where it lies in the target's range
  (``[emit] program_numbers``), else the next free one with warning W0813; nesting
  deeper than the target's ``max_call_depth`` flattens the innermost levels with
  warning W0814.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from cncc import diagnostics as dg
from cncc.ir import CallBoundary, Command

if TYPE_CHECKING:
    from cncc.backends.gcode.emit import GcodeEmitter
    from cncc.backends.gcode.writer import BlockWriter

_MARK = "\x00call"
NO_INCREMENTAL = "\x00absolute only\n"  # a block inside a call that has no incremental form


def marker(begin: bool, index: int) -> str:
    return f"{_MARK} {'begin' if begin else 'end'} {index}\n"


@dataclass(slots=True)
class Run:
    """One run of a called program: its lines, with the runs it made in place."""

    key: str
    index: int  # into BlockWriter.calls
    parts: list[tuple[str, str] | Run] = field(default_factory=list)  # (absolute, incremental) lines
    closed: bool = False


def _tree(lines: Iterable[str]) -> tuple[Run, dict[str, list[Run]]]:
    root = Run("", -1)
    stack = [root]
    by_key: dict[str, list[Run]] = {}
    for line in lines:
        if not line.startswith(_MARK):
            pair = line.splitlines(keepends=True)
            stack[-1].parts.append((pair[0], pair[1]) if len(stack) > 1 and len(pair) == 2 else (line, line))
            continue
        what, index = line.split()[1:3]
        if what == "begin":
            run = Run("", int(index))
            stack[-1].parts.append(run)
            stack.append(run)
        elif len(stack) > 1:
            stack.pop().closed = True
    return root, by_key


class Writer:
    """Decides which programs are kept and writes the main program and the sections."""

    def __init__(self, em: GcodeEmitter, root: Run) -> None:
        self.em = em
        self.t = em.t
        self.root = root
        self.by_key: dict[str, list[Run]] = {}
        self._index(root, ())
        self.kept: dict[str, bool] = {}
        self.incremental: set[str] = set()  # kept programs written in G91
        self.numbers: dict[str, int] = {}
        self.form = str(self.t.dialect.raw.get("emit", {}).get("subprogram_form", "m98"))
        if self.form == "m98" and not (self.t.has("subprogram_call") and self.t.has("subprogram_return")):
            self.form = ""

    def _index(self, run: Run, keys: tuple[str, ...]) -> None:
        for p in run.parts:
            if isinstance(p, Run):
                p.key = self.em.calls[p.index][0]
                runs = self.by_key.setdefault(p.key, [])
                runs.append(p)
                if p.key in keys:  # recursion: the body contains a call of itself
                    self.kept[p.key] = False
                self._index(p, (*keys, p.key))

    # ---- decisions ---------------------------------------------------------------------------
    def is_kept(self, key: str) -> bool:
        found = self.kept.get(key)
        if found is not None:
            return found
        self.kept[key] = False  # while deciding (a cycle of calls stays flattened)
        runs = self.by_key[key]
        ok = all(r.closed for r in runs) and bool(self.text(runs[0]).strip())
        if ok and len({self.text(r) for r in runs}) > 1:
            inc = {self.text(r, True) for r in runs}
            ok = len(inc) == 1 and NO_INCREMENTAL not in inc.pop() and bool(self.t.code("incremental"))
            if ok:
                self.incremental.add(key)
        self.kept[key] = ok
        if not ok:
            self.note(runs[0], f"{self.name(key)} is written flattened: its calls do not write the same "
                               "blocks (the body depends on where or how it is called)")
        return ok

    def text(self, run: Run, inc: bool = False) -> str:
        """The run's blocks (``inc``: in their incremental form), kept calls as call blocks."""
        return "".join(p[inc] if isinstance(p, tuple) else self.call_or_body(p, inc) for p in run.parts)

    def call_or_body(self, run: Run, inc: bool) -> str:
        if not self.is_kept(run.key):
            return self.text(run, inc)
        back = self.em.block([self.t.code("incremental")]) if inc else ""  # the section ends in G90
        return self.call_line(run.key) + back

    def height(self, key: str) -> int:
        """Kept levels in ``key``'s body including itself."""
        run = self.by_key[key][0]
        return 1 + max((self.height(k) for k in self._children(run)), default=0)

    def _children(self, run: Run) -> set[str]:
        out: set[str] = set()
        for p in run.parts:
            if isinstance(p, Run):
                out |= {p.key} if self.kept.get(p.key) else self._children(p)
        return out

    def limit_depth(self) -> None:
        limit = max(1, self.t.max_call_depth)
        while True:
            top = self._children(self.root)
            depth = max((self.height(k) for k in top), default=0)
            if depth <= limit:
                return
            leaves = [k for k, v in self.kept.items() if v and not self._children(self.by_key[k][0])]
            run = self.by_key[leaves[0]][0]
            self.warn(dg.XL_NESTING, run, f"subprograms nest {depth} deep; {self.t.name} calls at most "
                                          f"{limit} deep: the innermost level is written flattened")
            for k in leaves:
                self.kept[k] = False

    def number(self) -> None:
        low, high = self.t.program_numbers
        used: set[int] = set()
        wanted: list[tuple[str, int | None]] = []
        for key in self.by_key:
            if not self.kept.get(key):
                continue
            digits = "".join(ch for ch in self.name(key) if ch.isdigit())
            n = int(digits) if digits and self.name(key).upper().startswith(("O", "P")) else None
            if n is not None and low <= n <= high and n not in used:
                self.numbers[key] = n
                used.add(n)
            else:
                wanted.append((key, n))
        free = (n for n in range(low, high + 1) if n not in used)
        for key, n in wanted:
            new = next(free, None)
            if new is None:
                self.kept[key] = False
                self.warn(dg.XL_PROGRAM_NUMBER, self.by_key[key][0], f"no free program number in {low}-{high} "
                                                                     f"for {self.name(key)}: written flattened")
                continue
            self.numbers[key] = new
            used.add(new)
            if n is not None:
                self.warn(dg.XL_PROGRAM_NUMBER, self.by_key[key][0], f"{self.name(key)} is outside "
                                                                     f"{self.t.name}'s program numbers {low}-{high}: "
                                                                     f"written as {new}")

    # ---- text --------------------------------------------------------------------------------
    def name(self, key: str) -> str:
        return self.em.calls[self.by_key[key][0].index][1] or key

    def call_line(self, key: str) -> str:
        n = self.numbers.get(key, 0)
        if self.form == "oword":
            return f"o{n} call\n"
        return self.em.block([self.t.code("subprogram_call"), f"P{n}"])

    def section(self, key: str) -> list[str]:
        n = self.numbers[key]
        inc = key in self.incremental
        body = self.em.block([self.t.code("incremental" if inc else "absolute")])
        body += self.text(self.by_key[key][0], inc)
        if inc:
            body += self.em.block([self.t.code("absolute")])
        if self.form == "oword":
            return [f"o{n} sub\n", body, f"o{n} endsub\n"]
        return [f"O{n:04d}\n", body, self.em.block([self.t.code("subprogram_return")])]

    def note(self, run: Run, message: str) -> None:
        self.warn(dg.XL_SUBPROGRAMS, run, message)

    def warn(self, code: str, run: Run, message: str) -> None:
        sink = self.em.sink
        if sink is None:
            return
        span = self.em.calls[run.index][2] if run.index >= 0 else None
        severity = dg.Severity.ERROR if sink.werror and dg.CODES[code].severity is dg.Severity.NOTE else None
        sink.emit(code, span, message, severity=severity)  # type: ignore[arg-type]

    def write(self) -> Iterator[str]:
        if not self.by_key:
            yield from (p[0] for p in self.root.parts if isinstance(p, tuple))
            return
        if not self.form:
            run = self.by_key[next(iter(self.by_key))][0]
            self.note(run, f"{self.t.name} cannot call subprograms: the output is flattened")
            self.kept = dict.fromkeys(self.by_key, False)
        for key in self.by_key:
            self.is_kept(key)
        self.limit_depth()
        self.number()
        main = self.text(self.root)
        sections = [line for key in self.by_key if self.kept.get(key) for line in self.section(key)]
        head, tail = ("%\n", "%\n") if self.t.percent else ("", "")
        body = main[len(head):len(main) - len(tail)] if head and main.startswith(head) and main.endswith(tail) \
            else main
        if self.form == "oword":
            yield from (head, *sections, body, tail)
        else:
            yield from (head, body, *sections, tail)


def incremental_form(em: BlockWriter, words: list[str], comment: str) -> str:
    """The block written with incremental axis words (a poisoned line when it has none)."""
    pair, em.inc_words = em.inc_words, None
    poison, em.inc_poison = em.inc_poison or em.sync_poison, False
    if poison:
        return NO_INCREMENTAL
    if pair is not None:
        swap = dict(zip(*pair, strict=True))
        words = [swap.get(w, w) for w in words]
    em.in_alt = True
    try:
        return em.block(words, comment)
    finally:
        em.in_alt = False


def call_marker(em: BlockWriter, cmd: CallBoundary) -> str:
    """A marker line (not program text) where a called program's run begins or ends."""
    begin = cmd.begin
    if begin:
        em.calls.append((cmd.key, cmd.name, cmd.span))
        em.call_depth += 1
        em.feed = None  # every run writes its first F and all of X Y Z in its first move: what was in
        em.all_axes = True  # force at one call only must not make the runs' blocks differ
    else:
        em.call_depth = max(0, em.call_depth - 1)
    return marker(begin, len(em.calls) - 1 if begin else -1)


def keep_subprograms(em: GcodeEmitter, cmds: Iterable[Command]) -> Iterator[str]:
    """The emitter's output with kept subprograms (the whole program is read first)."""
    root, _ = _tree(em.emit(cmds))
    yield from Writer(em, root).write()
