"""A readable dump of IR commands with their source lines (``--emit=ir``)."""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from dataclasses import fields

from cncc.ir import PROGRAMMED, Command
from cncc.source import SourceMap

_SKIP = {"span", "frame"}


def _fmt(v: object) -> str:
    if isinstance(v, float):
        return f"{v:.4f}".rstrip("0").rstrip(".") if v == v else "nan"
    if isinstance(v, tuple):
        return "(" + ", ".join(_fmt(x) for x in v) + ")"
    if hasattr(v, "name") and hasattr(v, "value") and type(v).__module__.startswith("cncc"):
        return str(v.name)
    return repr(v) if isinstance(v, str) else str(v)


def dump_ir(cmds: Iterable[Command], sources: SourceMap) -> Iterator[str]:
    for c in cmds:
        where = sources.describe(c.span)
        src = sources.get(c.span.source_id)
        text = ""
        if src is not None:
            text = src.line_text(src.position(c.span.start).line).strip()
        parts = []
        for f in fields(c):
            if f.name in _SKIP:
                continue
            val = getattr(c, f.name)
            if f.name == "motion" or (f.name == "origin" and val == PROGRAMMED):
                continue
            parts.append(f"{f.name}={_fmt(val)}")
        yield f"{where}: {type(c).__name__}({', '.join(parts)})  ; {text}\n"
