"""Guess a program's dialect when ``-x`` is not given.

``guess_dialect(name, text)`` looks at the file name's extension and at the first
lines of the text for the marks each dialect leaves: LinuxCNC's ``o<name>`` lines and
``#<name>`` parameters, SZGH's WAT/OUT/FILE statements, SERIES 8's bare axis letters,
G55/G57 R and G10 R/L corners, Fanuc macro B with G20/G21,
SYNTEC's G70/G71 and ``//`` comments, grbl's ``$`` settings lines and ``.gcode``
files.  It returns the name and a short reason (the driver prints it with ``-v``).
"""

from __future__ import annotations

import re
from collections.abc import Callable

DEFAULT = "syntec"
_SCAN_CHARS = 200_000  # look at the head of a large file only

_STRONG: tuple[tuple[str, str, re.Pattern[str]], ...] = (
    ("linuxcnc", "O-word control flow (o<name> / o100 sub|call|if|while ...)",
     re.compile(r"^\s*[oO]\s*(<[^>]*>|\d+)\s*(sub|call|if|while|do|repeat|endsub|return)\b", re.I | re.M)),
    ("linuxcnc", "named parameters #<name>", re.compile(r"#\s*<[^>]+>")),
    ("szgh", "SZGH statements (WAT, OUT, FILEON, PP ...)",
     re.compile(r"\b(WAT[+-]|OUT[+-]|FILEON|FILEMS|STAF\s*\()|^\s*PP\s", re.I | re.M)),
    ("grbl", "grbl settings lines ($...)", re.compile(r"^\s*\$[A-Za-z0-9#$]", re.M)),
    ("series8", "SERIES 8 marks (bare axis letters G00XY, G55 R rotation, G57 R scaling, G10 R/L corners)",
     re.compile(r"^\s*G0?0\s*[XYZ][XYZ]?\s*(;.*)?$|G5[57]\s*R[-+.\d]|G10(?![^;\n]*[PQ])[^;\n]*[RL]\s*[-+.\d]",
                re.I | re.M)),
)
_EXTENSIONS = {".ngc": "linuxcnc", ".gcode": "grbl", ".gc": "grbl", ".fnc": "fanuc"}
_SYNTEC_UNITS = re.compile(r"(?<![\d.])G0?7[01](?![\d.])|//", re.I)
_UNITS_20 = re.compile(r"(?<![\d.])G2[01](?![\d.])", re.I)
_MACRO_B = re.compile(r"#\d+\s*=|WHILE\s*\[|IF\s*\[|GOTO|^\s*O\d+", re.I | re.M)
_SEMI_TEXT = re.compile(r";\s*[A-Za-z][a-z]+\s", re.M)  # ';' starting a comment, not ending a block
_WEAK: tuple[tuple[str, str, Callable[[str], bool]], ...] = (
    ("series8", "G70/G71 units codes with ';' comments (SERIES 8; SYNTEC ends blocks with ';')",
     lambda t: bool(_SYNTEC_UNITS.search(t) and _SEMI_TEXT.search(t) and "//" not in t)),
    ("syntec", "G70/G71 units codes or // comments",
     lambda t: bool(_SYNTEC_UNITS.search(t))),
    ("fanuc", "G20/G21 with Fanuc macro B (#n =, WHILE[, IF[, GOTO) or an O number header",
     lambda t: bool(_UNITS_20.search(t) and _MACRO_B.search(t))),
    ("linuxcnc", "G20/G21 units codes without Fanuc macros (numbers in program units)",
     lambda t: bool(_UNITS_20.search(t))),
)


def guess_dialect(name: str, text: str) -> tuple[str, str]:
    """(dialect name, why) for a program called ``name`` with contents ``text``."""
    head = text[:_SCAN_CHARS]
    for dialect, why, pattern in _STRONG:
        if pattern.search(head):
            return dialect, why
    lower = name.lower()
    for ext, dialect in _EXTENSIONS.items():
        if lower.endswith(ext):
            return dialect, f"file extension {ext}"
    for dialect, why, test in _WEAK:
        if test(head):
            return dialect, why
    return DEFAULT, "nothing dialect-specific found; the default"
