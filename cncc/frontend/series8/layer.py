"""The SERIES 8 layer over the shared handler table.

The SERIES 8 modules register their ops, wrappers, block hooks and op order here, not
in :mod:`cncc.frontend.ops`'s shared tables: :func:`handler_table` composes a copy for
SERIES 8 interpreters only, so other dialects never run through SERIES 8 code
(tests/dialects/test_series8_isolation.py).
"""

from __future__ import annotations

import functools

from cncc.frontend import ops

LAYER = ops.Layer()


@functools.cache
def handler_table() -> ops.HandlerTable:
    """The core table with the SERIES 8 layer on top (all SERIES 8 modules imported)."""
    from cncc.frontend.series8 import front as _front  # noqa: F401  (imports every registering module)

    return LAYER.compose(ops.core_table())
