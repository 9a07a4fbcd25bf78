"""Hover texts: what a code, an address or a variable means in this dialect.

The code texts come from the dialect tables (summary, modal group, the words a
code reads and their kinds); the address texts from the dialect's address kinds
and least input units.  A value written without a decimal point is shown as the
dialect reads it (``X5500`` -> 5.5 mm under the least-input-unit rule).
"""

from __future__ import annotations

from cncc.dialects import CodeDef, Dialect, code_name
from cncc.lsp.scan import Token

# What each address letter usually does in the Fanuc family (our own words).
LETTERS: dict[str, str] = {
    "A": "rotary axis about X (or a macro argument)",
    "B": "rotary axis about Y (or a macro argument)",
    "C": "rotary axis about Z (or a macro argument)",
    "D": "cutter radius offset number (G41/G42)",
    "E": "tolerance or extra parameter of some codes",
    "F": "feed rate (per minute in G94, per revolution in G95)",
    "G": "preparatory function: selects a motion, a mode or a one-shot operation",
    "H": "tool length offset number (G43/G44), or the sequence number an M98 starts at",
    "I": "arc centre offset along X from the start point; a parameter of cycles and patterns",
    "J": "arc centre offset along Y from the start point; a parameter of cycles and patterns",
    "K": "arc centre offset along Z from the start point; a parameter of cycles",
    "L": "repeat count, or the table selector of G10",
    "M": "miscellaneous function: spindle, coolant, tool change, stops, subprogram calls",
    "N": "sequence number (a label that M98 H, M99 P and GOTO can jump to)",
    "O": "program number",
    "P": "dwell time, program number of a call, or a code-specific parameter",
    "Q": "peck depth or shift amount of a canned cycle",
    "R": "arc radius, or the retract (R) level of a canned cycle",
    "S": "spindle speed (rpm, or surface speed under G96)",
    "T": "tool number to select",
    "U": "secondary linear axis parallel to X",
    "V": "secondary linear axis parallel to Y",
    "W": "secondary linear axis parallel to Z",
    "X": "X axis position (absolute in G90, increment in G91)",
    "Y": "Y axis position (absolute in G90, increment in G91)",
    "Z": "Z axis position (absolute in G90, increment in G91)",
}
KINDS: dict[str, str] = {
    "length": "a length",
    "angle": "an angle in degrees",
    "time": "a time",
    "time_ms": "a time in milliseconds",
    "int": "an integer",
    "feed": "a feed rate",
    "real": "a number",
}


def code_hover(dialect: Dialect, cdef: CodeDef) -> str:
    lines = [f"**{cdef.name}** — {cdef.summary or cdef.op}", ""]
    if cdef.group == "non_modal":
        lines.append("One-shot: acts in this block only.")
    else:
        number = dialect.groups.get(cdef.group)
        group = f"{cdef.group} (group {number:02d})" if number is not None else cdef.group
        lines.append(f"Modal group: {group}.")
        if dialect.defaults.get(cdef.group) == cdef.name:
            lines.append("In force at power-on.")
    if cdef.words:
        kinds = ", ".join(f"{k}: {KINDS.get(v, v)}" for k, v in sorted(cdef.words.items()))
        lines.append(f"Words read differently by this code: {kinds}.")
    lines.append(f"cncc operation: `{cdef.op}` ({dialect.name}).")
    return "\n".join(lines)


def word_hover(dialect: Dialect, tok: Token) -> str | None:
    """Markdown for the word ``tok`` (a letter and its value)."""
    letter = tok.text
    if letter in "GM":
        tenths = tok.tenths
        if tenths is None:
            return f"**{letter}** — {LETTERS[letter]}"
        cdef = dialect.code(letter, tenths)
        if cdef is None:
            return f"**{code_name(letter, tenths)}** is not a {dialect.name} code."
        return code_hover(dialect, cdef)
    meaning = LETTERS.get(letter)
    if meaning is None:
        return None
    kind = dialect.addresses.get(letter, "")
    head = f"**{letter}{tok.value}** — {meaning}" if tok.value else f"**{letter}** — {meaning}"
    lines = [head]
    if kind:
        lines.append("")
        lines.append(f"Value: {KINDS.get(kind, kind)}." + _reading(dialect, kind, tok))
    return "\n".join(lines)


def _reading(dialect: Dialect, kind: str, tok: Token) -> str:
    value = tok.number
    if value is None or dialect.decimal_rule != "liu":
        return ""
    point = "." in tok.value
    if kind == "length":
        if point:
            return " Written with a decimal point: read in the programmed unit (mm or inch)."
        mm = value * dialect.liu.get("length_mm", 0.001)
        return f" Without a decimal point it is in least input units: {mm:g} mm (metric)."
    if kind == "angle" and not point:
        return f" Without a decimal point: {value * dialect.liu.get('angle_deg', 0.001):g} degrees."
    if kind == "time" and not point:
        return f" Without a decimal point: {value * dialect.liu.get('time_s', 0.001):g} s."
    return ""
