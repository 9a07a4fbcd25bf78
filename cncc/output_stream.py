"""Streaming a compilation's output as it is made (the command line's way to compile).

:func:`compile_to` runs :func:`cncc.driver.compile_files` with an ``out`` that gathers the
backend's pieces into blocks of about :attr:`Pieces.BLOCK` characters and writes each block to
standard output, or to ``-o FILE`` through :func:`cncc.outfile.write_stream` -- peak memory
holds a block of the output, not all of it.  :func:`streams_output` says when the command line
may do so.
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from typing import IO, Any, TextIO

from cncc.diagnostics import DiagnosticSink
from cncc.driver import Options, Result, compile_files, new_sink, writes_own_output
from cncc.outfile import write_stream


class Pieces:
    """The output pieces, passed on to ``out`` in blocks of about ``BLOCK`` characters, so that
    memory holds one block, not the output."""

    BLOCK = 1 << 16

    def __init__(self, out: Callable[[str], Any]) -> None:
        self.out, self.size = out, 0
        self.parts: list[str] = []

    def add(self, piece: str) -> None:
        self.parts.append(piece)
        self.size += len(piece)
        if self.size >= self.BLOCK:
            self.out("".join(self.parts))
            self.parts.clear()
            self.size = 0

    def finish(self) -> None:
        text = "".join(self.parts)
        self.parts, self.size = [], 0
        if text:
            self.out(text)


def streams_output(opts: Options) -> bool:
    """True when the command line may stream the output as it is made (:func:`compile_to`)."""
    return not (opts.syntax_only or opts.list_deps or writes_own_output(opts))


def _compile_into(opts: Options, out: Callable[[str], Any], sink: DiagnosticSink) -> Result:
    pieces = Pieces(out)
    result = compile_files(opts, out=pieces.add, sink=sink)
    pieces.finish()
    return result


def compile_to(opts: Options, stdout: TextIO | None = None) -> tuple[Result, bool]:
    """Compile and write the output as it is made: to standard output, or to ``opts.output``
    through :func:`write_stream` (a regular file atomically: a temporary file renamed into place
    when no error was reported; a device or FIFO in place) -- peak memory holds a block of the
    output, not all of it.  (Result, whether the output was written)."""
    sink = new_sink(opts)
    path = opts.output
    if path in (None, "-"):
        stream = stdout or sys.stdout
        return _compile_into(opts, stream.write, sink), True
    done: list[Result] = []

    def write(fh: IO[bytes]) -> None:
        done.append(_compile_into(opts, lambda text: fh.write(text.encode("utf-8")), sink))

    written = write_stream(path, opts.inputs, sink, write)
    if not done:  # refused or not writable before compiling: compile for the diagnostics alone
        done.append(compile_files(opts, out=lambda text: None, sink=sink))
    return done[0], written
