"""Names to models: the dialect (``-x NAME`` or a dialect TOML file, with its ``-f`` options) and the
machine (``-m NAME``, with the controller's rapid type) an :class:`cncc.options.Options` names.

The ``resolve_*`` functions report problems as diagnostics (E0904, a bad option value) and return None;
they never raise on bad input.
The driver resolves each input file's options through these; the backend stage (:mod:`cncc.emit`)
resolves the ``-t`` target dialect and the ``--compare`` machines.
"""

from __future__ import annotations

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink
from cncc.dialects import Dialect, DialectError, load_dialect
from cncc.ir.machine import Axis, MachineModel
from cncc.options import DEFAULT_DIALECT, Options
from cncc.source import NO_SPAN


def resolve_dialect(opts: Options, sink: DiagnosticSink) -> Dialect | None:
    name = opts.dialect or DEFAULT_DIALECT
    try:
        dialect = dialect_file(name) if name.endswith(".toml") else load_dialect(name)
        unknown = [k for k in opts.dialect_options if k not in dialect.options]
        if unknown:
            from cncc.flags import unknown_option

            sink.emit(dg.BAD_OPTION, NO_SPAN, unknown_option(unknown[0], opts.dialect_options[unknown[0]],
                                                             dialect.options, dialect.name))
            return None
        if opts.dialect_options:
            dialect = dialect.with_options(opts.dialect_options)
    except DialectError as exc:
        sink.emit(dg.BAD_OPTION, NO_SPAN, str(exc))
        return None
    return dialect


def dialect_file(path: str) -> Dialect:
    """A dialect TOML file (a dialect of one's own, as the language server also reads)."""
    import tomllib

    from cncc.dialects import parse_dialect

    try:
        with open(path, "rb") as fh:
            return parse_dialect(tomllib.load(fh))
    except (OSError, tomllib.TOMLDecodeError) as exc:
        raise DialectError(f"{path}: {exc}") from None


def resolve_machine(name: str, sink: DiagnosticSink) -> MachineModel | None:
    try:
        from cncc import machines  # data + loader (may be absent in minimal builds)
    except ImportError:
        return default_machine()
    loader = getattr(machines, "load_machine", None)
    if loader is None:
        return default_machine()
    try:
        model: MachineModel = loader(name)
    except (ValueError, OSError) as exc:
        sink.emit(dg.BAD_OPTION, NO_SPAN, f"machine {name!r}: {exc}")
        return None
    return model


def apply_dialect_to_machine(machine: MachineModel, opts: Options, sink: DiagnosticSink) -> MachineModel:
    """The controller's rapid type (SYNTEC Pr411, SZGH P9_D6) overrides the machine's
    rapid mode when the user sets it (``-frapid_type=...``); the dialect's own default
    applies only to the machine model that emulates that controller."""
    from dataclasses import replace

    from cncc.ir.machine import RapidMode

    value = opts.dialect_options.get("rapid_type")
    if value is None:
        return machine
    try:
        mode = RapidMode(str(value))
    except ValueError:
        sink.emit(dg.BAD_OPTION, NO_SPAN, f"-frapid_type={value}: expected 'interpolated' or 'independent'")
        return machine
    return replace(machine, rapid_mode=mode)


def default_machine() -> MachineModel:
    return MachineModel("generic-mill", tuple(Axis(a) for a in "XYZ"))
