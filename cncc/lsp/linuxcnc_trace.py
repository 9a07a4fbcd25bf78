"""The LinuxCNC front end with the server's variable trace attached (for hover).

:func:`cncc.frontend.lower` runs LinuxCNC programs on
:class:`~cncc.frontend.linuxcnc.executor.LinuxcncExecutor`, which has no per-block
hook.  For the editor, :func:`lower_traced` builds the same executor the same way
(``run_linuxcnc``) and wraps its one-block step so that the trace samples, for every
parameter reference of a block of the document -- ``#<name>`` and ``#n`` -- the
value before the block runs (an assignment's target: after it).  The commands and
diagnostics are the executor's own; ``tests/lsp/test_linuxcnc_subs.py`` compares
them with ``lower``'s.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from typing import Any

from cncc.diagnostics import DiagnosticSink
from cncc.dialects import Dialect
from cncc.ir import Command
from cncc.lsp.scan import Comments, code_part
from cncc.lsp.trace import VariableTrace
from cncc.source import SourceFile

_REF_RE = re.compile(r"#\s*(?:<(?P<name>[^>]*)>|(?P<num>\d+))(?P<assign>\s*=(?!=))?")
_COMMENTS = Comments(paren=True, slash=False, semi=True)

Plan = tuple[tuple[int, "str | int", bool], ...]  # (offset of '#', name or number, assignment target)


def plan_of(text: str, start: int, end: int) -> Plan:
    """The parameter references in ``text[start:end]`` (one block), outside comments."""
    line = text[start:end]
    out = []
    for lo, hi in code_part(line, _COMMENTS):
        for m in _REF_RE.finditer(line, lo, hi):
            key: str | int = "".join(m.group("name").split()).lower() if m.group("name") is not None \
                else int(m.group("num"))
            out.append((start + m.start(), key, m.group("assign") is not None))
    return tuple(out)


def lower_traced(src: SourceFile, dialect: Dialect, sink: DiagnosticSink, iopts: Any, macro: Any,
                 trace: VariableTrace) -> Iterator[Command]:
    from cncc.frontend.interp import Interpreter
    from cncc.frontend.linuxcnc.executor import LinuxcncExecutor
    from cncc.frontend.parser import ParseOptions, Parser

    parser = Parser(dialect, sink, ParseOptions(strict=iopts.strict))
    interp = Interpreter(dialect, sink, src.source_id, iopts)
    dirs = tuple(getattr(macro, "include_dirs", ()) or ())
    steps = int(getattr(macro, "max_steps", 5_000_000) or 5_000_000)
    ex = LinuxcncExecutor(dialect, sink, interp, parser, dirs, steps)
    step = ex._step
    plans: dict[int, Plan] = {}
    text = src.text
    trace.ran = True

    def sample(params: Any, plan: Plan, after: bool) -> None:
        for at, key, target in plan:
            if target != after:
                continue
            value = params.lookup(key) if isinstance(key, str) else params.read_number(key)
            trace.record(at, value)

    def traced(fr: Any) -> None:
        blocks = fr.index.blocks
        if fr.pc >= len(blocks) or fr.index.src.source_id != src.source_id:
            step(fr)
            return
        block = blocks[fr.pc]
        plan = plans.get(block.start)
        if plan is None:
            plan = plans[block.start] = plan_of(text, block.start, block.end)
        if plan:
            sample(ex.params, plan, False)
        step(fr)
        if plan:
            sample(ex.params, plan, True)

    ex._step = traced  # type: ignore[method-assign]
    return ex.run(src)
