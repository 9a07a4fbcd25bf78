"""Tables derived from a dialect live on the Dialect object, not in caches keyed by its name.

A user dialect file may be called like a built-in one (``name = "syntec"``) and still
declare its own codes; the fast path and the macro executor must see those codes.
"""

from __future__ import annotations

import tomllib
from importlib import resources
from pathlib import Path

from cncc.api import compile_commands
from cncc.dialects import load_dialect
from cncc.frontend.fastpath import is_straight_line
from cncc.frontend.macro import needs_executor
from cncc.ir import Linear

# G200 is no SYNTEC code; the user file declares it as a macro call (as G65: P names the program).
EXTRA = '\n[[g]]\ncode = "G200"\ngroup = "non_modal"\nop = "macro_call"\nsummary = "Own macro call."\n'
# Straight-line text apart from G200: the called program is a file in an -I folder.
PROGRAM = "G90 G00 X0. Y0. Z0.\nG01 X1. F100.\nG200 P9001\nG01 X2.\nM30\n"
CALLED = "O9001\nG01 X7. Y8. F100.\nM99\n"


def _user_syntec(tmp_path: Path) -> Path:
    text = resources.files("cncc.dialects").joinpath("syntec.toml").read_text(encoding="utf-8")
    path = tmp_path / "syntec.toml"
    path.write_text(text + EXTRA, encoding="utf-8")
    assert tomllib.loads(path.read_text())["name"] == "syntec"  # same name as the built-in
    return path


def test_user_dialect_named_like_a_builtin_runs_its_own_macro_call(tmp_path: Path) -> None:
    path = _user_syntec(tmp_path)
    builtin = load_dialect("syntec")
    plain = "G00 X0 Y0\nG01 X1 F100\nG01 X2\n"
    # warm the built-in dialect's tables first (what a long-running process has done already)
    assert is_straight_line(plain, builtin)
    assert not needs_executor(plain, builtin)
    (tmp_path / "O9001").write_text(CALLED, encoding="utf-8")

    cmds, r = compile_commands(PROGRAM, dialect=str(path), include_dirs=[str(tmp_path)])
    assert r.ok, [(d.code, d.message) for d in r.sink]
    ends = [tuple(c.end[:2]) for c in cmds if isinstance(c, Linear)]
    assert (7.0, 8.0) in ends  # the called program O9001 ran


def test_derived_tables_belong_to_each_dialect_object(tmp_path: Path) -> None:
    from cncc.driver import dialect_file

    user = dialect_file(str(_user_syntec(tmp_path)))
    builtin = load_dialect("syntec")
    text = "G01 X1 F100\nG200 P9001\n"
    assert is_straight_line(text, builtin)  # G200 means nothing to the built-in SYNTEC
    assert not is_straight_line(text, user)
    assert needs_executor(text, user)
    assert not needs_executor(text, builtin)
    # an option override is a new dialect object with its own (fresh) tables
    assert needs_executor(text, user.with_options({}))
