"""The op catalogue (cncc/frontend/op_catalogue.toml) is the one table of in-block order,
M groups, axis-word takers and executor ops, and it names only ops the dialects use."""

from __future__ import annotations

import tomllib

import pytest

from cncc.dialects import available, load_dialect
from cncc.frontend import catalogue
from cncc.frontend.catalogue import CatalogueError, parse_catalogue

TEXT = '''
default_order = 90
[order]
dwell = 40
[m_order]
tool_change = 0
spindle_cw = 1
[m_group.spindle]
prefix = "spindle"
[m_group.stop]
ops = ["program_end"]
[axis]
takes = ["set_origin"]
[exec]
ops = ["jump"]
'''


def test_the_catalogue_reads_its_toml() -> None:
    c = parse_catalogue(tomllib.loads(TEXT))
    assert dict(c.order) == {"dwell": 40} and c.default_order == 90
    assert dict(c.m_order) == {"tool_change": 0, "spindle_cw": 1}
    assert c.m_group("spindle_orient") == "spindle" and c.m_group("program_end") == "stop"
    assert c.m_group("coolant_flood") == "other"
    assert c.axis_takers == {"set_origin"} and c.exec_ops == {"jump"}
    with pytest.raises(CatalogueError, match="order"):
        parse_catalogue({"order": {"dwell": "early"}})
    with pytest.raises(CatalogueError, match=r"m_group\.x"):
        parse_catalogue({"m_group": {"x": {}}})


def test_the_catalogue_names_only_ops_the_dialects_use() -> None:
    used = {c.op for n in available() for c in load_dialect(n).codes.values()}
    c = catalogue.CATALOGUE
    named = set(c.order) | set(c.m_order) | c.axis_takers | c.exec_ops | {op for _, ops, _ in c.m_groups for op in ops}
    assert named - used == set()


def test_the_readers_take_the_catalogues_tables() -> None:
    from cncc.frontend import handler_tables, interp, ops, registry
    from cncc.frontend.macro import executor

    assert registry.ORDER is catalogue.ORDER and registry.DEFAULT_ORDER == catalogue.DEFAULT_ORDER
    assert dict(handler_tables.core_table().order) == dict(catalogue.ORDER)
    assert ops.M_ORDER is catalogue.M_ORDER and ops.AXIS_TAKERS is catalogue.AXIS_TAKERS
    assert executor.EXEC_OPS is catalogue.EXEC_OPS
    assert interp.m_group is catalogue.m_group
