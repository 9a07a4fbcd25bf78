"""docs/cycles.md's cross-check table is generated from the code and must be current."""

from __future__ import annotations

from cncc.tools import cycletable


def test_cycle_table_is_current() -> None:
    doc = cycletable.DOC.read_text(encoding="utf-8")
    assert doc == cycletable.updated(doc), "docs/cycles.md is stale: run python -m cncc.tools.cycletable --write"


def test_table_covers_every_cycle_code_of_every_dialect() -> None:
    from cncc.dialects import available, load_dialect

    table = cycletable.table()
    for name in available():
        for c in load_dialect(name).codes.values():
            if c.op == "cycle":
                assert f"| {name} | {c.name} |" in table
