"""The core handler table: composed once from every module that registers core ops.

The composition root of the front end's ops.  It imports the registering modules in a
fixed order and freezes the result; the block hooks run in that order whoever imported
first (RS274's arc-centre and inverse-time hooks, then the lone H/D words of
``transforms``).  An op registered by two modules takes the later one's handler; every
registering module imports :mod:`~cncc.frontend.ops` first, so its own handlers win over
the core ones (no op is registered twice today).  No registering module imports this one, and :mod:`cncc.frontend.ops`
imports none of them, so the modules form no import circle (tests/test_layers.py).

A dialect layer builds on :func:`core_table` (``series8/front.py``:
``LAYER.compose(core_table())``).
"""

from __future__ import annotations

import functools
from types import MappingProxyType

from cncc.frontend import (
    cycles,  # canned cycles; guards around the plane and spindle ops
    holes,  # G134/G135/G136/G137.1 hole patterns
    mcodes,  # machine M codes, smoothing, G54.1/G154 P
    ops,  # the core G and M codes, motions and the block driver
    rs274,  # LinuxCNC/grbl G61, G92.1, G10 L20 ...
    rs274_curves,  # G5, G5.1, G5.2/G5.3
    rs274_g10,  # G10 with LinuxCNC's tables
    rs274_io,  # M62-M68 digital and analog I/O
    rs274_probe,  # G38.2 - G38.5
    rs274_sync,  # G33, G33.1
    rs274_tools,  # M61
    rs274_words,  # @ ^ polar words, $ spindle number
    saved_points,  # SZGH G25, G61, G26
    transforms,  # G10, G15/G16, G41/G42, G43, G51 ...
)
from cncc.frontend.linuxcnc import g76, lathe  # LinuxCNC G7/G8 and G76
from cncc.frontend.registry import BLOCK_HOOKS, HANDLERS, MOTIONS, ORDER, HandlerTable

REGISTERING_MODULES = (ops, cycles, holes, mcodes, rs274, rs274_g10, rs274_curves, rs274_sync, rs274_probe,
                       rs274_io, rs274_tools, rs274_words, saved_points,
                       transforms, lathe, g76)


_RANK = {m.__name__: k for k, m in enumerate(REGISTERING_MODULES)}


@functools.cache
def core_table() -> HandlerTable:
    """The shared table, frozen: read-only copies of what the modules above registered.

    The block hooks run in the order of :data:`REGISTERING_MODULES` (each module's own in
    the order it added them), not in the order a process happened to import the modules."""
    hooks = sorted(BLOCK_HOOKS, key=lambda h: _RANK.get(h.__module__, len(_RANK)))
    return HandlerTable(MappingProxyType(dict(HANDLERS)), MappingProxyType(dict(MOTIONS)), tuple(hooks),
                        MappingProxyType(dict(ORDER)))


__all__ = ["REGISTERING_MODULES", "core_table"]
