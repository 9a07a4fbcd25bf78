"""The core IR's CycleKind holds the kinds every dialect may use; SERIES 8's own kinds live in its
layer (cncc/dialects/series8_cycles.py), and every cycle a dialect table names has a kind and an expansion."""

from __future__ import annotations

import cncc.driver  # noqa: F401  (the front end, imported in its own order: frontend/ops.py has an import circle)
from cncc.dialects import available, load_dialect
from cncc.dialects.series8_cycles import Series8CycleKind
from cncc.ir import CycleKind, CycleKindBase, cycle_kind
from cncc.passes.expand_cycles import SEQUENCES

# SERIES 8's own sequences (spec series8.md 4.14: G83 with I/J, G86-G89 as SERIES 8 defines them)
SERIES8_ONLY = {"peck_first", "bore_dwell_stop_out", "bore_dwell_stop_rapid_out", "case_bore", "bore_orient_out",
                "bore_orient_rapid_out", "back_bore_return"}


def _cycle_names(dialect: str) -> set[str]:
    return {c.cycle for c in load_dialect(dialect).codes.values() if c.op == "cycle" and c.cycle}


def test_series8_kinds_are_not_core_kinds() -> None:
    assert {k.value for k in Series8CycleKind} == SERIES8_ONLY
    assert not SERIES8_ONLY & {k.value for k in CycleKind}
    assert issubclass(Series8CycleKind, CycleKindBase) and issubclass(CycleKind, CycleKindBase)


def test_other_dialects_name_only_core_kinds() -> None:
    core = {k.value for k in CycleKind}
    for d in available():
        if d != "series8":
            assert _cycle_names(d) <= core, d


def _kind_of(name: str) -> CycleKindBase | None:
    import cncc.frontend.ops  # noqa: F401  (first: frontend/ops.py sits in an import circle, issue 16)
    from cncc.frontend.series8.cycles import kind_of

    return kind_of(name)


def test_every_series8_cycle_has_a_kind_and_an_expansion() -> None:
    names = _cycle_names("series8")
    assert names | {"bore_dwell_stop_rapid_out", "bore_orient_rapid_out"} >= SERIES8_ONLY  # the rapid-out readings
    for name in names | SERIES8_ONLY:
        kind = _kind_of(name)
        assert kind is not None and kind is cycle_kind(name), name
        assert kind in SEQUENCES, name


def test_an_unknown_kind_is_none() -> None:
    assert _kind_of("no_such_cycle") is None and cycle_kind("no_such_cycle") is None
