"""The op catalogue: how each front-end op runs within a block, read once from data.

``cncc/frontend/op_catalogue.toml`` holds, per op: its rank within a block
(:data:`ORDER`, :data:`DEFAULT_ORDER`), the M ops that run before the G codes
(:data:`M_ORDER`), the M groups (:func:`m_group`), the ops that take the block's axis
words (:data:`AXIS_TAKERS`) and the ops the macro executor runs itself
(:data:`EXEC_OPS`).  The interpreter, the block driver, the macro executor and the
fast path read these tables; none of them keeps its own list.
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass
from importlib import resources
from types import MappingProxyType
from typing import Any


class CatalogueError(ValueError):
    """The op catalogue is malformed (message names the key)."""


@dataclass(frozen=True, slots=True)
class Catalogue:
    order: MappingProxyType[str, int]
    default_order: int
    m_order: MappingProxyType[str, int]
    m_groups: tuple[tuple[str, tuple[str, ...], str], ...]  # (group, ops, prefix)
    axis_takers: frozenset[str]
    exec_ops: frozenset[str]

    def m_group(self, op: str) -> str:
        """The M group of ``op`` ("other" when it is in none)."""
        for name, ops, prefix in self.m_groups:
            if op in ops or (prefix and op.startswith(prefix)):
                return name
        return "other"


def _ranks(raw: Any, where: str) -> MappingProxyType[str, int]:
    if not isinstance(raw, dict) or not all(isinstance(v, int) for v in raw.values()):
        raise CatalogueError(f"{where}: expected a table of op = integer rank")
    return MappingProxyType({str(k): int(v) for k, v in raw.items()})


def _ops(raw: Any, where: str) -> tuple[str, ...]:
    if not isinstance(raw, list) or not all(isinstance(v, str) for v in raw):
        raise CatalogueError(f"{where}: expected a list of op names")
    return tuple(raw)


def parse_catalogue(raw: dict[str, Any]) -> Catalogue:
    groups = []
    for name, entry in raw.get("m_group", {}).items():
        if not isinstance(entry, dict) or not ({"ops", "prefix"} & set(entry)):
            raise CatalogueError(f"m_group.{name}: give 'ops' or 'prefix'")
        groups.append((str(name), _ops(entry.get("ops", []), f"m_group.{name}.ops"), str(entry.get("prefix", ""))))
    return Catalogue(
        order=_ranks(raw.get("order", {}), "order"),
        default_order=int(raw.get("default_order", 90)),
        m_order=_ranks(raw.get("m_order", {}), "m_order"),
        m_groups=tuple(groups),
        axis_takers=frozenset(_ops(raw.get("axis", {}).get("takes", []), "axis.takes")),
        exec_ops=frozenset(_ops(raw.get("exec", {}).get("ops", []), "exec.ops")),
    )


def _load() -> Catalogue:
    text = resources.files(__package__).joinpath("op_catalogue.toml").read_text(encoding="utf-8")
    return parse_catalogue(tomllib.loads(text))


CATALOGUE = _load()
ORDER = CATALOGUE.order
DEFAULT_ORDER = CATALOGUE.default_order
M_ORDER = CATALOGUE.m_order
AXIS_TAKERS = CATALOGUE.axis_takers
EXEC_OPS = CATALOGUE.exec_ops
m_group = CATALOGUE.m_group

__all__ = ["AXIS_TAKERS", "CATALOGUE", "DEFAULT_ORDER", "EXEC_OPS", "M_ORDER", "ORDER", "Catalogue", "m_group",
           "parse_catalogue"]
