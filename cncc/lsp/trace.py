"""Variable values seen while the analysis runs the program (for hover).

The macro executor calls a :class:`VariableTrace` before and after every block it
runs (``MacroOptions.trace``).  For each variable reference ``#n`` in a block of the
document (a constant number, a local or common variable), the trace keeps what it
saw there: the last value, the smallest and largest, and how many passes saw a
value or a vacant variable.  Reads are sampled before the block runs (the words
and conditions see those values); an assignment's target after it.  So a hover
inside a loop, after a jump or in a subprogram shows what the program really
computed there, not what a top-to-bottom reading suggests.

Memory is bounded: one small record per reference site of the document
(:data:`MAX_SITES` at most); a site seen a million times still costs one record.
"""

from __future__ import annotations

from dataclasses import dataclass, fields, is_dataclass
from typing import Any

MAX_SITES = 100_000
KINDS = ("local", "common")  # system variables may have side effects when read; not sampled

Site = tuple[int, int]  # (offset of '#', variable number)


@dataclass(slots=True)
class Seen:
    """What one reference site saw over all the passes of the run."""

    last: float | None = None
    lo: float = float("inf")
    hi: float = float("-inf")
    values: int = 0  # passes that saw a value
    vacant: int = 0  # passes that saw the variable vacant

    def add(self, value: float | None) -> None:
        self.last = value
        if value is None:
            self.vacant += 1
            return
        self.values += 1
        if value < self.lo:
            self.lo = value
        if value > self.hi:
            self.hi = value

    @property
    def passes(self) -> int:
        return self.values + self.vacant


class VariableTrace:
    """The executor's per-block hook; ``sites`` maps the offset of a ``#`` to what it saw."""

    def __init__(self, source_id: int = 0, max_sites: int = MAX_SITES) -> None:
        self.source_id = source_id
        self.max_sites = max_sites
        self.sites: dict[int, Seen] = {}
        self.ran = False  # the executor ran (else the program had no macro features)
        self._plans: dict[int, tuple[tuple[Site, ...], tuple[Site, ...]]] = {}

    def __call__(self, ex: Any, block: Any, after: bool) -> None:
        self.ran = True
        if ex.it.source_id != self.source_id:
            return
        plan = self._plans.get(block.start)
        if plan is None:
            plan = self._plans[block.start] = _plan(block, ex.vars.layout)
        todo = plan[1] if after else plan[0]
        if not todo:
            return
        read = ex.vars.read
        sites = self.sites
        for at, n in todo:
            seen = sites.get(at)
            if seen is None:
                if len(sites) >= self.max_sites:
                    continue
                seen = sites[at] = Seen()
            seen.add(read(n))

    def record(self, at: int, value: float | None) -> None:
        """One pass of the reference whose ``#`` is at offset ``at`` saw ``value``."""
        seen = self.sites.get(at)
        if seen is None:
            if len(self.sites) >= self.max_sites:
                return
            seen = self.sites[at] = Seen()
        seen.add(value)

    def at(self, offset: int) -> Seen | None:
        return self.sites.get(offset)


def _plan(block: Any, layout: Any) -> tuple[tuple[Site, ...], tuple[Site, ...]]:
    """(sites read before the block, assignment targets read after it)."""
    from cncc.frontend.syntax import Assign, Num, Var

    reads: list[Site] = []
    targets: list[Site] = []

    def site(v: Var) -> Site | None:
        if v.name or not isinstance(v.index, Num):
            return None
        n = round(v.index.value)
        return (v.start, n) if layout.kind(n) in KINDS else None

    def walk(node: object) -> None:
        if isinstance(node, Var):
            s = site(node)
            if s is not None:
                reads.append(s)
            if node.index is not None:
                walk(node.index)
            return
        if isinstance(node, Assign):
            s = site(node.target)
            if s is not None:
                targets.append(s)
            if node.target.index is not None:
                walk(node.target.index)
            walk(node.expr)
            return
        if isinstance(node, tuple | list):
            for x in node:
                walk(x)
            return
        if is_dataclass(node) and not isinstance(node, type):
            for f in fields(node):
                value = getattr(node, f.name)
                if isinstance(value, tuple | list) or is_dataclass(value):
                    walk(value)

    walk(block.words)
    walk(block.statements)
    return tuple(reads), tuple(targets)
