"""The ``-f`` flags of the command line, and did-you-mean for a ``-fNAME`` that is none of them.

A ``-fNAME=VALUE`` that is not a cncc flag sets the dialect option ``NAME``
(``-frapid_type=independent``); an unknown name is reported with the closest cncc
flags and dialect options.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable

SWITCHES = ("syntax-only", "strict", "repair-arcs", "no-block-delete", "line-numbers", "no-verify")
VALUED = ("diagnostics-format", "diagnostics-color", "max-errors")  # -fNAME=VALUE flags of cncc itself
FLAGS = SWITCHES + VALUED


def _norm(name: str) -> str:
    return name.replace("_", "-").lower()


def suggest(name: str, dialect_options: Iterable[str], dialect: str) -> str:
    """' did you mean ...?' naming whether each suggestion is a cncc flag or a dialect option ('' if none)."""
    options = {_norm(o): o for o in dialect_options}
    flags = {_norm(f): f for f in FLAGS}
    close = difflib.get_close_matches(_norm(name), list(flags) + list(options), n=3, cutoff=0.6)
    hints = [f"-f{flags[c]} (a cncc flag)" if c in flags else f"-f{options[c]} (an option of dialect {dialect})"
             for c in close]
    return f"; did you mean {' or '.join(hints)}?" if hints else ""


def unknown_option(name: str, value: object, dialect_options: Iterable[str], dialect: str) -> str:
    """The message for ``-fNAME=VALUE`` when NAME is neither a cncc flag nor an option of ``dialect``."""
    return (f"-f{name}={value}: {name!r} is neither a cncc flag nor an option of dialect {dialect}"
            + suggest(name, dialect_options, dialect))
