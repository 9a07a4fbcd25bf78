"""Dialect profiles: G-code dialects as data.

Each dialect is a TOML file in this folder (``syntec.toml`` ...).  This module loads
one into a :class:`Dialect`: code tables keyed by ``(letter, number in tenths)``,
address kinds, least input units, comment and block-end syntax, defaults and
options.  The same tables drive parsing, lowering, hover texts and emitters.
"""

from __future__ import annotations

import functools
import tomllib
from collections.abc import Callable
from dataclasses import dataclass, field
from importlib import resources
from typing import Any, TypeVar

from cncc.dialects.detection import DetectError, Detection, parse_detection
from cncc.dialects.lexicon import Lexicon, LexiconError, parse_lexicon

_T = TypeVar("_T")


class DialectError(ValueError):
    """A dialect file is malformed (message names the key)."""


def code_tenths(number_text: str) -> int:
    """``"59.1"`` -> 591, ``"00"`` -> 0, ``"137.1"`` -> 1371."""
    whole, _, frac = number_text.partition(".")
    frac = (frac + "0")[:1]
    return int(whole or "0") * 10 + int(frac or "0")


def code_name(letter: str, tenths: int) -> str:
    """``("G", 591)`` -> ``"G59.1"``, ``("G", 0)`` -> ``"G00"``."""
    whole, frac = divmod(tenths, 10)
    text = f"{letter}{whole:02d}"
    return f"{text}.{frac}" if frac else text


@dataclass(frozen=True, slots=True)
class CodeDef:
    letter: str
    tenths: int
    name: str
    op: str
    group: str
    summary: str
    words: dict[str, str] = field(default_factory=dict)  # per-code address kinds
    index: int = 0
    cycle: str = ""


@dataclass(frozen=True, slots=True)
class Dialect:
    name: str
    title: str
    grammar: str
    macro_flavour: str
    comments: tuple[str, ...]
    block_end: str
    decimal_rule: str  # "liu" or "units"
    default_units: str
    codes: dict[tuple[str, int], CodeDef]
    addresses: dict[str, str]
    liu: dict[str, float]
    groups: dict[str, int]
    defaults: dict[str, str]
    options: dict[str, Any]
    extensions: tuple[str, ...]
    max_m_per_block: int
    default_feed_mm_min: float
    default_feed_mm_rev: float
    raw: dict[str, Any]
    # What the controller rejects, with its reason: keys are codes ("G41", "M98") or
    # address letters ("Q", "#"); values the controller's own reason (LSP, translator).
    unsupported: dict[str, str] = field(default_factory=dict)
    # The front-end plug-in that runs the dialect's programs (``frontend = "series8"``;
    # cncc/frontend/plugins.py holds the registry).
    frontend: str = "fanuc"
    # Detection marks (``[detect]``: extension points, compiled rules), read when the dialect loads.
    detection: Detection = field(default_factory=lambda: Detection({}, ()))
    # Keywords (statements, functions, word operators, executor marks): cncc/dialects/lexicon.py.
    lexicon: Lexicon = field(default_factory=Lexicon)
    # Tables derived from this dialect's data (compiled regexes ...), built on first use by
    # :meth:`derived`.  They live on the object, never in a module-level cache keyed by
    # ``name``: a user dialect file may share a built-in dialect's name (decisions 2026-12-01).
    _derived: dict[str, Any] = field(default_factory=dict, init=False, compare=False, repr=False)

    def derived(self, key: str, build: Callable[[Dialect], _T]) -> _T:
        """The table ``key`` of this dialect, built once by ``build(self)``."""
        try:
            return self._derived[key]  # type: ignore[no-any-return]
        except KeyError:
            value = self._derived[key] = build(self)
            return value

    def code(self, letter: str, tenths: int) -> CodeDef | None:
        return self.codes.get((letter, tenths))

    def unsupported_reason(self, letter: str, tenths: int | None = None) -> str | None:
        """Why the controller rejects ``letter`` (an address) or code ``letter``+``tenths``; None if it does not."""
        if tenths is None:
            return self.unsupported.get(letter)
        return self.unsupported.get(code_name(letter, tenths))

    def option(self, key: str, default: Any = None) -> Any:
        return self.options.get(key, default)

    def with_options(self, overrides: dict[str, Any]) -> Dialect:
        """A copy with some options replaced (unknown keys are an error)."""
        for key in overrides:
            if key not in self.options:
                raise DialectError(f"dialect {self.name!r} has no option {key!r}")
        opts = {**self.options, **overrides}
        fields = {f: getattr(self, f) for f, d in self.__dataclass_fields__.items() if d.init}
        return Dialect(**{**fields, "options": opts})


def available() -> list[str]:
    names = []
    for entry in resources.files(__package__).iterdir():
        if entry.name.endswith(".toml"):
            names.append(entry.name[:-5])
    return sorted(names)


def _codes(raw: dict[str, Any], letter: str) -> dict[tuple[str, int], CodeDef]:
    out: dict[tuple[str, int], CodeDef] = {}
    key = letter.lower()
    for i, entry in enumerate(raw.get(key, [])):
        where = f"{key}[{i}]"
        try:
            code = str(entry["code"])
            op = str(entry["op"])
        except KeyError as exc:
            raise DialectError(f"{where}: missing key {exc.args[0]!r}") from None
        if not code.startswith(letter):
            raise DialectError(f"{where}.code: {code!r} does not start with {letter}")
        tenths = code_tenths(code[1:])
        words = entry.get("words", {})
        if not isinstance(words, dict):
            raise DialectError(f"{where}.words: expected a table")
        out[(letter, tenths)] = CodeDef(
            letter=letter,
            tenths=tenths,
            name=code,
            op=op,
            group=str(entry.get("group", "non_modal")),
            summary=str(entry.get("summary", "")),
            words={str(k): str(v) for k, v in words.items()},
            index=int(entry.get("index", 0)),
            cycle=str(entry.get("cycle", "")),
        )
    return out


def _unsupported_key(key: str) -> str:
    """``"g1"`` -> ``"G01"``, ``"G59.1"`` stays, ``"q"`` -> ``"Q"``."""
    key = key.strip().upper()
    if len(key) > 1 and key[0] in "GM" and key[1:].replace(".", "", 1).isdigit():
        return code_name(key[0], code_tenths(key[1:]))
    return key


def parse_dialect(raw: dict[str, Any]) -> Dialect:
    try:
        name = str(raw["name"])
    except KeyError:
        raise DialectError("missing key 'name'") from None
    codes = _codes(raw, "G") | _codes(raw, "M")
    return Dialect(
        name=name,
        title=str(raw.get("title", name)),
        grammar=str(raw.get("grammar", "fanuc")),
        macro_flavour=str(raw.get("macro_flavour", "none")),
        comments=tuple(raw.get("comments", ["paren"])),
        block_end=str(raw.get("block_end", "")),
        decimal_rule=str(raw.get("decimal_rule", "units")),
        default_units=str(raw.get("default_units", "mm")),
        codes=codes,
        addresses={str(k): str(v) for k, v in raw.get("addresses", {}).items()},
        liu={str(k): float(v) for k, v in raw.get("liu", {}).items()},
        groups={str(k): int(v) for k, v in raw.get("groups", {}).items()},
        defaults={str(k): str(v) for k, v in raw.get("defaults", {}).items()},
        options=dict(raw.get("options", {})),
        extensions=tuple(raw.get("extensions", [])),
        max_m_per_block=int(raw.get("max_m_per_block", 1)),
        default_feed_mm_min=float(raw.get("default_feed_mm_min", 0.0)),
        default_feed_mm_rev=float(raw.get("default_feed_mm_rev", 0.0)),
        raw=raw,
        unsupported={_unsupported_key(str(k)): str(v) for k, v in raw.get("unsupported", {}).items()},
        frontend=_frontend(raw),
        detection=_detection(name, raw),
        lexicon=_lexicon(raw),
    )


def _lexicon(raw: dict[str, Any]) -> Lexicon:
    try:
        return parse_lexicon(str(raw.get("grammar", "fanuc")), raw)
    except LexiconError as exc:
        raise DialectError(str(exc)) from None


def _detection(name: str, raw: dict[str, Any]) -> Detection:
    try:
        return parse_detection(name, raw, tuple(str(e) for e in raw.get("extensions", [])))
    except DetectError as exc:
        raise DialectError(str(exc)) from None


def _frontend(raw: dict[str, Any]) -> str:
    """The ``frontend`` key (``checker`` is its old spelling); by default the macro flavour's
    own front end for LinuxCNC, else the Fanuc family's."""
    name = raw.get("frontend", raw.get("checker"))
    if name is None:
        return "linuxcnc" if raw.get("macro_flavour") == "linuxcnc" else "fanuc"
    if not isinstance(name, str) or not name.isidentifier():
        raise DialectError(f"frontend: expected the name of a front end, got {name!r}")
    return name


NOT_INHERITED = frozenset({"name", "title", "base", "remove", "detect"})
"""Keys a dialect with ``base = "..."`` does not take from its base."""


def merge_base(base: dict[str, Any], top: dict[str, Any]) -> dict[str, Any]:
    """``top`` written as changes to ``base``: tables are merged key by key, the ``[[g]]`` and
    ``[[m]]`` entries by code (``top`` replaces or adds), ``remove = ["G22", ...]`` drops codes,
    any other key of ``top`` replaces the base's."""
    out = {k: v for k, v in base.items() if k not in NOT_INHERITED}
    drop = {_unsupported_key(str(c)) for c in top.get("remove", [])}
    for key in ("g", "m"):
        out[key] = [e for e in out.get(key, []) if _unsupported_key(str(e.get("code", ""))) not in drop]
    for key, value in top.items():
        if key in ("g", "m") and isinstance(value, list):
            mine = {_unsupported_key(str(e.get("code", ""))) for e in value}
            out[key] = [e for e in out[key] if _unsupported_key(str(e.get("code", ""))) not in mine] + value
        elif isinstance(value, dict) and isinstance(out.get(key), dict):
            out[key] = {**out[key], **value}
        elif key != "remove":
            out[key] = value
    return out


def _read_raw(name: str, depth: int = 0) -> dict[str, Any]:
    if name not in available():
        raise DialectError(f"unknown dialect {name!r} (known: {', '.join(available())})")
    if depth > 4:
        raise DialectError(f"{name}.toml: 'base' nested too deep")
    text = resources.files(__package__).joinpath(f"{name}.toml").read_text(encoding="utf-8")
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise DialectError(f"{name}.toml: {exc}") from None
    base = raw.get("base")
    if base is None:
        return raw
    return merge_base(_read_raw(str(base), depth + 1), raw)


@functools.cache
def load_dialect(name: str) -> Dialect:
    """Load a built-in dialect by name (raises :class:`DialectError` if unknown).

    A dialect file may start from another (``base = "fanuc"``) and list only what differs
    (:func:`merge_base`)."""
    return parse_dialect(_read_raw(name))
