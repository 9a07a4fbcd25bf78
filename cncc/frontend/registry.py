"""The registration tables of the front end's ops, and the per-dialect handler tables.

``HANDLERS`` maps an op name (the ``op`` of a code in ``cncc/dialects/*.toml``) to a
function ``(interp, ctx, code) -> None``; ``MOTIONS`` maps a motion mode to the function
that lowers the block's end point; ``BLOCK_HOOKS`` run for words without a code (H, D
...); ``ORDER`` ranks the ops within one block.  The modules of the core language
(:mod:`~cncc.frontend.ops`, ``cycles``, ``holes``, ``mcodes``, ``rs274*``,
``saved_points``, ``transforms``) register into them when imported;
:mod:`cncc.frontend.handler_tables` imports them all, in a fixed order, and freezes the
result as the core :class:`HandlerTable`.  A dialect :class:`Layer` (SERIES 8:
``series8/layer.py``) composes its own copy over it.

This module imports none of the modules that register here, so there is no import
circle (tests/test_layers.py).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from types import MappingProxyType
from typing import TYPE_CHECKING

from cncc.dialects import CodeDef
from cncc.ir import Vec6

if TYPE_CHECKING:
    from cncc.frontend.interp import BlockContext, Interpreter

Handler = Callable[["Interpreter", "BlockContext", CodeDef], None]
MotionHandler = Callable[["Interpreter", "BlockContext", Vec6], None]
BlockHook = Callable[["Interpreter", "BlockContext"], None]
HANDLERS: dict[str, Handler] = {}
BLOCK_HOOKS: list[BlockHook] = []  # words without a code (H, D ...)
MOTIONS: dict[str, MotionHandler] = {}


def handler(*ops: str) -> Callable[[Handler], Handler]:
    def deco(fn: Handler) -> Handler:
        for op in ops:
            HANDLERS[op] = fn
        return fn

    return deco


# ---- handler tables per dialect ---------------------------------------------------
@dataclass(frozen=True, slots=True)
class HandlerTable:
    """What one interpreter dispatches through: op handlers, motion handlers, block
    hooks and the in-block order of ops.  ``handler_tables.core_table()`` is the shared
    one; a dialect layer composes its own copy (:meth:`Layer.compose`) instead of
    changing the shared one."""

    handlers: Mapping[str, Handler]
    motions: Mapping[str, MotionHandler]
    block_hooks: Sequence[BlockHook]
    order: Mapping[str, int]


class Layer:
    """A dialect's own handlers, wrappers, hooks and op order over a base table.

    Registering records a step; :meth:`compose` replays the steps on copies of the base
    table, so the base table and every other dialect's interpreters are untouched."""

    def __init__(self) -> None:
        self._steps: list[Callable[[dict[str, Handler], dict[str, MotionHandler], list[BlockHook],
                                    dict[str, int]], None]] = []

    def handler(self, *ops: str) -> Callable[[Handler], Handler]:
        def deco(fn: Handler) -> Handler:
            self._steps.append(lambda h, m, b, o: h.update(dict.fromkeys(ops, fn)))
            return fn

        return deco

    def wrap_handler(self, op: str, wrap: Callable[[Handler], Handler]) -> None:
        self._steps.append(lambda h, m, b, o: h.__setitem__(op, wrap(h[op])))

    def wrap_motion(self, mode: str, wrap: Callable[[MotionHandler], MotionHandler]) -> None:
        self._steps.append(lambda h, m, b, o: m.__setitem__(mode, wrap(m[mode])))

    def hook_first(self, hook: BlockHook) -> None:
        self._steps.append(lambda h, m, b, o: b.insert(0, hook))

    def set_order(self, op: str, rank: int) -> None:
        self._steps.append(lambda h, m, b, o: o.__setitem__(op, rank))

    def compose(self, base: HandlerTable) -> HandlerTable:
        handlers, motions = dict(base.handlers), dict(base.motions)
        hooks, order = list(base.block_hooks), dict(base.order)
        for step in self._steps:
            step(handlers, motions, hooks, order)
        return HandlerTable(MappingProxyType(handlers), MappingProxyType(motions), tuple(hooks),
                            MappingProxyType(order))


# Execution order of the ops within one block (lower runs first).
ORDER: dict[str, int] = {
    "feed_per_min": 10, "feed_per_rev": 10, "inverse_time": 10,
    "dwell": 40,
    "plane_xy": 50, "plane_zx": 50, "plane_yz": 50,
    "inch": 55, "metric": 55,
    "comp_off": 60, "comp_left": 60, "comp_right": 60,
    "length_plus": 65, "length_minus": 65, "length_off": 65,
    "work": 70,
    "exact_stop_mode": 75, "curve_mode": 75, "tapping_mode": 75, "continuous_mode": 75, "exact_stop_once": 75,
    "absolute": 80, "incremental": 80,
    "return_initial": 85, "return_r": 85,
    "css_on": 86, "css_off": 86,
    "polar_on": 87, "polar_off": 87, "scale_on": 87, "scale_off": 87, "mirror_on": 87, "mirror_off": 87,
    "rotate_on": 88, "rotate_off": 88,
}
DEFAULT_ORDER = 90  # non-modal and motion codes
