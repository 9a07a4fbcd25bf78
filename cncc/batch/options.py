"""What a batch computes for each program: the options every row of a results file shares."""

from __future__ import annotations

import hashlib
import json
from dataclasses import asdict, dataclass, field
from typing import Any

from cncc import __version__

EMITS = ("timing", "lint")
DEFAULT_TIME_LIMIT_S = 300.0
DEFAULT_MEMORY_LIMIT_MB = 4096


@dataclass(frozen=True, slots=True)
class RowOptions:
    """The options of one row's computation (shipped with the program text to a worker).

    ``time_limit_s`` is CPU time in the process that compiles the program;
    ``memory_limit_mb`` its address space (0: no limit).  ``offsets_text`` is the
    content of ``--offsets`` (the soft limits are checked only with it).
    """

    emit: str = "timing"
    opt_level: int = 2
    max_steps: int = 5_000_000
    time_limit_s: float = DEFAULT_TIME_LIMIT_S
    memory_limit_mb: int = DEFAULT_MEMORY_LIMIT_MB
    offsets_text: str | None = None
    strict: bool = False
    dialect_options: tuple[tuple[str, Any], ...] = ()

    def fingerprint(self) -> str:
        """A short hash of every option that can change a row (and the cncc version)."""
        doc = {"cncc": __version__, **asdict(self), "time_limit_s": float(self.time_limit_s)}  # 1 == 1.0
        blob = json.dumps(doc, sort_keys=True, default=str).encode()
        return hashlib.sha256(blob).hexdigest()[:16]


@dataclass(frozen=True, slots=True)
class Task:
    """One program on one machine: all a worker needs (it reads no file of the library)."""

    path: str
    text: str
    machine: str
    options: RowOptions = field(default_factory=RowOptions)
    dialect: str = "syntec"  # given with -x, else guessed from the path and text (``dialect_from``)
    dialect_from: str = "given"
    include_dirs: tuple[str, ...] = ()  # the program's folder, for the subprograms it calls
    read_error: str = ""  # the file could not be read: the row says so

    @property
    def sha256(self) -> str:
        return hashlib.sha256(self.text.encode("utf-8", "surrogateescape")).hexdigest()

    @property
    def key(self) -> str:
        """Content hash + machine + dialect + options: equal keys give equal rows (path aside)."""
        parts = (self.sha256, self.machine, self.dialect, *self.include_dirs, self.options.fingerprint())
        blob = "\0".join(parts).encode()
        return hashlib.sha256(blob).hexdigest()[:24]
