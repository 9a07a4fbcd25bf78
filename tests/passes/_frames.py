"""Helpers for the frame and compensation tests: run a program, look at the tool path."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from cncc.ir import Arc, Linear, Rapid
from tests.helpers import compile_commands


def tools_file(tmp: Path, entries: dict[int, tuple[float, float]], units: str = "mm") -> str:
    """A TOML tool table: number -> (length, radius)."""
    lines = [f'units = "{units}"']
    for n, (length, radius) in entries.items():
        lines += [f"[tools.{n}]", f"length_mm = {length!r}", f"radius_mm = {radius!r}"]
    path = tmp / "tools.toml"
    path.write_text("\n".join(lines) + "\n")
    return str(path)


def path(text: str, dialect: str = "syntec", **opts: Any) -> tuple[list[Any], list[str]]:
    """(motions after the path passes, diagnostic codes).  Program coordinates unless
    ``emit="timing"`` asks for machine coordinates."""
    cmds, r = compile_commands(text, dialect=dialect, **opts)
    return [c for c in cmds if isinstance(c, Rapid | Linear | Arc)], [d.code for d in r.sink]


def ends(motions: list[Any], plane: bool = True) -> list[tuple[float, ...]]:
    """End points (XY, or XYZ with ``plane=False``), rounded to 4 decimals."""
    n = 2 if plane else 3
    return [tuple(round(v, 4) + 0.0 for v in m.end[:n]) for m in motions]


def close(a: tuple[float, ...], b: tuple[float, ...], tol: float = 1e-3) -> bool:
    return len(a) == len(b) and all(abs(x - y) <= tol for x, y in zip(a, b, strict=True))


def has_point(points: list[tuple[float, ...]], p: tuple[float, ...], tol: float = 1e-3) -> bool:
    return any(close(q, p, tol) for q in points)
