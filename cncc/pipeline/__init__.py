"""The one pipeline: which passes run, in which order, with which options, and how.

* :mod:`cncc.pipeline.builder` makes every list of passes the compiler runs -- the path
  stage after the front end, the language server's light variant, the frame passes alone,
  and the planning stage (blend, plan, verify) -- from a :class:`PipelineConfig`, reading
  the pass registry of :mod:`cncc.passes` by name.  ``-p 'name{opt=value},...'``
  (:mod:`cncc.pipeline.spec`) replaces the default list.
* :mod:`cncc.pipeline.manager` runs a list: plainly chained, or instrumented with
  ``--verify-each`` (:mod:`cncc.pipeline.invariants`), ``--print-after`` and
  ``--time-passes``.

The driver (CLI and :mod:`cncc.api`), the language server and the batch runner (through
:mod:`cncc.api`) all get their passes here; ``tests/pipeline/test_builder.py`` checks that
no other module makes pass objects.
"""

from cncc.pipeline.builder import PipelineConfig

__all__ = ["PipelineConfig"]
