"""The ``--io FILE`` format: input values for programs that branch on inputs.

One assignment per line, ``NAME = VALUE`` (TOML-compatible when the name is
quoted): ``X12 = 1`` (SZGH input X12 valid), ``M14 = on`` (the M14 input),
``"#1800" = 5`` (an input register or any system variable the program reads),
``#1000 = 1`` (Fanuc input).  Values are numbers or ``on/off``, ``true/false``,
``valid/invalid``.  Blank lines and lines starting with ``;``, ``//`` or ``# ``
(a hash and a blank) are comments.
"""

from __future__ import annotations

import re

_LINE = re.compile(r'^\s*"?(?P<name>[XYM]\d{1,4}|#\d{1,6})"?\s*[=:]?\s*(?P<value>[^\s;]+)\s*(?:;.*)?$', re.IGNORECASE)
_WORDS = {"on": 1.0, "true": 1.0, "valid": 1.0, "yes": 1.0, "off": 0.0, "false": 0.0, "invalid": 0.0, "no": 0.0}


class IoFileError(ValueError):
    """The file is malformed (the message names the line)."""


def parse_io(text: str, name: str = "--io") -> dict[str, float]:
    values: dict[str, float] = {}
    for k, raw in enumerate(text.splitlines(), start=1):
        line = raw.strip()
        if not line or line.startswith((";", "//", "# ", "[")) or line == "#":
            continue
        m = _LINE.match(line)
        if m is None:
            raise IoFileError(f"{name}:{k}: expected 'NAME = VALUE' (X12 = 1, M14 = on, #1800 = 5), got {raw!r}")
        key = m.group("name").upper()
        text_value = m.group("value").lower()
        if text_value in _WORDS:
            values[key] = _WORDS[text_value]
            continue
        try:
            values[key] = float(text_value)
        except ValueError:
            raise IoFileError(f"{name}:{k}: {m.group('value')!r} is not a number or on/off") from None
    return values


def read_io(path: str) -> dict[str, float]:
    try:
        with open(path, encoding="utf-8") as fh:
            text = fh.read()
    except OSError as exc:
        raise IoFileError(f"cannot read {path}: {exc.strerror or exc}") from None
    return parse_io(text, path)
