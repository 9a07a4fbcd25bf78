"""A SERIES 8 compile does not change how other dialects run later in the same process.

The SERIES 8 modules compose their own handler table (cncc/frontend/series8/layer.py)
instead of wrapping the shared one, so a SYNTEC/Fanuc/SZGH interpreter never calls a
SERIES 8 function, and its IR is the one a fresh process gives.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from cncc.api import compile_commands
from cncc.diagnostics import DiagnosticSink
from cncc.dialects import load_dialect
from cncc.frontend.handler_tables import core_table
from cncc.frontend.interp import Interpreter

ROOT = Path(__file__).resolve().parents[2]
SERIES8 = (ROOT / "examples" / "series8_part.nc").read_text(encoding="utf-8")
# Arcs, a dwell, cutter compensation, a canned cycle, incremental moves: the ops SERIES 8 wraps.
SYNTEC = ("G90 G17 G54\nG00 X0. Y0. Z5.\nG01 Z-1. F200.\nG02 X10. Y0. R5.\nG03 X0. Y0. I-5. J0.\n"
          "G04 X0.5\nG41 D1 G01 X5. Y5.\nG40 G01 X0. Y0.\nG00 Z5.\nG81 X10. Y10. Z-3. R1. F100.\nG80\n"
          "G91 G01 X1. Y1.\nG90\nM30\n")
FANUC = SYNTEC.replace("G04 X0.5", "G04 P500")
SZGH = "G90 G00 X0 Y0 Z5\nG01 Z-1 F200\nG02 X10 Y0 R5\nG04 X0.5\nG00 Z5\nG81 X10 Y10 Z-3 R1 F100\nG80\nM30\n"
OTHERS = (("syntec", SYNTEC), ("fanuc", FANUC), ("szgh", SZGH))

_SCRIPT = """
import sys
from cncc.api import compile_commands
if sys.argv[1] == "series8-first":
    cmds, r = compile_commands(sys.argv[2], dialect="series8")
    assert r.ok and cmds
for dialect, text in {others!r}:
    cmds, r = compile_commands(text, dialect=dialect)
    print(dialect, [d.code for d in r.sink])
    for c in cmds:
        print(repr(c))
"""


def _fresh(mode: str) -> str:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    out = subprocess.run([sys.executable, "-c", _SCRIPT.format(others=OTHERS), mode, SERIES8], env=env,
                         capture_output=True, text=True, check=True, cwd=ROOT)
    return out.stdout


def test_series8_first_gives_the_same_ir_for_other_dialects() -> None:
    alone = _fresh("alone")
    assert alone.count("Arc(") >= 3 and "Dwell(" in alone and alone.count("Linear(") >= 8
    assert _fresh("series8-first") == alone


def test_no_series8_function_on_other_dialects_call_path() -> None:
    cmds, r = compile_commands(SERIES8, dialect="series8")
    assert r.ok and cmds
    called: set[str] = set()

    def profile(frame: object, event: str, arg: object) -> None:
        if event == "call":
            called.add(frame.f_globals.get("__name__", ""))  # type: ignore[attr-defined]

    for dialect, text in OTHERS:
        sys.setprofile(profile)
        try:
            cmds, r = compile_commands(text, dialect=dialect)
        finally:
            sys.setprofile(None)
        assert cmds, dialect
        assert "cncc.frontend.ops" in called  # the profile does see the handlers
        s8 = sorted(m for m in called if m.startswith("cncc.frontend.series8"))
        assert not s8, (dialect, s8)
        called.clear()


def test_tables_other_dialects_use_hold_no_series8_function() -> None:
    compile_commands(SERIES8, dialect="series8")
    it = Interpreter(load_dialect("syntec"), DiagnosticSink())
    table = it.table
    assert table is core_table()
    fns = [*table.handlers.values(), *table.motions.values(), *table.block_hooks]
    assert not [f for f in fns if getattr(f, "__module__", "").startswith("cncc.frontend.series8")]
    assert "absolute_once" not in table.order  # a SERIES 8 op
