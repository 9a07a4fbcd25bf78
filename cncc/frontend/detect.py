"""Guess a program's dialect when ``-x`` is not given, by scoring evidence.

The evidence is data: each dialect file has a ``[detect]`` table (read with the dialect,
:mod:`cncc.dialects.detection`, onto ``Dialect.detection``) (``extensions`` with
points, and ``[[detect.rule]]`` entries: a regular expression, the points it gives,
the reason, and the view of the program it searches).  The views are

* ``code``     — the head of the text with ``( ... )`` comments blanked out, so a URL
  inside a CamBam comment (``http://``) is no ``//`` comment;
* ``comments`` — the text of the ``( ... )`` comments and ``;`` comment lines (CAM
  headers, post-processor names);
* ``name``     — the file name;
* ``text``     — the head of the text as it is (round brackets that are not comments:
  SZGH's ``IF (#1 GT 0)``).

A rule may list ``needs``: literals one of which must occur in the view (a cheap
pre-check before the regular expression, for the rules large CAM files never match).

A rule counts once, however often it matches.  On top of the rules, every dialect
loses a point per G code the program uses that its table does not define (at most
three): the *code set* evidence.  The dialect with the most points wins; a tie goes
to the dialect listed first in :data:`TIE_ORDER`; with no evidence at all the guess
is :data:`DEFAULT`.  :func:`detect` returns the scores and the evidence, which the
driver prints with ``-v``.
"""

from __future__ import annotations

import functools
import re
from dataclasses import dataclass

from cncc.dialects import Dialect, DialectError, available, code_tenths, load_dialect

DEFAULT = "syntec"
TIE_ORDER = ("linuxcnc", "szgh", "grbl", "series8", "haas", "fanuc", "syntec")
_SCAN_CHARS = 200_000  # look at the head of a large file only
_CODE_SET_PENALTY = 1  # points lost per G code the dialect does not define
_CODE_SET_CAP = 3

_PAREN = re.compile(r"\([^)\n]*\)?")
_SEMI_LINE = re.compile(r"^\s*;(.*)$", re.M)
_G_CODE = re.compile(r"(?<![A-Z#<_])G\s*0*(\d{1,3}(?:\.\d)?)(?![\d])", re.I)


@dataclass(frozen=True, slots=True)
class Evidence:
    dialect: str
    points: int
    why: str


@dataclass(frozen=True, slots=True)
class Detection:
    dialect: str
    scores: dict[str, int]
    evidence: tuple[Evidence, ...]

    @property
    def score(self) -> int:
        return self.scores.get(self.dialect, 0)

    def runner_up(self) -> tuple[str, int] | None:
        others = [(n, s) for n, s in self.scores.items() if n != self.dialect]
        if not others:
            return None
        return max(others, key=lambda ns: (ns[1], -_tie_rank(ns[0])))

    def explain(self) -> str:
        """One line for ``-v``: the winner's evidence, then the runner-up's score."""
        if not any(e.points > 0 for e in self.evidence):
            return "nothing dialect-specific found; the default"
        mine = [e for e in self.evidence if e.dialect == self.dialect]
        parts = [f"{e.why} {e.points:+d}" for e in mine]
        text = f"score {self.score}: " + ", ".join(parts) if parts else f"score {self.score}"
        second = self.runner_up()
        if second is not None and second[1] > 0:
            theirs = [e for e in self.evidence if e.dialect == second[0] and e.points > 0]
            reasons = ", ".join(f"{e.why} {e.points:+d}" for e in theirs[:3])
            text += f"; next {second[0]} {second[1]}" + (f" ({reasons})" if reasons else "")
        return text


def _tie_rank(name: str) -> int:
    return TIE_ORDER.index(name) if name in TIE_ORDER else len(TIE_ORDER)


@functools.cache
def _dialects() -> tuple[Dialect, ...]:
    out = []
    for name in available():
        try:
            out.append(load_dialect(name))
        except DialectError:  # a broken dialect file is reported when it is selected
            continue
    return tuple(out)


@functools.cache
def _builtin_extension_points() -> dict[str, dict[str, int]]:
    return _extension_points(_dialects())


def _extension_points(dialects: tuple[Dialect, ...]) -> dict[str, dict[str, int]]:
    """File name ending -> {dialect: points}, from each dialect's ``[detect] extensions``."""
    exts: dict[str, dict[str, int]] = {}
    for d in dialects:
        for ext, points in d.detection.extensions.items():
            exts.setdefault(ext, {})[d.name] = points
    return exts


def views(name: str, text: str) -> dict[str, str]:
    """The program seen as code without comments, as comment text, and as a file name."""
    head = text[:_SCAN_CHARS]
    comments = [m.group(0) for m in _PAREN.finditer(head)]
    comments += [m.group(1) for m in _SEMI_LINE.finditer(head)]
    out = {"code": _PAREN.sub(" ", head), "comments": "\n".join(comments), "name": name, "text": head}
    for key in list(out):
        out[key + ":upper"] = out[key].upper()
    return out


def _code_set(code: str) -> set[int]:
    return {code_tenths(m.group(1)) for m in _G_CODE.finditer(code)}


def detect(name: str, text: str, dialects: tuple[Dialect, ...] | None = None) -> Detection:
    """Score every dialect (the built-in ones, or ``dialects``) for a program called ``name``
    with contents ``text``."""
    if dialects is None:
        dialects, exts = _dialects(), _builtin_extension_points()
    else:
        exts = _extension_points(dialects)
    seen = views(name, text)
    scores = {d.name: 0 for d in dialects}
    found: list[Evidence] = []

    def add(dialect: str, points: int, why: str) -> None:
        scores[dialect] = scores.get(dialect, 0) + points
        found.append(Evidence(dialect, points, why))

    lower = name.lower()
    for ext, by_dialect in exts.items():
        if lower.endswith(ext):
            for dialect, points in by_dialect.items():
                add(dialect, points, f"file extension {ext}")
    for d in dialects:
        for rule in d.detection.rules:
            if rule.matches(seen):
                add(rule.dialect, rule.points, rule.why)
    used = _code_set(seen["code"])
    if used:
        for d in dialects:
            missing = sorted(t for t in used if d.code("G", t) is None)
            if missing:
                shown = " ".join(f"G{t // 10}" + (f".{t % 10}" if t % 10 else "") for t in missing[:3])
                add(d.name, -min(_CODE_SET_CAP, _CODE_SET_PENALTY * len(missing)),
                    f"uses {shown}{' ...' if len(missing) > 3 else ''} that it does not define")
    if not any(e.points > 0 for e in found):
        return Detection(DEFAULT, scores, tuple(found))
    best = max(scores, key=lambda n: (scores[n], -_tie_rank(n)))
    return Detection(best, scores, tuple(found))


def guess_dialect(name: str, text: str) -> tuple[str, str]:
    """(dialect name, why) for a program called ``name`` with contents ``text``."""
    d = detect(name, text)
    return d.dialect, d.explain()


_INTEGER_LENGTH = re.compile(r"(?<![A-Z#\[])([XYZ])\s*(-?0*[1-9]\d*)(?![\d.])", re.I)  # X0 is 0 under every rule


def integer_length_word(text: str) -> str | None:
    """The first non-zero axis word written without a decimal point (``X10``), or None."""
    m = _INTEGER_LENGTH.search(_PAREN.sub(" ", text[:_SCAN_CHARS]))
    return None if m is None else f"{m.group(1).upper()}{m.group(2)}"


CONFIDENT_SCORE = 6
CONFIDENT_MARGIN = 4


def numbers_warning(found: Detection, text: str) -> str | None:
    """A warning when the guess decides what integers mean and the evidence is weak.

    Under a least-input-unit dialect ``X10`` is 0.010 mm; under grbl, LinuxCNC or Haas
    it is 10 mm.  When the program has such integers, the guessed dialect reads them in
    least input units, and the guess is not confident (a score below
    :data:`CONFIDENT_SCORE`, or within :data:`CONFIDENT_MARGIN` of a dialect that reads
    them as whole units), say so without ``-v``.
    """
    try:
        chosen = load_dialect(found.dialect)
    except DialectError:
        return None
    if chosen.decimal_rule != "liu":
        return None
    word = integer_length_word(text)
    if word is None:
        return None
    whole = [(n, s) for n, s in found.scores.items() if load_dialect(n).decimal_rule != "liu"]
    rival = max(whole, key=lambda ns: (ns[1], -_tie_rank(ns[0]))) if whole else None
    margin = found.score - rival[1] if rival is not None else CONFIDENT_SCORE
    if found.score >= CONFIDENT_SCORE and margin >= CONFIDENT_MARGIN:
        return None
    unit = chosen.liu.get("length_mm", 0.001)
    value = float(word[1:]) * unit
    other = f"; -x {rival[0]} reads it as {word[1:]} mm" if rival is not None else ""
    return (f"the dialect was guessed as {found.dialect} (score {found.score}), which reads integers in least "
            f"input units: {word} is {value:.3f} mm{other}; give -x to choose")


__all__ = ["CONFIDENT_MARGIN", "CONFIDENT_SCORE", "DEFAULT", "Detection", "Evidence", "detect", "guess_dialect",
           "integer_length_word", "numbers_warning", "views"]
