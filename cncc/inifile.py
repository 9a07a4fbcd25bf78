"""LinuxCNC INI files (``--ini FILE``): what LinuxCNC's interpreter reads from one.

The format is LinuxCNC's: ``[SECTION]`` lines, ``NAME = VALUE`` lines, comments from ``#``
or ``;`` at the start of a line, blank lines; the first of repeated names counts.  Any
other line is reported (E0984, at its place in the INI file) and skipped; an unreadable
file is E0983.

:class:`IniSettings` is what cncc uses, as LinuxCNC 2.9's ``rs274`` reads it:

- ``[RS274NGC] SUBROUTINE_PATH``: folders searched for ``o<name> call`` files, ``:``
  separated, after the ``-I`` folders.  A relative folder is taken from the INI file's
  folder (LinuxCNC runs from its configuration folder; the stand-alone ``rs274`` takes it
  from its working folder);
- every numeric value as the read-only parameter ``#<_ini[section]name>`` (names are
  case-insensitive; a value that is not a number is not a parameter);
- ``[RS274NGC] DISABLE_FANUC_STYLE_SUB``: M98/M99 subprograms are errors.

- the keys of the dialect's ``[ini]`` table (:func:`dialect_options`): each sets a dialect
  option, within the range LinuxCNC accepts (``CENTER_ARC_RADIUS_TOLERANCE_MM``/``_INCH``,
  ``RETAIN_G43``, ``[TRAJ] SPINDLES``); a value outside it is W0972 and the default stays, as
  rs274 warns "invalid [SECTION]NAME in INI file" and keeps its own.  An option given with
  ``-f`` wins over the INI file.

Other keys are ignored, as LinuxCNC ignores keys it does not know; not modelled: ``OWORD_NARGS``,
``NO_DOWNCASE_OWORD``, ``OWORD_WARNONLY``, ``PARAMETER_FILE``, ``USER_M_PATH``, remaps.
"""

from __future__ import annotations

import math
import os
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink
from cncc.source import NO_SPAN, SourceMap, Span

_SECTION = re.compile(r"^\s*\[([^\]]*)\]\s*$")
_ENTRY = re.compile(r"^\s*([^=\s][^=]*?)\s*=\s*(.*?)\s*$")
_NUMBER = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")


@dataclass(slots=True)
class IniSettings:
    path: str
    sections: dict[str, dict[str, str]] = field(default_factory=dict)  # upper-case names

    def get(self, section: str, name: str) -> str | None:
        return self.sections.get(section.upper(), {}).get(name.upper())

    def flag(self, section: str, name: str) -> bool:
        v = self.get(section, name)
        if v is None:
            return False
        try:
            return float(v) != 0.0
        except ValueError:
            return v.strip().lower() in ("true", "yes", "on")

    def subroutine_dirs(self) -> tuple[str, ...]:
        raw = self.get("RS274NGC", "SUBROUTINE_PATH") or ""
        base = os.path.dirname(os.path.abspath(self.path))
        return tuple(os.path.join(base, os.path.expanduser(d)) for d in raw.split(":") if d.strip())

    def parameters(self) -> dict[str, float]:
        """``_ini[section]name`` (lower case, as LinuxCNC names parameters) -> value, for numeric values."""
        out: dict[str, float] = {}
        for sec, entries in self.sections.items():
            for name, value in entries.items():
                if _NUMBER.match(value):
                    out["".join(f"_ini[{sec}]{name}".split()).lower()] = float(value)
        return out

    def number(self, section: str, name: str) -> float | None:
        v = self.get(section, name)
        return float(v) if v is not None and _NUMBER.match(v) else None


def read_ini(path: str, sources: SourceMap, sink: DiagnosticSink) -> IniSettings | None:
    """The INI file at ``path``, its malformed lines reported; None when it cannot be read."""
    try:
        with open(path, "rb") as fh:
            text = fh.read().decode("utf-8", errors="replace")
    except OSError as exc:
        sink.emit(dg.INI_UNREADABLE, NO_SPAN, f"--ini {path}: cannot read it: {exc.strerror or exc}")
        return None
    src = sources.add(path, text)
    ini = IniSettings(path)
    section: dict[str, str] | None = None
    pos = 0
    for line in text.splitlines(keepends=True):
        start, body = pos, line.rstrip("\r\n")
        pos += len(line)
        stripped = body.strip()
        if not stripped or stripped[0] in "#;":
            continue
        m = _SECTION.match(body)
        if m is not None:
            section = ini.sections.setdefault(m.group(1).strip().upper(), {})
            continue
        e = _ENTRY.match(body)
        lead = len(body) - len(body.lstrip())
        at = Span(src.source_id, start + lead, start + len(body))
        if e is None:
            sink.emit(dg.INI_BAD_LINE, at, "not a [SECTION] line, a NAME = VALUE line or a comment; skipped")
        elif section is None:
            sink.emit(dg.INI_BAD_LINE, at, f"{e.group(1)} = ... before the first [SECTION]; the line is skipped")
        else:
            section.setdefault(e.group(1).upper(), e.group(2))
    return ini


def dialect_options(ini: IniSettings, table: Mapping[str, Any], explicit: Mapping[str, Any],
                    sink: DiagnosticSink) -> dict[str, Any]:
    """The dialect options ``ini`` sets: ``table`` is the dialect's ``[ini]`` (``"SECTION.NAME" =
    {option, kind = "number"|"flag"|"count", min, max}``); options in ``explicit`` (``-f``) are kept."""
    out: dict[str, Any] = {}
    for key, spec in table.items():
        section, _, name = str(key).partition(".")
        raw = ini.get(section, name)
        option = str(spec["option"])
        if raw is None or option in explicit:
            continue
        value = _value(raw, spec)
        if value is None:
            sink.emit(dg.INI_BAD_VALUE, NO_SPAN, f"--ini {ini.path}: invalid [{section}]{name} = {raw} "
                      f"(LinuxCNC accepts {_accepted(spec)}); the default is kept")
            continue
        out[option] = value
    return out


def _value(raw: str, spec: Mapping[str, Any]) -> Any:
    kind = str(spec.get("kind", "number"))
    if kind == "flag":
        return raw.strip().lower() in ("1", "true", "yes", "on") or (bool(_NUMBER.match(raw)) and float(raw) != 0)
    if not _NUMBER.match(raw.strip()):
        return None
    v = float(raw)
    if not math.isfinite(v):
        return None
    if kind == "count":
        v = float(int(v))
    lo, hi = float(spec.get("min", -math.inf)), float(spec.get("max", math.inf))
    if not lo <= v <= hi:
        return None
    return int(v) if kind == "count" else v


def _accepted(spec: Mapping[str, Any]) -> str:
    lo, hi = spec.get("min"), spec.get("max")
    if lo is not None and hi is not None:
        return f"{lo} to {hi}"
    return f"at least {lo}" if lo is not None else "a number"
