"""Machine models as data: TOML files -> :class:`cncc.ir.machine.MachineModel`.

Consumes a built-in name (``generic-mill``, ``szgh-990mdb``, ``syntec-900m``) or a path
to a user's TOML file; produces a frozen ``MachineModel``.  Keys are the dataclass
field names (units in the names).  Axes are an array of tables::

    name = "my-router"
    base = "generic-mill"            # optional: start from a built-in (or another file)
    max_feed_mm_min = 8000
    [[axes]]
    name = "X"
    max_accel_mm_s2 = 800
    [axes.step]
    steps_per_mm = 400

With ``base``, an ``[[axes]]`` entry whose ``name`` matches a base axis changes only
the keys it gives.  ``overrides`` (e.g. from the command line) are dotted paths:
``{"max_feed_mm_min": 5000, "axes.X.max_accel_mm_s2": 500}``.

A bad file raises :class:`MachineError` (a ``ValueError``) whose ``key`` is the path of
the offending key (``axes.X.max_jerk_mm_s3``); the driver turns it into a diagnostic.

:func:`effective_corner_rule` says which corner rule a plan at a given ``-O`` level
follows on a machine; the planner and the verifier's caller both use it.
"""

from __future__ import annotations

import dataclasses
import enum
import tomllib
import types
import typing
from collections.abc import Mapping
from importlib import resources
from pathlib import Path
from typing import Any

from cncc.ir.machine import Axis, CornerRule, MachineModel, MCode, StepOutput

BUILTIN = ("generic-mill", "szgh-990mdb", "syntec-900m")


class MachineError(ValueError):
    """A machine file or override is malformed; ``key`` names the offending key."""

    def __init__(self, key: str, message: str) -> None:
        super().__init__(f"{key}: {message}" if key else message)
        self.key = key


def builtin_names() -> tuple[str, ...]:
    return BUILTIN


def load_machine(name_or_path: str | Path, overrides: Mapping[str, Any] | None = None) -> MachineModel:
    """Load a built-in machine or a TOML file, apply dotted ``overrides``."""
    data = _read(str(name_or_path), depth=0)
    for key, value in (overrides or {}).items():
        _set_dotted(data, key, value)
    return machine_from_dict(data)


def machine_from_dict(data: Mapping[str, Any]) -> MachineModel:
    """Build a ``MachineModel`` from a parsed mapping (keys checked against the fields)."""
    body = {k: v for k, v in data.items() if k != "base"}
    if "axes" not in body:
        raise MachineError("axes", "a machine needs at least one [[axes]] table")
    raw_axes = body.pop("axes")
    if not isinstance(raw_axes, list) or not raw_axes:
        raise MachineError("axes", "expected a non-empty array of tables")
    axes = tuple(_build_axis(a, i) for i, a in enumerate(raw_axes))
    names = [a.name for a in axes]
    if len(set(names)) != len(names):
        raise MachineError("axes", f"duplicate axis names {names}")
    m_codes = _m_codes(body.pop("m_codes", []))
    kwargs = _convert_fields(MachineModel, body, prefix="", skip={"axes", "m_codes"})
    kwargs["m_codes"] = m_codes
    kwargs.setdefault("name", "unnamed")
    model = MachineModel(axes=axes, **kwargs)
    _check_positive(model)
    return model


def _m_codes(raw: Any) -> tuple[tuple[str, MCode], ...]:
    """``[[m_codes]] code = "M10", meaning = "...", seconds = 0.8`` -> (("M10", MCode), ...)."""
    if not isinstance(raw, list):
        raise MachineError("m_codes", "expected an array of tables ([[m_codes]])")
    out = []
    for i, entry in enumerate(raw):
        where = f"m_codes[{i}]"
        if not isinstance(entry, dict) or not isinstance(entry.get("code"), str):
            raise MachineError(where, "needs a string 'code' such as \"M10\"")
        unknown = set(entry) - {"code", "meaning", "seconds"}
        if unknown:
            raise MachineError(f"{where}.{sorted(unknown)[0]}", "unknown key (known: code, meaning, seconds)")
        code = entry["code"].strip().upper()
        if code[:1] != "M" or not code[1:].replace(".", "", 1).isdigit():
            raise MachineError(f"{where}.code", f"{code!r} is not an M code")
        seconds = entry.get("seconds", 0.0)
        if not isinstance(seconds, int | float) or seconds < 0:
            raise MachineError(f"{where}.seconds", "expected a number of seconds, 0 or more")
        whole, _, frac = code[1:].partition(".")
        name = f"M{int(whole):02d}" + (f".{frac}" if frac else "")
        out.append((name, MCode(str(entry.get("meaning", "")), float(seconds))))
    return tuple(out)


def effective_corner_rule(machine: MachineModel, level: int) -> CornerRule:
    """The corner rule a plan at ``-O<level>`` follows on ``machine``.

    ``-O1`` emulates the controller class: exact stop and SZGH speed step stay, anything
    else becomes grbl/Klipper junction deviation.  ``-O2``/``-O3`` blend geometrically
    (``BLEND``) unless the machine stops at every corner (``EXACT_STOP``).
    """
    rule = machine.corner_rule
    if level <= 1:
        return rule if rule in (CornerRule.EXACT_STOP, CornerRule.SPEED_STEP) else CornerRule.JUNCTION_DEVIATION
    return CornerRule.EXACT_STOP if rule is CornerRule.EXACT_STOP else CornerRule.BLEND


# ---- reading ---------------------------------------------------------------------------
def _read(name: str, depth: int) -> dict[str, Any]:
    if depth > 8:
        raise MachineError("base", "too many nested 'base' references")
    text, where = _locate(name)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise MachineError("", f"{where}: {exc}") from None
    base = data.get("base")
    if base is None:
        return data
    if not isinstance(base, str):
        raise MachineError("base", "expected the name of a machine")
    merged = _read(base, depth + 1)
    _merge(merged, data)
    return merged


def _locate(name: str) -> tuple[str, str]:
    if name in BUILTIN:
        return resources.files(__name__).joinpath(f"{name}.toml").read_text(encoding="utf-8"), name
    path = Path(name)
    if not path.exists() and path.suffix != ".toml" and Path(name + ".toml").exists():
        path = Path(name + ".toml")
    if not path.exists():
        raise MachineError("", f"no built-in machine or file named {name!r} (built-in: {', '.join(BUILTIN)})")
    return path.read_text(encoding="utf-8"), str(path)


def _merge(into: dict[str, Any], top: Mapping[str, Any]) -> None:
    for key, value in top.items():
        if key == "base":
            continue
        if key == "axes" and isinstance(value, list) and isinstance(into.get("axes"), list):
            into["axes"] = _merge_axes(into["axes"], value)
        elif isinstance(value, dict) and isinstance(into.get(key), dict):
            _merge(into[key], value)
        else:
            into[key] = value
    into.pop("base", None)


def _merge_axes(base: list[Any], top: list[Any]) -> list[Any]:
    out = [dict(a) if isinstance(a, dict) else a for a in base]
    for ax in top:
        match = [b for b in out if isinstance(b, dict) and isinstance(ax, dict) and b.get("name") == ax.get("name")]
        if match:
            _merge(match[0], ax)
        else:
            out.append(ax)
    return out


def _set_dotted(data: dict[str, Any], key: str, value: Any) -> None:
    parts = key.split(".")
    node: Any = data
    for i, part in enumerate(parts[:-1]):
        if part == "axes" and i + 2 < len(parts) and isinstance(node.get("axes"), list):
            axis_name = parts[i + 1]
            found = [a for a in node["axes"] if isinstance(a, dict) and a.get("name") == axis_name]
            if not found:
                raise MachineError(key, f"no axis named {axis_name!r}")
            _set_dotted(found[0], ".".join(parts[i + 2:]), value)
            return
        node = node.setdefault(part, {})
        if not isinstance(node, dict):
            raise MachineError(key, f"{part!r} is not a table")
    node[parts[-1]] = value


# ---- conversion ------------------------------------------------------------------------
def _build_axis(raw: Any, index: int) -> Axis:
    if not isinstance(raw, dict) or not isinstance(raw.get("name"), str):
        raise MachineError(f"axes[{index}]", "an axis table needs a string 'name'")
    prefix = f"axes.{raw['name']}"
    body = dict(raw)
    step_raw = body.pop("step", {})
    if not isinstance(step_raw, dict):
        raise MachineError(f"{prefix}.step", "expected a table")
    step = StepOutput(**_convert_fields(StepOutput, step_raw, prefix=f"{prefix}.step"))
    return Axis(step=step, **_convert_fields(Axis, body, prefix=prefix, skip={"step"}))


def _convert_fields(cls: type, raw: Mapping[str, Any], prefix: str, skip: frozenset[str] | set[str] = frozenset()
                    ) -> dict[str, Any]:
    hints = typing.get_type_hints(cls)
    fields = {f.name for f in dataclasses.fields(cls)} - set(skip)
    out: dict[str, Any] = {}
    for key, value in raw.items():
        path = f"{prefix}.{key}" if prefix else key
        if key not in fields:
            raise MachineError(path, f"unknown key (known: {', '.join(sorted(fields))})")
        out[key] = _coerce(hints[key], value, path)
    return out


def _coerce(hint: Any, value: Any, path: str) -> Any:
    origin = typing.get_origin(hint)
    if origin in (types.UnionType, typing.Union):
        args = [a for a in typing.get_args(hint) if a is not type(None)]
        return None if value is None else _coerce(args[0], value, path)
    if isinstance(hint, type) and issubclass(hint, enum.Enum):
        try:
            return hint(value)
        except ValueError:
            allowed = ", ".join(repr(m.value) for m in hint)
            raise MachineError(path, f"{value!r} is not one of {allowed}") from None
    if hint is bool:
        if not isinstance(value, bool):
            raise MachineError(path, f"expected true or false, got {value!r}")
        return value
    if hint is float:
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise MachineError(path, f"expected a number, got {value!r}")
        return float(value)
    if hint is int:
        if isinstance(value, bool) or not isinstance(value, int):
            raise MachineError(path, f"expected an integer, got {value!r}")
        return value
    if hint is str:
        if not isinstance(value, str):
            raise MachineError(path, f"expected a string, got {value!r}")
        return value
    if origin is tuple:
        if not isinstance(value, list):
            raise MachineError(path, f"expected an array, got {value!r}")
        params = typing.get_args(hint)
        inner = params[0] if params else Any
        if inner is Any:
            return tuple(v for v in value)
        return tuple(_coerce(inner, v, f"{path}[{i}]") for i, v in enumerate(value))
    return value


_POSITIVE_AXIS = ("max_velocity_mm_min", "max_accel_mm_s2", "max_jerk_mm_s3", "rapid_mm_min")


def _check_positive(model: MachineModel) -> None:
    for ax in model.axes:
        for key in _POSITIVE_AXIS:
            if getattr(ax, key) <= 0:
                raise MachineError(f"axes.{ax.name}.{key}", "must be positive")
        if ax.step.steps_per_mm <= 0 or ax.step.max_step_rate_hz <= 0:
            raise MachineError(f"axes.{ax.name}.step", "steps_per_mm and max_step_rate_hz must be positive")
    for key in ("max_feed_mm_min", "interpolation_period_s", "arc_tolerance_mm"):
        if getattr(model, key) <= 0:
            raise MachineError(key, "must be positive")
