"""Writing an output file the way a Unix tool does (``-o PATH``).

Consumes a path and a function that streams bytes into a binary file; produces the
file.  Two cases, chosen by what ``PATH`` is *now*:

* a **regular file** (or nothing yet): the bytes go to a temporary file beside the
  target, which then replaces it with ``os.replace``, so a reader never sees half a
  file and a failed run leaves the old file alone.  A new file gets ``0666 & ~umask``
  (as ``open(..., "w")`` would give it); an overwritten file keeps its mode.  A symbolic
  link to a regular file is followed: the link stays, its target is replaced.
* anything else — a FIFO, a character or block device (``/dev/null``), a terminal,
  ``/dev/stdout``, a process substitution (``/dev/fd/63``) — is **written in place**:
  it is opened for writing and never replaced, removed or re-created.

In both cases the bytes are produced first (in memory-light form: a temporary file) and
only reach the target when ``keep()`` says yes, so a run that reported errors writes
nothing.

:func:`write_stream` and :func:`write_output` are the compiler's way in (the driver, the
command line): never over an input file, problems reported as diagnostics.
"""

from __future__ import annotations

import os
import shutil
import stat
import sys
import tempfile
from collections.abc import Callable
from typing import IO, Any, TextIO

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink
from cncc.source import NO_SPAN

CHUNK_BYTES = 1 << 16


def current_umask() -> int:
    """The process umask (read by setting it and putting it back)."""
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def is_special(path: str) -> bool:
    """True when ``path`` exists and is not a regular file (symbolic links followed)."""
    try:
        st = os.stat(path)
    except FileNotFoundError:
        return False
    return not stat.S_ISREG(st.st_mode)


def write_file(path: str, write: Callable[[IO[bytes]], Any], keep: Callable[[], bool]) -> bool:
    """Stream ``write(fh)`` into ``path``; return False (writing nothing) when ``keep()`` is False.

    Raises OSError when the path cannot be written.
    """
    if is_special(path):
        return _write_in_place(path, write, keep)
    return _write_atomic(os.path.realpath(path), write, keep)


def _write_in_place(path: str, write: Callable[[IO[bytes]], Any], keep: Callable[[], bool]) -> bool:
    with tempfile.TemporaryFile() as buf:
        write(buf)
        if not keep():
            return False
        buf.seek(0)
        # No O_CREAT and no O_TRUNC games: the node exists and stays what it is.
        with open(path, "wb", buffering=0) as out:
            shutil.copyfileobj(buf, out, CHUNK_BYTES)
    return True


def _write_atomic(real: str, write: Callable[[IO[bytes]], Any], keep: Callable[[], bool]) -> bool:
    try:
        mode = stat.S_IMODE(os.stat(real).st_mode)
    except FileNotFoundError:
        mode = 0o666 & ~current_umask()
    fd, tmp = tempfile.mkstemp(prefix=".cncc-", suffix=".tmp", dir=os.path.dirname(real) or ".")
    try:
        with os.fdopen(fd, "wb") as fh:
            write(fh)
        if not keep():
            os.unlink(tmp)
            return False
        os.chmod(tmp, mode)
        os.replace(tmp, real)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return True


def write_stream(path: str, inputs: list[str], sink: DiagnosticSink, write: Callable[[IO[bytes]], Any],
                 keep_on_errors: bool = False) -> bool:
    """Stream ``write(binary file)`` into ``path`` (atomically for regular files, in place for devices and
    FIFOs: :func:`write_file`); nothing is kept if errors were reported (unless ``keep_on_errors``)."""
    real = os.path.realpath(path)
    if any(inp != "-" and os.path.exists(inp) and os.path.realpath(inp) == real for inp in inputs):
        sink.emit(dg.OUTPUT_IS_INPUT, NO_SPAN, f"refusing to overwrite the input file {path}")
        return False
    try:
        return write_file(path, write, lambda: keep_on_errors or not sink.has_errors)
    except OSError as exc:
        sink.emit(dg.CANNOT_WRITE, NO_SPAN, f"cannot write {path}: {exc.strerror or exc}")
        return False


def write_output(text: str, path: str | None, inputs: list[str], sink: DiagnosticSink,
                 stdout: TextIO | None = None) -> bool:
    """Write ``text`` to ``path`` (``-``/None: stdout) through :func:`write_stream`; never over an input."""
    if path is None or path == "-":
        (stdout or sys.stdout).write(text)
        return True
    return write_stream(path, inputs, sink, lambda fh: fh.write(text.encode("utf-8")))


__all__ = ["current_umask", "is_special", "write_file", "write_output", "write_stream"]
