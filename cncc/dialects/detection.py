"""A dialect's detection marks, read from its ``[detect]`` table when the dialect loads.

``[detect] extensions = { ".ngc" = 4 }`` gives points to a file name ending so; each
``[[detect.rule]]`` is a regular expression with the points it gives, the reason
shown by ``-v``, the view of the program it searches (``code``, ``comments``,
``name``, ``text``: :func:`cncc.frontend.detect.views`), optional ``also`` /
``unless`` patterns, ``needs`` literals (a cheap pre-check) and ``case = true`` for a
case-sensitive match.  An extension with points must also be one the dialect claims
in its top-level ``extensions`` list (the files it reads and calls).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any

VIEWS = ("code", "comments", "name", "text")


class DetectError(ValueError):
    """The ``[detect]`` table is malformed (message names the key)."""


@dataclass(frozen=True, slots=True)
class Rule:
    dialect: str
    view: str  # one of VIEWS
    pattern: re.Pattern[str]
    points: int
    why: str
    also: re.Pattern[str] | None = None  # must match too
    unless: re.Pattern[str] | None = None  # must not match
    needs: tuple[str, ...] = ()  # upper-case literals one of which must occur (a cheap pre-check)

    def matches(self, seen: dict[str, str]) -> bool:
        if self.needs:
            upper = seen.get(self.view + ":upper", "")
            if not any(n in upper for n in self.needs):
                return False
        text = seen.get(self.view, "")
        if self.pattern.search(text) is None:
            return False
        if self.also is not None and self.also.search(text) is None:
            return False
        return self.unless is None or self.unless.search(text) is None


@dataclass(frozen=True, slots=True)
class Detection:
    """What counts as evidence for one dialect."""

    extensions: dict[str, int]  # lower-case file name ending -> points
    rules: tuple[Rule, ...]


def _pattern(entry: dict[str, Any], key: str, flags: int, where: str) -> re.Pattern[str] | None:
    if key not in entry:
        return None
    try:
        return re.compile(str(entry[key]), flags)
    except re.error as exc:
        raise DetectError(f"{where}.{key}: {exc}") from None


def _rule(dialect: str, entry: Any, where: str) -> Rule:
    if not isinstance(entry, dict):
        raise DetectError(f"{where}: expected a table")
    flags = re.M | (0 if entry.get("case", False) else re.I)
    main = _pattern(entry, "pattern", flags, where)
    if main is None:
        raise DetectError(f"{where}: a rule needs a 'pattern'")
    view = str(entry.get("view", "code"))
    if view not in VIEWS:
        raise DetectError(f"{where}.view: {view!r} is not one of {', '.join(VIEWS)}")
    try:
        points = int(str(entry["points"]))
        why = str(entry["why"])
    except KeyError as exc:
        raise DetectError(f"{where}: missing key {exc.args[0]!r}") from None
    except ValueError:
        raise DetectError(f"{where}.points: expected an integer") from None
    needs = tuple(str(n).upper() for n in entry.get("needs", []))
    return Rule(dialect, view, main, points, why, _pattern(entry, "also", flags, where),
                _pattern(entry, "unless", flags, where), needs)


def parse_detection(dialect: str, raw: dict[str, Any], claimed: tuple[str, ...]) -> Detection:
    """The ``[detect]`` table of the dialect file ``raw`` (``claimed``: its ``extensions``)."""
    table = raw.get("detect", {})
    if not isinstance(table, dict):
        raise DetectError("detect: expected a table")
    exts: dict[str, int] = {}
    for ext, points in table.get("extensions", {}).items():
        if str(ext).lower() not in {c.lower() for c in claimed}:
            raise DetectError(f"detect.extensions: {ext!r} gives points but is not in the dialect's 'extensions'")
        exts[str(ext).lower()] = int(points)
    rules = tuple(_rule(dialect, entry, f"detect.rule[{i}]") for i, entry in enumerate(table.get("rule", [])))
    return Detection(exts, rules)
