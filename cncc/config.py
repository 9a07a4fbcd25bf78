"""The project configuration, one resolver for the command line and the language server.

Where a setting of one program file comes from, lowest precedence first:

1. the built-in default;
2. ``cncc.toml``, the nearest one found walking up from the file's folder (the
   language server stops at the workspace root).  Top-level keys, or the same keys in a
   ``[cncc]`` table: ``dialect``, ``target``, ``machine``, ``offsets``, ``tools``, ``ini``,
   ``opt_level`` (also ``opt-level``) and an ``[options]`` table of dialect options.
   Relative paths are relative to the folder of ``cncc.toml``; ``[lsp]`` holds the
   editor's own settings;
3. the modeline ``(cncc: dialect=NAME)`` in the file's first 2000 characters;
4. the command line (``-x``, ``-t``, ``-m``, ``--offsets``, ``--tools``, ``--ini``, ``-O``,
   ``-fNAME=VALUE``) — or, in the editor, the client's settings (which a modeline
   still overrides, as before).

:func:`resolve` gives the values and, for ``-v``, where each came from.  A dialect
given nowhere is guessed from the file by the driver.
"""

from __future__ import annotations

import os
import re
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

CONFIG_NAME = "cncc.toml"
MODELINE_RE = re.compile(r"cncc\s*:\s*dialect\s*=\s*([\w./-]+)", re.IGNORECASE)
MODELINE_WINDOW = 2000  # characters at the start of a file where a modeline counts
PATH_KEYS = ("offsets", "tools", "ini")  # always file names
MAYBE_PATH_KEYS = ("dialect", "target", "machine")  # names, or a .toml file
KEYS = ("dialect", "target", "machine", "offsets", "tools", "ini", "opt_level", "options")


def find_config(folder: str, stop_at: str | None = None) -> str | None:
    """The nearest ``cncc.toml`` at or above ``folder`` (not above ``stop_at``)."""
    folder = os.path.abspath(folder)
    stop = os.path.abspath(stop_at) if stop_at else None
    while True:
        candidate = os.path.join(folder, CONFIG_NAME)
        if os.path.isfile(candidate):
            return candidate
        parent = os.path.dirname(folder)
        if parent == folder or (stop is not None and folder == stop):
            return None
        folder = parent


def read_config(path: str) -> tuple[dict[str, Any], str | None]:
    """The table in ``path`` and an error message (empty table when unreadable)."""
    try:
        with open(path, "rb") as fh:
            return tomllib.load(fh), None
    except (OSError, tomllib.TOMLDecodeError) as exc:
        return {}, f"{path}: {exc}"


def modeline(text: str) -> tuple[str, int] | None:
    """(dialect, character offset) of a ``(cncc: dialect=NAME)`` modeline near the top of ``text``."""
    m = MODELINE_RE.search(text[:MODELINE_WINDOW])
    return None if m is None else (m.group(1), m.start())


def project_table(data: Mapping[str, Any]) -> dict[str, Any]:
    """The project keys of a ``cncc.toml`` table (``[cncc]`` merged in, ``opt-level`` as ``opt_level``)."""
    flat = {k: v for k, v in data.items() if k not in ("cncc", "lsp")}
    sub = data.get("cncc")
    if isinstance(sub, dict):
        flat.update(sub)
    out: dict[str, Any] = {}
    for key in KEYS:
        alias = key.replace("_", "-")
        if key in flat or alias in flat:
            out[key] = flat[key] if key in flat else flat[alias]
    return out


@dataclass(slots=True)
class Resolved:
    """The settings of one file and where each came from (``origins``: key -> description)."""

    values: dict[str, Any] = field(default_factory=dict)
    origins: dict[str, str] = field(default_factory=dict)
    config_path: str | None = None
    errors: list[str] = field(default_factory=list)


def _from_file(value: Any, key: str, root: str) -> Any:
    if not isinstance(value, str) or not value:
        return value
    is_path = key in PATH_KEYS or value.endswith(".toml")
    if is_path and not os.path.isabs(value):
        return os.path.normpath(os.path.join(root, os.path.expanduser(value)))
    return value


def _checked(key: str, value: Any, where: str, errors: list[str]) -> Any:
    if key == "opt_level":
        if isinstance(value, int) and not isinstance(value, bool) and 0 <= value <= 3:
            return value
        errors.append(f"{where}: opt_level must be 0, 1, 2 or 3, not {value!r}")
        return None
    if key == "options":
        if isinstance(value, dict):
            return value
        errors.append(f"{where}: [options] must be a table of dialect options")
        return None
    if isinstance(value, str) and value:
        return value
    errors.append(f"{where}: {key} must be a non-empty string, not {value!r}")
    return None


def resolve(path: str | None, text: str, command_line: Mapping[str, Any], *,
            stop_at: str | None = None) -> Resolved:
    """The settings of the program ``path`` (``None``: standard input, no project file) with
    text ``text``: ``cncc.toml``, then the modeline, then ``command_line`` (keys of :data:`KEYS`;
    ``options`` merged key by key)."""
    out = Resolved()
    if path is not None:
        found = find_config(os.path.dirname(os.path.abspath(path)), stop_at)
        if found is not None:
            out.config_path = found
            data, error = read_config(found)
            if error is not None:
                out.errors.append(error)
            root = os.path.dirname(found)
            for key, raw in project_table(data).items():
                value = _checked(key, _from_file(raw, key, root), found, out.errors)
                if value is None:
                    continue
                if key == "options":
                    for name, v in value.items():
                        out.values.setdefault("options", {})[name] = v
                        out.origins[f"options.{name}"] = found
                else:
                    out.values[key] = value
                    out.origins[key] = found
    mode = modeline(text)
    if mode is not None:
        line = text.count("\n", 0, mode[1]) + 1
        out.values["dialect"] = mode[0]
        out.origins["dialect"] = f"the modeline at {path or '<stdin>'}:{line}"
    for key, value in command_line.items():
        if key == "options":
            for name, v in value.items():
                out.values.setdefault("options", {})[name] = v
                out.origins[f"options.{name}"] = "the command line"
        elif value is not None:
            out.values[key] = value
            out.origins[key] = "the command line"
    return out
