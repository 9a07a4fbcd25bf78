"""Macro expressions of Fanuc macro B and SZGH, over a :class:`Variables` store.

The evaluation itself is :class:`cncc.frontend.evaluate.Evaluator` with the
flavour's tables (:data:`cncc.frontend.functions.FANUC` / ``SZGH``, chosen by the
store's layout); this module binds it to the variable store.  Fanuc macro B rules,
which the SZGH language follows:

* a vacant variable read on its own stays vacant (``#2 = #1`` keeps ``#2`` vacant);
* in arithmetic and functions a vacant value counts as 0;
* ``EQ``/``NE`` tell vacant from 0 (``#1 EQ #0`` is true only for a vacant ``#1``);
  the ordering comparisons ``GT GE LT LE`` read vacant as 0;
* the functions and operators are the flavour's table (:mod:`cncc.frontend.functions`).
"""

from __future__ import annotations

from cncc.frontend import evaluate
from cncc.frontend.functions import FLAVOURS
from cncc.frontend.macro.values import MacroError, Value, Variables
from cncc.frontend.syntax import Var


class Evaluator(evaluate.Evaluator):
    """Evaluates expressions against one variable store."""

    def __init__(self, variables: Variables) -> None:
        super().__init__(FLAVOURS[variables.layout.flavour], self._read, MacroError)
        self.vars = variables

    def _read(self, v: Var) -> Value:
        return self.vars.read(self.var_number(v), v.start, v.end)

    def var_number(self, v: Var) -> int:
        if v.index is None:
            raise MacroError("E0302", f"named variable #<{v.name}> is not part of this macro language",
                             v.start, v.end)
        return self.vars.number(self.number(v.index), v.start, v.end)


__all__ = ["Evaluator"]
