"""The SERIES 8 layer over the shared handler table.

The SERIES 8 modules register their ops, wrappers, block hooks and op order here, not
in :mod:`cncc.frontend.ops`'s shared tables: ``front.handler_table()`` composes a copy
for SERIES 8 interpreters only, so other dialects never run through SERIES 8 code
(tests/dialects/test_series8_isolation.py).
"""

from __future__ import annotations

from cncc.frontend import ops

LAYER = ops.Layer()
