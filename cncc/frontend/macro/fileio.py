"""The program-writing sandbox for SZGH ``FILEON/FILEWD/FILEWC/FILECE/FILEMS``.

Files are written only inside the folder given with ``--write-dir``.  A name that
is absolute, contains ``..``, a drive or a NUL, or that resolves (through
symbolic links) to a place outside the folder is refused; an input file of the
compilation is never overwritten.  Without ``--write-dir`` nothing is written and
the statement is reported.  Files are written whole when closed (``FILECE`` or the
end of the run), through a temporary file and an atomic rename.
"""

from __future__ import annotations

import os
import tempfile
from dataclasses import dataclass, field

_BAD_CHARS = frozenset("\0:\\")


class SandboxError(Exception):
    """A name the sandbox refuses (message says why)."""


@dataclass(slots=True)
class Sandbox:
    write_dir: str | None
    protected: tuple[str, ...] = ()  # real paths of the inputs
    written: list[str] = field(default_factory=list)

    def resolve(self, name: str) -> str:
        """The real path for program ``name`` inside the write folder, or raise."""
        if self.write_dir is None:
            raise SandboxError("no --write-dir was given, so programs are not written")
        text = name.strip()
        if not text:
            raise SandboxError("the program name is empty")
        if any(c in _BAD_CHARS for c in text) or os.path.isabs(text) or text.startswith(("/", "~")):
            raise SandboxError(f"{text!r} is not a plain program name (absolute paths are refused)")
        parts = text.replace("\\", "/").split("/")
        if any(p in ("..", ".", "") for p in parts):
            raise SandboxError(f"{text!r} leaves the write folder ('..' and empty parts are refused)")
        root = os.path.realpath(self.write_dir)
        target = os.path.realpath(os.path.join(root, *parts))
        if os.path.commonpath([root, target]) != root or target == root:
            raise SandboxError(f"{text!r} resolves outside the write folder (through a symbolic link?)")
        if target in self.protected:
            raise SandboxError(f"{text!r} is an input of this compilation and is never overwritten")
        return target

    def write(self, path: str, text: str) -> None:
        """Write ``text`` to ``path`` (already resolved) atomically."""
        folder = os.path.dirname(path)
        os.makedirs(folder, exist_ok=True)
        # check again after creating folders: a link could have been planted meanwhile
        root = os.path.realpath(self.write_dir or "")
        if os.path.commonpath([root, os.path.realpath(folder)]) != root:
            raise SandboxError("the target folder resolves outside the write folder")
        fd, tmp = tempfile.mkstemp(prefix=".cncc-", suffix=".tmp", dir=folder)
        try:
            with os.fdopen(fd, "w", encoding="utf-8", newline="\n") as fh:
                fh.write(text)
            if os.path.islink(path):
                raise SandboxError("the target is a symbolic link")
            os.replace(tmp, path)
        except BaseException:
            if os.path.exists(tmp):
                os.unlink(tmp)
            raise
        self.written.append(path)
