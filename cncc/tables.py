"""Offset and tool tables given on the command line (``--offsets``, ``--tools``).

Offsets (TOML)::

    units = "mm"            # or "inch", or "um" (micrometres, as SZGH stores tool data)
    [work.G54]              # also G55 ... G59, G59.1 ... G59.9, or the index 1 ... 15
    X = 100.0
    Y = 50.0
    Z = -20.0

Tools (TOML), keyed by offset number (the H and D words)::

    units = "mm"
    [tools.1]
    length_mm = 50.0
    radius_mm = 5.0

Tools may also be a LinuxCNC tool table (``.tbl``: ``T1 P1 Z+50.0 D10.0 ;comment``,
D is the diameter).  Missing entries read as zero.
"""

from __future__ import annotations

import tomllib
from typing import Any

Vec6 = tuple[float, float, float, float, float, float]
_WORK_INDEX = {f"G{54 + i}": i + 1 for i in range(6)} | {f"G59.{k}": 6 + k for k in range(1, 10)}


class TableError(ValueError):
    """A table file is malformed; the message names the file and key."""


def _load_toml(path: str) -> dict[str, Any]:
    try:
        with open(path, "rb") as fh:
            return tomllib.load(fh)
    except OSError as exc:
        raise TableError(f"{path}: cannot read: {exc.strerror or exc}") from None
    except tomllib.TOMLDecodeError as exc:
        raise TableError(f"{path}: {exc}") from None


def _scale(path: str, raw: dict[str, Any]) -> float:
    units = raw.get("units", "mm")
    scale = {"mm": 1.0, "inch": 25.4, "um": 0.001}  # "um": SZGH keeps tool data in micrometres
    if units not in scale:
        raise TableError(f"{path}: units: expected 'mm', 'inch' or 'um', got {units!r}")
    return scale[units]


def _number(path: str, key: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise TableError(f"{path}: {key}: expected a number, got {value!r}")
    return float(value)


def read_offsets(path: str) -> dict[int, Vec6]:
    raw = _load_toml(path)
    k = _scale(path, raw)
    out: dict[int, Vec6] = {}
    work = raw.get("work", {})
    if not isinstance(work, dict):
        raise TableError(f"{path}: work: expected a table")
    for name, entry in work.items():
        index = _WORK_INDEX.get(name.upper()) if not name.isdigit() else int(name)
        if index is None or not 1 <= index <= 15:
            raise TableError(f"{path}: work.{name}: not a work coordinate system (G54 ... G59.9 or 1 ... 15)")
        if not isinstance(entry, dict):
            raise TableError(f"{path}: work.{name}: expected a table of axis values")
        vals = [0.0] * 6
        for axis, value in entry.items():
            pos = "XYZABC".find(axis.upper())
            if pos < 0 or len(axis) != 1:
                raise TableError(f"{path}: work.{name}.{axis}: unknown axis")
            v = _number(path, f"work.{name}.{axis}", value)
            vals[pos] = v * k if pos < 3 else v
        out[index] = (vals[0], vals[1], vals[2], vals[3], vals[4], vals[5])
    return out


def read_tools(path: str) -> tuple[dict[int, float], dict[int, float]]:
    """(length by H number, radius by D number), in mm."""
    if path.endswith(".tbl"):
        return _read_tbl(path)
    raw = _load_toml(path)
    k = _scale(path, raw)
    lengths: dict[int, float] = {}
    radii: dict[int, float] = {}
    tools = raw.get("tools", {})
    if not isinstance(tools, dict):
        raise TableError(f"{path}: tools: expected a table")
    for num, entry in tools.items():
        if not num.isdigit():
            raise TableError(f"{path}: tools.{num}: expected an offset number")
        if not isinstance(entry, dict):
            raise TableError(f"{path}: tools.{num}: expected a table")
        for key in entry:
            if key not in ("length_mm", "radius_mm", "length", "radius", "comment"):
                raise TableError(f"{path}: tools.{num}.{key}: unknown key (length_mm, radius_mm)")
        n = int(num)
        if "length_mm" in entry or "length" in entry:
            key = "length_mm" if "length_mm" in entry else "length"
            lengths[n] = _number(path, f"tools.{num}.{key}", entry[key]) * k
        if "radius_mm" in entry or "radius" in entry:
            key = "radius_mm" if "radius_mm" in entry else "radius"
            radii[n] = _number(path, f"tools.{num}.{key}", entry[key]) * k
    return lengths, radii


def _read_tbl(path: str) -> tuple[dict[int, float], dict[int, float]]:
    try:
        with open(path, encoding="utf-8", errors="replace") as fh:
            lines = fh.readlines()
    except OSError as exc:
        raise TableError(f"{path}: cannot read: {exc.strerror or exc}") from None
    lengths: dict[int, float] = {}
    radii: dict[int, float] = {}
    for no, line in enumerate(lines, 1):
        body = line.split(";", 1)[0].strip()
        if not body:
            continue
        fields: dict[str, float] = {}
        for tok in body.split():
            letter, value = tok[0].upper(), tok[1:]
            try:
                fields[letter] = float(value)
            except ValueError:
                raise TableError(f"{path}:{no}: bad field {tok!r}") from None
        if "T" not in fields:
            raise TableError(f"{path}:{no}: a tool line needs a T number")
        t = int(fields["T"])
        lengths[t] = fields.get("Z", 0.0)
        radii[t] = fields.get("D", 0.0) / 2.0
    return lengths, radii
