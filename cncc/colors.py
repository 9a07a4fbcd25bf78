"""Colours of the text diagnostics: ``-fdiagnostics-color=auto|always|never``, ``NO_COLOR``, ``GCC_COLORS``.

As gcc: ``auto`` colours when standard error is a terminal (and ``TERM`` is not
``dumb``); ``NO_COLOR`` (any non-empty value, https://no-color.org) turns ``auto``
off; ``always`` and ``never`` win over the environment.  ``GCC_COLORS`` (or
``CNCC_COLORS``, read first) overrides the SGR codes of the capabilities
``error``, ``warning``, ``note``, ``caret`` and ``locus``, e.g.
``GCC_COLORS='error=01;31:warning=01;35:note=01;36:caret=01;32:locus=01'``; an
empty value turns colours off, as it does for gcc.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TextIO

CHOICES = ("auto", "always", "never")
DEFAULT_SGR: dict[str, str] = {"error": "01;31", "warning": "01;35", "note": "01;36", "caret": "01;32",
                               "locus": "01"}


@dataclass(frozen=True, slots=True)
class Palette:
    """SGR codes by capability; empty: no colour."""

    sgr: Mapping[str, str] = field(default_factory=dict)

    def paint(self, cap: str, text: str) -> str:
        code = self.sgr.get(cap, "")
        return f"\x1b[{code}m\x1b[K{text}\x1b[m\x1b[K" if code and text else text


def parse_colors(spec: str) -> dict[str, str]:
    """``name=SGR:name=SGR`` over the defaults (unknown names and malformed entries are ignored)."""
    out = dict(DEFAULT_SGR)
    for item in spec.split(":"):
        name, sep, code = item.partition("=")
        if sep and name in out and all(part.isdigit() for part in code.split(";") if part):
            out[name] = code
    return out


def palette(mode: str, stream: TextIO, env: Mapping[str, str] | None = None) -> Palette:
    """The palette for ``-fdiagnostics-color=mode`` writing to ``stream``."""
    env = os.environ if env is None else env
    if mode == "never":
        return Palette()
    if mode == "auto":
        tty = bool(getattr(stream, "isatty", lambda: False)())
        if not tty or env.get("NO_COLOR") or env.get("TERM") == "dumb":
            return Palette()
    spec = env.get("CNCC_COLORS", env.get("GCC_COLORS"))
    if spec is None:
        return Palette(dict(DEFAULT_SGR))
    if not spec:
        return Palette()
    return Palette(parse_colors(spec))
