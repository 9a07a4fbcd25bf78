"""Run the oracle over generated programs: agreement per feature, the allow-list applied."""

from __future__ import annotations

import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from tests.oracle.harness import compare
from tests.oracle.programs import Program, generate

ALLOW_FILE = Path(__file__).with_name("allow.toml")


@dataclass(frozen=True, slots=True)
class Allowance:
    feature: str
    program: str
    diff: str
    reason: str

    def covers(self, feature: str, program: str, diff: str) -> bool:
        return (self.feature in ("*", feature) and re.search(self.program, program) is not None
                and re.search(self.diff, diff) is not None)


def allowances() -> list[Allowance]:
    raw = tomllib.loads(ALLOW_FILE.read_text())
    return [Allowance(a.get("feature", "*"), a.get("program", ""), a.get("diff", ""), a["reason"])
            for a in raw.get("allow", [])]


@dataclass(slots=True)
class Tally:
    feature: str
    programs: int = 0
    agree: int = 0
    both_fail: int = 0
    allowed: int = 0
    disagreements: list[tuple[Program, str]] = field(default_factory=list)


def tally(feature: str, count: int, seed: int = 0) -> Tally:
    allow = allowances()
    t = Tally(feature)
    for prog in generate(feature, count, seed):
        v = compare(prog.text, prog.tool_table, dict(prog.local_files), ini=prog.ini, files=prog.files)
        t.programs += 1
        if v.agree:
            t.agree += 1
            if v.oracle is not None and not v.oracle.ok:
                t.both_fail += 1
        elif any(a.covers(feature, prog.text, v.reason) for a in allow):
            t.allowed += 1
        else:
            t.disagreements.append((prog, v.reason))
    return t


def explain(t: Tally, limit: int = 3) -> str:
    lines = [f"{t.feature}: {len(t.disagreements)} of {t.programs} programs disagree with rs274"]
    for prog, why in t.disagreements[:limit]:
        lines.append(f"  {why}\n    " + prog.text.strip().replace("\n", "\n    "))
    return "\n".join(lines)
