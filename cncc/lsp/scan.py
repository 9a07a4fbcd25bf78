"""A lexical view of a program for editor features: words, labels, calls, variables.

Editor features need to know what is under the cursor and where labels and calls
are, also on lines the compiler rejects.  This scanner reads one line at a time,
skips the dialect's comments, and yields the address words (letter + number),
keywords (``GOTO``, ``WHILE``, LinuxCNC's ``sub``/``call`` ...), variables (``#100``),
LinuxCNC named parameters (``#<depth>``) and named O-words (``o<square>``) with
their offsets.  It
never fails; anything it does not recognise is skipped.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from dataclasses import dataclass

from cncc.dialects import Dialect, code_tenths

_KEYWORDS = ("ENDSUB|ENDWHILE|ENDREPEAT|REPEAT|RETURN|ELSEIF|SUB|CALL|BREAK|CONTINUE|"
             "GOTO|THEN|WHILE|ENDIF|ELIF|ELSE|END|IF|DO|EQ|NE|GT|GE|LT|LE|AND|XOR|OR|MOD|ASIN|ACOS|ATAN|SIN|COS|"
             "TAN|SQRT|ABS|ROUND|FIX|FUP|LN|EXP|BIN|BCD|POW|WAT|OUT|MSG|STAF|FILE[A-Z]*")
_TOKEN_RE = re.compile(
    r"(?P<var>#\s*(?P<varnum>\d+))"
    r"|(?P<named>#[ \t]*<(?P<pname_>[^>]*)>)"
    r"|(?P<oname>[Oo][ \t]*<(?P<oname_>[^>]*)>)"
    rf"|(?P<kw>(?i:{_KEYWORDS}))(?![A-Za-z])"
    r"|(?P<bare>\d+\.?\d*)"
    r"|(?P<pname>[Pp])(?P<name>[A-Za-z_][\w/]*)"
    r"|(?P<letter>[A-Za-z])[ \t]*(?P<num>[-+]?[ \t]*(?:\d+\.?\d*|\.\d+))?"
)


@dataclass(frozen=True, slots=True)
class Token:
    kind: str  # "word", "keyword", "var", "named", "oname", "number" (after a keyword: GOTO 5, DO 1)
    text: str  # letter (word), keyword upper-cased, variable number (var), name (named: ``#<name>``,
    # oname: LinuxCNC ``o<name>``) in LinuxCNC's form: blanks removed, lower case
    value: str  # number text of a word ("" when the letter has no value); keyword: ""
    start: int  # absolute offsets in the document
    end: int

    @property
    def number(self) -> float | None:
        try:
            return float(self.value.replace(" ", "").replace("\t", ""))
        except ValueError:
            return None

    @property
    def tenths(self) -> int | None:
        """G/M code number in tenths (``G59.1`` -> 591), None when not a number."""
        v = self.value.strip().lstrip("+")
        if not v or not (v[0].isdigit() or v[0] == "."):
            return None
        try:
            return code_tenths(v)
        except ValueError:
            return None


@dataclass(frozen=True, slots=True)
class Comments:
    paren: bool
    slash: bool
    semi: bool

    @staticmethod
    def of(dialect: Dialect) -> Comments:
        kinds = set(dialect.comments)
        return Comments("paren" in kinds, "slash" in kinds, "semi" in kinds and dialect.block_end != ";")


def code_part(line: str, comments: Comments) -> list[tuple[int, int]]:
    """The (start, end) pieces of ``line`` that are outside comments."""
    pieces: list[tuple[int, int]] = []
    i = 0
    start = 0
    n = len(line)
    while i < n:
        ch = line[i]
        if ch == "(" and comments.paren:
            pieces.append((start, i))
            close = line.find(")", i + 1)
            if close < 0:
                return pieces
            i = start = close + 1
            continue
        if (ch == "/" and comments.slash and line.startswith("//", i)) or (ch == ";" and comments.semi):
            pieces.append((start, i))
            return pieces
        i += 1
    pieces.append((start, n))
    return pieces


def tokens(line: str, base: int, comments: Comments) -> Iterator[Token]:
    """Tokens of one line (``base`` is the line's offset in the document)."""
    for lo, hi in code_part(line, comments):
        for m in _TOKEN_RE.finditer(line, lo, hi):
            if m.group("var"):
                yield Token("var", m.group("varnum"), "", base + m.start(), base + m.end())
            elif m.group("named"):
                yield Token("named", _name(m.group("pname_")), "", base + m.start(), base + m.end())
            elif m.group("oname"):
                yield Token("oname", _name(m.group("oname_")), "", base + m.start(), base + m.end())
            elif m.group("kw"):
                yield Token("keyword", m.group("kw").upper(), "", base + m.start(), base + m.end())
            elif m.group("bare"):
                yield Token("number", "", m.group("bare"), base + m.start(), base + m.end())
            elif m.group("pname"):
                yield Token("word", "P", m.group("name"), base + m.start(), base + m.end())
            else:
                value = m.group("num") or ""
                yield Token("word", m.group("letter").upper(), value.strip(), base + m.start(), base + m.end())


def _name(inner: str) -> str:
    """LinuxCNC ignores blanks and case in ``#<names>`` and ``o<names>``."""
    return "".join(inner.split()).lower()


def token_at(line: str, base: int, offset: int, comments: Comments) -> Token | None:
    """The token that contains ``offset`` (or ends just before it)."""
    best = None
    for tok in tokens(line, base, comments):
        if tok.start <= offset < tok.end:
            return tok
        if tok.end == offset:
            best = tok
    return best


def in_comment(line: str, col: int, comments: Comments) -> bool:
    return not any(lo <= col <= hi for lo, hi in code_part(line, comments))
