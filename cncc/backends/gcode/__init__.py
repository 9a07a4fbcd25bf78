"""G-code emitter: IR commands -> program text in a target dialect (translation).

Driven by the target dialect's tables: each IR construct is written with the code
whose ``op`` means it in that dialect (:mod:`cncc.backends.gcode.target`).  The
driver decides which cycles stay whole (:func:`keep_problem`) and which transforms
cncc applies itself; ``docs/translation.md`` describes the whole translation.
"""

from cncc.backends.gcode.cycles import keep_problem
from cncc.backends.gcode.emit import EmitOptions, GcodeEmitter, emit_gcode
from cncc.backends.gcode.target import Target, make_target

__all__ = ["EmitOptions", "GcodeEmitter", "Target", "emit_gcode", "keep_problem", "make_target"]
