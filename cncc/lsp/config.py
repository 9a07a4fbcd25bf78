"""Server settings: ``cncc.toml`` in the workspace, initialization options, guesses.

Precedence, lowest first: built-in defaults, the ``cncc.toml`` found by walking up
from the document's folder (stopping at the workspace root), the client's
initialization options / ``workspace/didChangeConfiguration`` settings.  The dialect
of a document is then: a modeline in its first lines (``(cncc: dialect=szgh)``), the
configured dialect, the command line's guess from the content and the well-known
extensions (:mod:`cncc.frontend.detect`), SZGH's named programs, the one dialect
file that claims the extension, and finally the driver's default.
"""

from __future__ import annotations

import os
import tomllib
from dataclasses import dataclass, field, fields, replace
from typing import Any

from cncc.config import CONFIG_NAME, find_config, modeline, read_config
from cncc.dialects import Dialect, DialectError, available, load_dialect, parse_dialect

__all__ = ["CONFIG_NAME", "Settings", "find_config", "guess_dialect", "open_dialect", "read_config"]
DEFAULT_DIALECT = "syntec"


@dataclass(frozen=True, slots=True)
class Settings:
    dialect: str | None = None  # a built-in dialect name or a path to a dialect TOML
    target: str | None = None  # dialect the program is meant to run on (unsupported-code checks)
    machine: str | None = None
    offsets: str | None = None  # work offsets table (TOML)
    tools: str | None = None  # tool table
    opt_level: int = 0  # planner level of the inlay hints
    dialect_options: dict[str, Any] = field(default_factory=dict)
    debounce_ms: int = 60
    budget_s: float = 4.0  # an analysis that takes longer is stopped (partial results kept)
    inlay_hints: bool = True
    max_diagnostics: int = 1000
    root: str = ""  # folder that relative paths are resolved against

    def merged(self, data: dict[str, Any], root: str | None = None) -> Settings:
        """A copy with the known keys of ``data`` applied (unknown keys ignored)."""
        changes: dict[str, Any] = {}
        flat = dict(data)
        for section in ("cncc", "lsp"):
            sub = flat.pop(section, None)
            if isinstance(sub, dict):
                flat.update(sub)
        if isinstance(flat.get("options"), dict):
            flat["dialect_options"] = {**self.dialect_options, **flat.pop("options")}
        for f in fields(self):
            key = f.name
            alias = key.replace("_", "-")
            if key in flat or alias in flat:
                value = flat[key] if key in flat else flat[alias]
                coerced = _coerce(key, value, getattr(self, key))
                if coerced is not None or value is None:
                    changes[key] = coerced
        if root is not None:
            changes["root"] = root
        return replace(self, **changes)

    def path(self, value: str | None) -> str | None:
        if not value:
            return None
        value = os.path.expanduser(value)
        return value if os.path.isabs(value) or not self.root else os.path.join(self.root, value)


def _coerce(key: str, value: Any, current: Any) -> Any:
    if value is None:
        return None
    if isinstance(current, bool):
        return bool(value)
    if isinstance(current, int) and not isinstance(current, bool):
        return int(value) if isinstance(value, int | float | str) and str(value).lstrip("-").isdigit() else current
    if isinstance(current, float):
        return float(value) if isinstance(value, int | float) else current
    if isinstance(current, dict):
        return dict(value) if isinstance(value, dict) else current
    return str(value)


# ---- dialects --------------------------------------------------------------------
# Marks the command line's detection (cncc/frontend/detect.py) does not look for.
def guess_dialect(path: str, text: str, configured: str | None) -> str:
    """The dialect of one document: a modeline, else the configured dialect, else the command
    line's guess (``cncc.frontend.detect``: the dialect files' marks, then well-known
    extensions), else the only dialect file that claims the extension,
    else the default."""
    from cncc.frontend.detect import guess_dialect as detect

    known = available()
    mode = modeline(text)  # the project resolver's modeline (cncc/config.py), as the command line reads it
    if mode is not None:
        return mode[0]
    if configured:
        return configured
    sample = text[:200_000]
    name, why = detect(path, sample)
    if name in known and not why.startswith("nothing"):
        return name
    ext = os.path.splitext(path)[1].lower()
    matches = [name for name in known if ext and ext in _extensions(name)]
    if len(matches) == 1:
        return matches[0]
    return DEFAULT_DIALECT


def _extensions(name: str) -> tuple[str, ...]:
    try:
        return load_dialect(name).extensions
    except DialectError:
        return ()


def open_dialect(name: str, settings: Settings) -> Dialect:
    """A built-in dialect by name, or a dialect TOML file by path; options applied."""
    if name.endswith(".toml"):
        path = settings.path(name) or name
        try:
            with open(path, "rb") as fh:
                dialect = parse_dialect(tomllib.load(fh))
        except (OSError, tomllib.TOMLDecodeError) as exc:
            raise DialectError(f"{path}: {exc}") from None
    else:
        dialect = load_dialect(name)
    opts = {k: v for k, v in settings.dialect_options.items() if k in dialect.options}
    return dialect.with_options(opts) if opts else dialect
