"""cncc: a compiler collection for CNC programs.

The public Python API is :func:`cncc.api.compile_text` and friends; see
``docs/api.md``.
"""

__version__ = "0.1.0"
