"""The Python API for pipelines: compile program text without the command line.

>>> from cncc.api import compile_text
>>> r = compile_text("G01 X10. F100", dialect="syntec", emit="canon")
>>> r.ok
True
>>> [ln for ln in r.output.splitlines() if "STRAIGHT_FEED" in ln]
[' N..... STRAIGHT_FEED(10.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)']
"""

from __future__ import annotations

import io
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
