"""The keywords of a dialect: one table, read when the dialect loads.

The lists come from ``cncc/grammar/lexicon.toml`` (one table per grammar family), and a dialect
file's own ``[lexicon]`` table replaces any of them.  The parser (its grammar's
``FUNC`` terminal and the macro-word abbreviations), the fast path, the macro
executor's program test and the editor's scanner all read ``Dialect.lexicon``; no
other module keeps a keyword list.
"""

from __future__ import annotations

import functools
import re
import tomllib
from dataclasses import dataclass
from importlib import resources
from typing import Any

_WORD = re.compile(r"^[A-Z][A-Z0-9_]*$")
FIELDS = ("statements", "functions", "operators", "executor_marks", "signal_statements")


class LexiconError(ValueError):
    """A ``[lexicon]`` table is malformed (message names the key)."""


@dataclass(frozen=True, slots=True)
class Lexicon:
    statements: tuple[str, ...] = ()
    functions: tuple[str, ...] = ()
    operators: tuple[str, ...] = ()
    executor_marks: tuple[str, ...] = ()
    signal_statements: tuple[str, ...] = ()  # statements whose operand is an I/O signal (SZGH WAT+X12)
    # (word, abbreviation) pairs: Fanuc's "first two letters of a macro word" (``[macro_words]``)
    abbreviations: tuple[tuple[str, str], ...] = ()

    @property
    def keywords(self) -> frozenset[str]:
        """Every word the dialect reads as a keyword rather than address letters."""
        return frozenset((*self.statements, *self.functions, *self.operators))

    @property
    def spellings(self) -> dict[str, str]:
        """Every spelling of a keyword (the abbreviations too) -> the keyword."""
        return {**{k: k for k in self.keywords}, **{short: word for word, short in self.abbreviations}}


@functools.cache
def _families() -> dict[str, dict[str, Any]]:
    text = resources.files("cncc.grammar").joinpath("lexicon.toml").read_text(encoding="utf-8")
    return tomllib.loads(text)


def families() -> tuple[str, ...]:
    """The grammar families ``lexicon.toml`` has a table for."""
    return tuple(_families())


def _words(value: Any, where: str) -> tuple[str, ...]:
    if not isinstance(value, list):
        raise LexiconError(f"{where}: expected a list of words")
    out = tuple(str(w).upper() for w in value)
    for w in out:
        if not _WORD.match(w):
            raise LexiconError(f"{where}: {w!r} is not a word (letters, digits, '_')")
    return out


def parse_lexicon(grammar: str, raw: dict[str, Any]) -> Lexicon:
    """The lexicon of a dialect file ``raw`` whose grammar family is ``grammar``."""
    base = _families().get(grammar, {})
    own = raw.get("lexicon", {})
    if not isinstance(own, dict):
        raise LexiconError("lexicon: expected a table")
    unknown = sorted(set(own) - set(FIELDS))
    if unknown:
        raise LexiconError(f"lexicon.{unknown[0]}: unknown key (known: {', '.join(FIELDS)})")
    got = {f: _words(own[f], f"lexicon.{f}") if f in own else _words(base.get(f, []), f"lexicon.toml {grammar}.{f}")
           for f in FIELDS}
    words = (*got["statements"], *got["operators"], *got["functions"])
    return Lexicon(**got, abbreviations=_abbreviations(raw.get("macro_words", {}), words))


def _abbreviations(raw: Any, keywords: tuple[str, ...]) -> tuple[tuple[str, str], ...]:
    """(word, abbreviation) pairs: the first ``abbreviation_letters`` letters of each keyword longer
    than that (or of the ``[macro_words] words`` a dialect file lists); an abbreviation two words
    share, or that is a word itself, is not used."""
    if not isinstance(raw, dict):
        raise LexiconError("macro_words: expected a table")
    letters = int(raw.get("abbreviation_letters", 0))
    if letters <= 0:
        return ()
    listed = _words(raw["words"], "macro_words.words") if "words" in raw else tuple(dict.fromkeys(keywords))
    words = [w for w in listed if len(w) > letters]
    short = [w[:letters] for w in words]
    return tuple((w, a) for w, a in zip(words, short, strict=True) if short.count(a) == 1 and a not in words)
