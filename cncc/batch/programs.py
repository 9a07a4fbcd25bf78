"""The programs of a library: folders, glob patterns and files -> tasks (one per program x machine)."""

from __future__ import annotations

import glob
import os
import re
from collections.abc import Iterator, Mapping, Sequence

from cncc.batch.options import RowOptions, Task

PROGRAM_EXTENSIONS = frozenset({
    ".nc", ".ngc", ".tap", ".cnc", ".gcode", ".gc", ".g", ".mpf", ".spf", ".fnc", ".iso", ".eia", ".min",
    ".ptp", ".txt", ".nci", ".pim", ".h",
})
"""What a folder walk takes (a glob pattern or a file name takes any file)."""
_FANUC_NAME = re.compile(r"^O\d+$", re.I)  # Fanuc-style program files have no extension


def is_program_name(name: str) -> bool:
    ext = os.path.splitext(name)[1].lower()
    return ext in PROGRAM_EXTENSIONS or bool(_FANUC_NAME.match(name))


def find_programs(inputs: Sequence[str]) -> list[str]:
    """Program files under the folders, matching the patterns, or named; sorted, each once."""
    found: dict[str, str] = {}
    for item in inputs:
        if os.path.isdir(item):
            paths: Iterator[str] = _walk(item)
        elif os.path.isfile(item):
            paths = iter((item,))
        else:
            paths = (p for p in glob.iglob(item, recursive=True) if os.path.isfile(p))
        for p in paths:
            found.setdefault(os.path.realpath(p), os.path.normpath(p))
    return sorted(found.values())


def _walk(top: str) -> Iterator[str]:
    for folder, dirs, files in os.walk(top):
        dirs[:] = sorted(d for d in dirs if not d.startswith("."))
        for name in sorted(files):
            if is_program_name(name) and not name.startswith("."):
                yield os.path.join(folder, name)


def read_program(path: str) -> str:
    from cncc.driver import decode

    with open(path, "rb") as fh:
        return decode(fh.read())


def make_tasks(paths: Sequence[str], machines: Sequence[str], options: RowOptions | Mapping[str, RowOptions],
               dialect: str | None = None) -> Iterator[Task]:
    """One task per program and machine; ``options`` per machine name or for all; ``dialect`` None:
    guessed per program (as the driver does)."""
    from cncc.frontend.detect import guess_dialect

    for path in paths:
        problem = ""
        try:
            text = read_program(path)
        except OSError as exc:
            text, problem = "", f"cannot read {path}: {exc.strerror or exc}"
        name, how = (dialect, "given") if dialect else (guess_dialect(path, text)[0], "guessed")
        include = (os.path.dirname(os.path.abspath(path)),)
        for m in machines:
            opts = options if isinstance(options, RowOptions) else options[m]
            yield Task(path, text, m, opts, name, how, include, problem)
