"""The backend stage: the path stage's items to the output ``--emit`` names.

* :mod:`cncc.emit.dispatch` -- :func:`run_backend`, the table from ``--emit=KIND`` to the backend call.
* :mod:`cncc.emit.gcode` -- ``--emit=gcode``: the target dialect (``-t``), what the translation keeps
  (cycles, transforms) before the path passes, the emitter's options.
* :mod:`cncc.emit.timing` -- ``--emit=timing``: one planned run per report column.
* :mod:`cncc.emit.pulses` -- ``--emit=pulses``: its options, plan, step/dir pulses to stdout or ``-o``.
* :mod:`cncc.emit.plan` -- :func:`plan_trajectory`, the planning stage the timing and pulse backends
  (and the language server's hints) run.

Each module imports its backend (:mod:`cncc.backends`) when it is called, so ``cncc --help`` does not
import numpy.  The driver (:mod:`cncc.driver`) calls this stage; it imports nothing above itself.
"""
