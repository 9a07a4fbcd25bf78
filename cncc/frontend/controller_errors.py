"""The controller's own error texts: a dialect's ``[errors]`` table, with cncc's default beside it.

LinuxCNC's rs274 rejects a block with a message of its own; the ``linuxcnc`` dialect lists
those messages by key, so cncc's E0250 says what the controller would say.  Every module
that rejects a block for the controller uses these two (imports nothing of the front end).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from cncc import diagnostics as dg

if TYPE_CHECKING:
    from cncc.frontend.interp import Interpreter
    from cncc.source import Span


def controller_error(it: Interpreter, key: str, default: str) -> str:
    """The controller's own text for error ``key`` (dialect ``[errors]``), else ``default``."""
    return str(it.dialect.raw.get("errors", {}).get(key, default))


def reject(it: Interpreter, span: Span, key: str, default: str) -> bool:
    """The controller rejects the block with its own text (E0250); False, for ``return reject(...)``."""
    it.emit_error(dg.CONTROLLER_REJECTS, span, controller_error(it, key, default))
    return False
