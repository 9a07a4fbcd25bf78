"""Shared test helpers: compile a program and look at its canon trace."""

from __future__ import annotations

import contextlib
import re
from typing import Any

from cncc.api import compile_commands, compile_text
from cncc.driver import Result

_CALL = re.compile(r"^ N\.\.\.\.\. (\w+)\((.*)\)$")
STARTUP = 6  # lines of the canon start-up sequence


def canon(text: str, dialect: str = "syntec", **opts: Any) -> tuple[list[str], Result]:
    """Canon lines after the start-up sequence, and the result."""
    r = compile_text(text, dialect=dialect, emit="canon", **opts)
    lines = r.output.splitlines()[STARTUP:]
    return lines, r


def calls(lines: list[str], *names: str) -> list[tuple[str, list[float]]]:
    """(name, numeric args) of the calls whose name is in ``names`` (all if none)."""
    out = []
    for ln in lines:
        m = _CALL.match(ln)
        if m is None:
            continue
        if names and m.group(1) not in names:
            continue
        args = []
        for a in m.group(2).split(","):
            a = a.strip()
            with contextlib.suppress(ValueError):
                args.append(float(a))
        out.append((m.group(1), args))
    return out


def moves(text: str, dialect: str = "syntec", **opts: Any) -> list[tuple[str, tuple[float, ...]]]:
    """(kind, XYZ end point) of every STRAIGHT_TRAVERSE / STRAIGHT_FEED / ARC_FEED."""
    lines, _ = canon(text, dialect, **opts)
    out = []
    for name, args in calls(lines, "STRAIGHT_TRAVERSE", "STRAIGHT_FEED", "ARC_FEED"):
        if name == "ARC_FEED":
            out.append((name, tuple(args)))
        else:
            out.append((name, tuple(args[:3])))
    return out


def codes(r: Result) -> list[str]:
    return [d.code for d in r.sink]


__all__ = ["calls", "canon", "codes", "compile_commands", "compile_text", "moves"]


def nominal(text: str, dialect: str = "syntec", **opts: Any) -> Any:
    """Nominal (-O0) timing of the compiled commands (``.total_s``, ``.by_category_s``)."""
    from cncc.backends.nominal import nominal_timing
    from cncc.diagnostics import DiagnosticSink
    from cncc.driver import resolve_machine

    cmds, r = compile_commands(text, dialect=dialect, **opts)
    assert r.ok, [(d.code, d.message) for d in r.sink]
    machine = resolve_machine(opts.get("machine", "generic-mill"), DiagnosticSink())
    assert machine is not None
    return nominal_timing(cmds, machine)
