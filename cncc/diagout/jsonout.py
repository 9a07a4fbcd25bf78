"""``-fdiagnostics-format=json``: one JSON document on standard error, described by ``schema.json``."""

from __future__ import annotations

import json
from collections.abc import Iterable
from importlib import resources
from typing import Any

from cncc.diagnostics import CODES, Diagnostic, Severity
from cncc.diagout.locate import Place, place
from cncc.source import SourceMap

SCHEMA_ID = "cncc-diagnostics/1"


def schema() -> dict[str, Any]:
    """The JSON Schema (draft 2020-12) of the document."""
    doc: dict[str, Any] = json.loads(resources.files(__package__).joinpath("schema.json").read_text("utf-8"))
    return doc


def _where(p: Place) -> dict[str, Any]:
    end = None if p.end_line is None else {"line": p.end_line, "column": p.end_column}
    return {"file": p.file, "line": p.line, "column": p.column, "end": end}


def document(diags: Iterable[Diagnostic], sources: SourceMap) -> dict[str, Any]:
    items = []
    for d in diags:
        info = CODES.get(d.code)
        items.append({
            **_where(place(sources, d.span)),
            "severity": d.severity.label,
            "code": d.code,
            "message": d.message,
            "summary": info.summary if info is not None else "",
            "related": [{**_where(place(sources, r.span)), "message": r.message} for r in d.related],
        })
    return {
        "schema": SCHEMA_ID,
        "diagnostics": items,
        "errors": sum(1 for i in items if i["severity"] == Severity.ERROR.label),
        "warnings": sum(1 for i in items if i["severity"] == Severity.WARNING.label),
    }


def render_json(diags: Iterable[Diagnostic], sources: SourceMap) -> str:
    return json.dumps(document(diags, sources), indent=1) + "\n"
