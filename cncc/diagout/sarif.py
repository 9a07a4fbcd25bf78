"""``-fdiagnostics-format=sarif``: SARIF 2.1.0 (OASIS), ready for code-scanning upload.

One run; the rules are the diagnostic codes that occur (id, summary, default level);
each result names its rule, level, message and location (region with 1-based lines
and columns counted in Unicode code points, ``columnKind``), and related spans as
``relatedLocations``.  File names are written as relative URI references when they
are relative (code scanning resolves them against the checkout), else as ``file://``
URIs.  Diagnostics without a position (the command line) have no location.
"""

from __future__ import annotations

import json
import os
from collections.abc import Iterable
from typing import Any
from urllib.parse import quote

from cncc import __version__
from cncc.diagnostics import CODES, Diagnostic, Severity
from cncc.diagout.locate import Place, place
from cncc.source import SourceMap, Span

SARIF_SCHEMA = "https://json.schemastore.org/sarif-2.1.0.json"
LEVEL = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.NOTE: "note"}


def uri(name: str) -> str:
    if os.path.isabs(name):
        return "file://" + quote(name.replace(os.sep, "/"))
    return quote(name.replace(os.sep, "/"))


def _physical(p: Place, artifacts: dict[str, int]) -> dict[str, Any]:
    assert p.file is not None
    index = artifacts.setdefault(p.file, len(artifacts))
    region: dict[str, Any] = {"startLine": p.line, "startColumn": p.column}
    if p.end_line is not None and p.end_column is not None:
        region.update(endLine=p.end_line, endColumn=max(p.end_column, 1))
    return {"artifactLocation": {"uri": uri(p.file), "index": index}, "region": region}


def _location(sources: SourceMap, span: Span, artifacts: dict[str, int], message: str | None = None,
              ident: int | None = None) -> dict[str, Any] | None:
    p = place(sources, span)
    if p.file is None:
        return None
    loc: dict[str, Any] = {"physicalLocation": _physical(p, artifacts)}
    if ident is not None:
        loc["id"] = ident
    if message is not None:
        loc["message"] = {"text": message}
    return loc


def sarif_log(diags: Iterable[Diagnostic], sources: SourceMap) -> dict[str, Any]:
    diags = list(diags)
    codes = list(dict.fromkeys(d.code for d in diags))
    rule_index = {c: i for i, c in enumerate(codes)}
    rules = []
    for c in codes:
        info = CODES.get(c)
        rule: dict[str, Any] = {"id": c, "shortDescription": {"text": info.summary if info else c}}
        if info is not None:
            rule["defaultConfiguration"] = {"level": LEVEL[info.severity]}
        rules.append(rule)
    artifacts: dict[str, int] = {}
    results = []
    for d in diags:
        res: dict[str, Any] = {"ruleId": d.code, "ruleIndex": rule_index[d.code], "level": LEVEL[d.severity],
                               "message": {"text": d.message}}
        loc = _location(sources, d.span, artifacts)
        if loc is not None:
            res["locations"] = [loc]
        related = [r for r in (_location(sources, rel.span, artifacts, rel.message, i)
                               for i, rel in enumerate(d.related)) if r is not None]
        if related:
            res["relatedLocations"] = related
        results.append(res)
    run = {
        "tool": {"driver": {"name": "cncc", "version": __version__, "rules": rules}},
        "artifacts": [{"location": {"uri": uri(name)}} for name in artifacts],
        "columnKind": "unicodeCodePoints",
        "results": results,
    }
    return {"$schema": SARIF_SCHEMA, "version": "2.1.0", "runs": [run]}


def render_sarif(diags: Iterable[Diagnostic], sources: SourceMap) -> str:
    return json.dumps(sarif_log(diags, sources), indent=1) + "\n"
