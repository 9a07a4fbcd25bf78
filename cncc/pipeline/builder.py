"""The pipeline builder: the one place that makes the lists of passes the compiler runs.

Stages (docs/architecture.md, "Pipeline"):

* **path** (:func:`path_passes`): ``expand-cycles``, the frame passes (``polar``,
  ``scaling``, ``mirror``, ``rotation``; with ``machine_coords`` also ``to-machine`` and
  ``tool-length``; then ``cutter-comp``), ``arc-check``.  Streamed between the front end
  and the backend.
* **light** (:func:`light_passes`): the path stage with ``relink`` in place of the frame
  passes (the language server, until a frame needs them).
* **plan** (:func:`plan_passes`): ``blend``, ``plan`` at one ``-O`` level, ``verify`` --
  run once per planned column of the timing and pulse backends.

Each pass is made from the registry (:func:`cncc.passes.registered`) by name, with the
options :func:`path_options` derives from the configuration and the dialect (arc
tolerances, the cutter compensation's corners, what a G-code target keeps).  A ``-p``
spec (``PipelineConfig.spec``) names the passes instead: path-stage names replace the path
stage (their unnamed options keep those defaults); plan-stage names, if any, replace the
plan stage.
"""

from __future__ import annotations

import dataclasses
import difflib
import importlib
from dataclasses import dataclass
from typing import Any

from cncc.dialects import Dialect
from cncc.passes import Pass, registered
from cncc.pipeline.spec import PassRequest, SpecError, convert, parse, settable

PASS_MODULES: dict[str, str] = {
    "expand-cycles": "cncc.passes.expand_cycles",
    "polar": "cncc.passes.polar",
    "scaling": "cncc.passes.scaling",
    "mirror": "cncc.passes.mirror",
    "rotation": "cncc.passes.rotation",
    "to-machine": "cncc.passes.to_machine",
    "tool-length": "cncc.passes.tool_length",
    "cutter-comp": "cncc.passes.cutter_comp",
    "cutter-comp-rs274": "cncc.passes.comp_rs274",
    "relink": "cncc.passes.relink",
    "arc-check": "cncc.passes.arc_check",
    "blend": "cncc.passes.blend",
    "plan": "cncc.passes.plan",
    "verify": "cncc.passes.verify",
}
"""Every pass by name, and the module that registers it (imported only when the pass is
used, so a canon trace does not import the planner's numpy)."""

PLAN_STAGE = ("blend", "plan", "verify")
FRAME_PASSES = ("polar", "scaling", "mirror", "rotation", "to-machine", "tool-length", "cutter-comp",
                "cutter-comp-rs274")
MACHINE_ONLY = frozenset({"to-machine", "tool-length"})  # frame passes of the machine-coordinate backends
SET_BY_DRIVER = {("plan", "level"): "-O and --compare choose the level"}


@dataclass(frozen=True, slots=True)
class PipelineConfig:
    """What decides the passes: the backend's coordinates, -frepair-arcs, what a G-code
    target keeps (``translation_prepare`` in the driver), and the ``-p`` spec."""

    machine_coords: bool = False  # timing, pulses: offsets and tool length applied
    repair_arcs: bool = False
    keep_cycles: frozenset[str] = frozenset()  # cycle kinds left whole (CycleKind values)
    keep_transforms: frozenset[Any] = frozenset()  # rotation, mirror and scaling records left in the frames
    keep_work: bool = False  # work-system rotations (LinuxCNC G10 L2 R) left in the frames (the canon trace)
    spec: str = ""  # -p: the passes by name ("" = the default pipeline)


def pass_class(name: str) -> type[Pass]:
    """The registered class of the pass ``name`` (its module imported first)."""
    importlib.import_module(PASS_MODULES[name])
    return registered()[name]


def make(name: str, options: dict[str, Any]) -> Pass:
    return pass_class(name)(**options)


def pass_names(stage: str | None = None) -> list[str]:
    """The names a spec may use (``stage``: only the path or only the plan stage)."""
    names = list(PASS_MODULES)
    if stage == "plan":
        return [n for n in names if n in PLAN_STAGE]
    if stage == "path":
        return [n for n in names if n not in PLAN_STAGE]
    return names


# ---- the spec ---------------------------------------------------------------------------------
def requests(spec: str) -> list[PassRequest]:
    """The spec's passes, checked: known names, settable options, values of the right type,
    the path stage before the plan stage, ``verify`` after ``plan``.  Raises :class:`SpecError`."""
    out = parse(spec)
    seen_plan = False
    for r in out:
        if r.name not in PASS_MODULES:
            close = difflib.get_close_matches(r.name, pass_names(), n=1)
            hint = f"did you mean '{close[0]}'? " if close else ""
            raise SpecError(f"unknown pass '{r.name}'; {hint}(passes: {', '.join(pass_names())})", r.start, r.end)
        in_plan = r.name in PLAN_STAGE
        if seen_plan and not in_plan:
            raise SpecError(f"{r.name} works on the program's path: it goes before blend, plan and verify",
                            r.start, r.end)
        seen_plan = seen_plan or in_plan
        fields = {f.name: f for f in dataclasses.fields(pass_class(r.name)) if f.init}
        for key, value in r.options.items():
            lo, hi = r.option_columns[key]
            f = fields.get(key)
            annotation = f.type if f is not None and isinstance(f.type, str) else ""
            if f is None or not settable(annotation):
                valid = [n for n, g in fields.items() if isinstance(g.type, str) and settable(g.type)]
                raise SpecError(f"{r.name} has no option '{key}' (options: {', '.join(valid) or 'none'})", lo, hi)
            if (r.name, key) in SET_BY_DRIVER:
                raise SpecError(f"{r.name}{{{key}}} cannot be set in -p: {SET_BY_DRIVER[r.name, key]}", lo, hi)
            try:
                convert(value, annotation)
            except ValueError as exc:
                raise SpecError(f"{r.name}{{{key}={value}}}: {exc}", lo, hi) from None
    names = [r.name for r in out]
    if "verify" in names and ("plan" not in names or names.index("verify") < names.index("plan")):
        r = out[names.index("verify")]
        raise SpecError("verify checks the trajectory plan makes: name plan before it", r.start, r.end)
    return out


def _options(r: PassRequest) -> dict[str, Any]:
    fields = {f.name: f for f in dataclasses.fields(pass_class(r.name))}
    return {k: convert(v, str(fields[k].type)) for k, v in r.options.items()}


# ---- the stages -------------------------------------------------------------------------------
def path_options(config: PipelineConfig, dialect: Dialect) -> dict[str, dict[str, Any]]:
    """Each path pass's options from the configuration and the dialect."""
    from cncc.passes.arc_check import ArcCheck

    arc = ArcCheck.for_dialect(dialect, repair=config.repair_arcs)
    keep = config.keep_transforms
    return {
        "expand-cycles": {"keep": config.keep_cycles},
        "scaling": {"keep": keep}, "mirror": {"keep": keep},
        "rotation": {"keep": keep, "keep_work": config.keep_work},
        "cutter-comp": {"outer_corner": str(dialect.option("comp_outer_corner", "intersection")),
                        "outer_arc_below_deg": float(dialect.option("comp_outer_arc_below_deg", 0.0)),
                        "lookahead": int(dialect.option("comp_lookahead", 2)),
                        "startup": str(dialect.option("comp_startup", "type_a"))},
        "arc-check": {"abs_tol_mm": arc.abs_tol_mm, "rel_tol": arc.rel_tol, "repair": arc.repair,
                      "abs_tol_inch_mm": arc.abs_tol_inch_mm, "max_abs_factor": arc.max_abs_factor},
    }


def default_path_names(config: PipelineConfig, dialect: Dialect | None = None) -> list[str]:
    """The default path stage; the dialect's ``comp_algorithm = "rs274"`` (LinuxCNC) picks
    ``cutter-comp-rs274`` for ``cutter-comp``."""
    comp = "cutter-comp-rs274" if dialect is not None and dialect.option("comp_algorithm", "") == "rs274" \
        else "cutter-comp"
    frame = [n for n in FRAME_PASSES if (config.machine_coords or n not in MACHINE_ONLY)
             and (not n.startswith("cutter-comp") or n == comp)]
    return ["expand-cycles", *frame, "arc-check"]


CHECK_ONLY = frozenset({"arc-check"})  # path passes that report but leave the commands as they are


def omitted_passes(config: PipelineConfig, dialect: Dialect | None = None) -> list[str]:
    """The default path passes a ``-p`` spec leaves out although the output is made of what they do:
    all of them (but the checks) when the spec names no path pass at all (``-p 'blend,plan,verify'``
    replaces the plan stage and, with it, drops the path stage), and ``to-machine``/``tool-length``
    when the output is in machine coordinates.  [] without a spec.  A spec that lists path passes
    chose them: it is not second-guessed beyond the machine coordinates."""
    if not config.spec:
        return []
    named = {r.name for r in requests(config.spec)}
    defaults = [n for n in default_path_names(config, dialect) if n not in CHECK_ONLY]
    if not named - set(PLAN_STAGE):
        return defaults
    return [n for n in defaults if n in MACHINE_ONLY and n not in named]


def path_passes(config: PipelineConfig, dialect: Dialect) -> list[Pass]:
    """The path stage (the default, or the path-stage passes of ``config.spec``)."""
    defaults = path_options(config, dialect)
    if not config.spec:
        return [make(n, defaults.get(n, {})) for n in default_path_names(config, dialect)]
    return [make(r.name, {**defaults.get(r.name, {}), **_options(r)})
            for r in requests(config.spec) if r.name not in PLAN_STAGE]


def frame_passes(config: PipelineConfig, dialect: Dialect) -> list[Pass]:
    """The frame passes alone (commands already past expand-cycles and arc-check)."""
    defaults = path_options(config, dialect)
    return [make(n, defaults.get(n, {})) for n in default_path_names(config, dialect) if n in FRAME_PASSES]


def light_passes(config: PipelineConfig, dialect: Dialect, memory: Any = None) -> list[Pass]:
    """The path stage with ``relink`` (given the language server's ``memory``) in place of the
    frame passes: what they do to commands whose frames transform nothing."""
    defaults = path_options(config, dialect)
    names = [n for n in default_path_names(config, dialect) if n not in FRAME_PASSES]
    out = [make(n, defaults.get(n, {})) for n in names]
    return [out[0], make("relink", {"memory": memory}), *out[1:]]


def plan_passes(config: PipelineConfig, level: int, *, verify: bool = True, soft_limits: bool = False,
                quiet: bool = False) -> list[Pass]:
    """Blend, plan at ``level`` and (``verify``, -O1..-O3) verify; or the plan-stage passes of
    ``config.spec`` when it names any.  -O0 plans with the nominal estimate of
    :mod:`cncc.backends.nominal` and is not verified: it has no acceleration by design, runs the
    programmed feed unclamped and draws arcs as coarse chords for its plots."""
    chosen = [r for r in requests(config.spec) if r.name in PLAN_STAGE] if config.spec else []
    options: dict[str, dict[str, Any]] = {
        "plan": _plan_options(level, quiet),
        "verify": {"check_dynamics": True, "jerk_limited": level >= 2, "soft_limits": soft_limits},
    }
    if not chosen:
        names = ["blend", "plan"] + (["verify"] if verify and level > 0 else [])
        return [make(n, options.get(n, {})) for n in names]
    return [make(r.name, {**options.get(r.name, {}), **_options(r)}) for r in chosen
            if r.name != "verify" or level > 0]


def _plan_options(level: int, quiet: bool) -> dict[str, Any]:
    if level == 0:
        from cncc.backends.nominal import nominal_trajectory

        return {"level": 0, "estimate": nominal_trajectory}
    from cncc.backends.timing.progress import planning_bar

    return {"level": level, "progress": lambda label, total: planning_bar(label, total, quiet)}
