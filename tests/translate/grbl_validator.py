"""A small grbl 1.1 program checker for the translation tests.

Written from grbl 1.1's documented command list (G0 G1 G2 G3 G4 G10 L2/L20 G17-G19
G20 G21 G28 G28.1 G30 G30.1 G38.2-G38.5 G40 G43.1 G49 G53 G54-G59 G61 G80 G90 G91
G91.1 G92 G92.1 G93 G94; M0 M1 M2 M30 M3 M4 M5 M7 M8 M9 M56; words F I J K L N P R S T
X Y Z) and its block rules: one command per modal group, no repeated word, arcs
with a plane axis word and I/J/K or R, feed moves with a feed rate in force, G4 with
P, no axis words with G80, at most 79 characters per line once blanks and comments
are removed, N up to 9999999, T up to 255.  It does not use cncc: it is an
independent reading of the output.
"""

from __future__ import annotations

import re

G_GROUPS: dict[str, str] = {
    **dict.fromkeys(["0", "1", "2", "3", "38.2", "38.3", "38.4", "38.5", "80"], "motion"),
    **dict.fromkeys(["4", "10", "28", "28.1", "30", "30.1", "53", "92", "92.1"], "non_modal"),
    **dict.fromkeys(["17", "18", "19"], "plane"),
    **dict.fromkeys(["90", "91"], "distance"),
    "91.1": "arc_distance",
    **dict.fromkeys(["93", "94"], "feed_mode"),
    **dict.fromkeys(["20", "21"], "units"),
    "40": "cutter_comp",
    **dict.fromkeys(["43.1", "49"], "tool_length"),
    **dict.fromkeys(["54", "55", "56", "57", "58", "59"], "work"),
    "61": "path",
}
M_GROUPS: dict[str, str] = {
    **dict.fromkeys(["0", "1", "2", "30"], "stopping"),
    **dict.fromkeys(["3", "4", "5"], "spindle"),
    **dict.fromkeys(["7", "8", "9"], "coolant"),
    "56": "override",
}
VALUE_LETTERS = set("FIJKLNPRSTXYZ")
AXES = {"17": "XY", "18": "ZX", "19": "YZ"}
OFFSETS = {"17": "IJ", "18": "IK", "19": "JK"}
WORD = re.compile(r"([A-Z])([-+]?(?:\d+\.?\d*|\.\d+))")


def strip(line: str) -> str:
    """Upper case, without comments and blanks (what grbl keeps in its line buffer)."""
    line = re.sub(r"\([^)]*\)", "", line.split(";", 1)[0])
    return re.sub(r"\s+", "", line).upper()


def _number(text: str) -> str:
    """``"01"`` -> ``"1"``, ``"28.10"`` -> ``"28.1"`` (grbl compares the value)."""
    value = float(text)
    return f"{value:g}"


class GrblChecker:
    def __init__(self) -> None:
        self.plane = "17"
        self.motion = "0"
        self.feed = False

    def check(self, program: str) -> list[str]:
        """Errors as ``"line N: reason"`` (empty when grbl would accept every line)."""
        errors: list[str] = []
        for n, raw in enumerate(program.splitlines(), 1):
            why = self.block(raw)
            if why:
                errors.append(f"line {n}: {why}: {raw!r}")
        return errors

    def block(self, raw: str) -> str:
        line = strip(raw)
        if raw.strip() == "%" or not line:
            return ""
        if len(line) > 79:
            return "error 11: line overflow"
        pos, words = 0, []
        for m in WORD.finditer(line):
            if m.start() != pos:
                return "error 1: expected a command letter"
            words.append((m.group(1), m.group(2)))
            pos = m.end()
        if pos != len(line):
            return "error 1/2: bad word"
        return self._words(words)

    def _words(self, words: list[tuple[str, str]]) -> str:
        groups: set[str] = set()
        values: dict[str, float] = {}
        gcodes: list[str] = []
        for letter, text in words:
            if letter in "GM":
                table = G_GROUPS if letter == "G" else M_GROUPS
                code = _number(text)
                group = table.get(code)
                if group is None:
                    return f"error 20: unsupported command {letter}{text}"
                if (letter, group) in {(g[0], g[1:]) for g in groups}:
                    return "error 21: two commands of one modal group"
                groups.add(letter + group)
                if letter == "G":
                    gcodes.append(code)
            elif letter in VALUE_LETTERS:
                if letter in values:
                    return f"error 25: repeated {letter} word"
                values[letter] = float(text)
            else:
                return f"error 20: unsupported word {letter}"
        return self._semantics(gcodes, values)

    def _semantics(self, gcodes: list[str], v: dict[str, float]) -> str:
        if v.get("N", 0) > 9999999 or v.get("N", 0) < 0:
            return "error 27: line number out of range"
        if v.get("T", 0) > 255 or v.get("T", 0) < 0:
            return "error 38: tool number beyond 255"
        if "F" in v:
            if v["F"] <= 0:
                return "error 22: feed rate not positive"
            self.feed = True
        for g in gcodes:
            if g in AXES:
                self.plane = g
            if g in ("0", "1", "2", "3", "80"):
                self.motion = g
        axis_words = [a for a in "XYZ" if a in v]
        if "4" in gcodes and "P" not in v:
            return "error 28: G4 without P"
        if "80" in gcodes and axis_words:
            return "error 31: axis words with G80"
        non_modal_axes = any(g in ("28", "30", "92", "53", "10") for g in gcodes)
        if not axis_words or non_modal_axes:
            return ""
        if self.motion in ("1", "2", "3") and not self.feed:
            return "error 22: no feed rate in force"
        if self.motion in ("2", "3"):
            if not any(a in v for a in AXES[self.plane]):
                return "error 26: arc without an axis word in the plane"
            if "R" not in v and not any(o in v for o in OFFSETS[self.plane]):
                return "error 26: arc without R or centre offsets in the plane"
        return ""
