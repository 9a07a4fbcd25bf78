"""The VS Code extension (editors/vscode) registers the ``gcode`` language for the G-code
extensions the server's dialects use and starts ``cncc lsp`` (issue 20).  Packaging it
(scripts/package-vscode.sh, which needs npm and the registry) is not run here."""

from __future__ import annotations

import json
from pathlib import Path

from cncc.dialects import load_dialect

EXT = Path(__file__).resolve().parents[2] / "editors" / "vscode"


def manifest() -> dict[str, object]:
    data: dict[str, object] = json.loads((EXT / "package.json").read_text(encoding="utf-8"))
    return data


def test_the_gcode_language_and_its_extensions() -> None:
    m = manifest()
    (lang,) = m["contributes"]["languages"]  # type: ignore[index]
    assert lang["id"] == "gcode"
    exts = set(lang["extensions"])
    assert {".nc", ".cnc", ".tap", ".ngc", ".gcode"} <= exts
    for name in ("linuxcnc", "grbl"):  # the extensions detection relies on open as gcode
        claimed = {e for e in load_dialect(name).extensions if e in (".ngc", ".gcode")}
        assert claimed <= exts
    assert (EXT / lang["configuration"]).exists()


def test_the_server_command_and_no_dialect_in_it() -> None:
    m = manifest()
    props = m["contributes"]["configuration"]["properties"]  # type: ignore[index]
    assert props["cncc.server.path"]["default"] == "cncc"
    assert props["cncc.server.args"]["default"] == ["lsp"]
    main = (EXT / str(m["main"])).read_text(encoding="utf-8")
    assert 'language: "gcode"' in main and "initializationOptions" not in main  # the server detects dialects
    assert f"{m['publisher']}.{m['name']}" == "cncc.cncc-gcode"  # the id docs/editors.md names
    docs = (EXT.parents[1] / "docs" / "editors.md").read_text(encoding="utf-8")
    assert "cncc.cncc-gcode" in docs
