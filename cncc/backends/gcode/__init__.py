"""G-code emitter: IR commands -> program text in a target dialect.

Driven by the target dialect's tables: each IR construct is written with the code
whose ``op`` means it in that dialect (see :func:`cncc.backends.gcode.emit.emit_gcode`).
"""

from cncc.backends.gcode.emit import EmitOptions, emit_gcode

__all__ = ["EmitOptions", "emit_gcode"]
