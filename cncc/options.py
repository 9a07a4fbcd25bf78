"""The compiler's options: one :class:`Options` record per compilation (or per input file, with its
``cncc.toml`` and modeline settings).

The command line (:func:`cncc.cli.build_options`), :mod:`cncc.api`, the language server and the batch
runner fill it in; the driver (:mod:`cncc.driver`) resolves it per file and the backend stage
(:mod:`cncc.emit`) reads it.  It is data only: what the options mean is decided where they are read.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from cncc.diagnostics import WarningPolicy

DEFAULT_DIALECT = "syntec"
DEFAULT_MACHINE = "generic-mill"


@dataclass(slots=True)
class Options:
    inputs: list[str] = field(default_factory=list)
    dialect: str | None = None
    target: str | None = None
    machine: str = DEFAULT_MACHINE
    emit: str = "canon"
    output: str | None = None
    syntax_only: bool = False
    werror: bool = False
    strict: bool = False
    opt_level: int = 2
    offsets_file: str | None = None
    tools_file: str | None = None
    ini_file: str | None = None  # --ini: a LinuxCNC INI file (cncc/inifile.py)
    dialect_options: dict[str, Any] = field(default_factory=dict)
    block_delete: bool = True
    repair_arcs: bool = False
    report_format: str = "text"
    # macros and subprograms (cncc/frontend/macro): -D, -I, -M, -E, --max-steps, --io, --write-dir
    defines: dict[int, float] = field(default_factory=dict)
    include_dirs: list[str] = field(default_factory=list)
    list_deps: bool = False
    expand: bool = False
    max_steps: int = 5_000_000
    io_file: str | None = None
    write_dir: str | None = None
    compare: str = ""  # timing report columns: "O0,O1,O2" or machine names (NAME@O1)
    annotate_time: bool = False  # timing: the program with elapsed times as comments
    verbose: bool = False  # -v: notes on what the driver chose (the guessed dialect)
    start_machine_mm: tuple[float, ...] | None = None  # machine position at the start (default: the G54 zero)
    quiet: bool = False  # -q: no progress bars
    # translation (--emit=gcode -t, cncc/backends/gcode, docs/translation.md)
    units: str = ""  # --units: "" as programmed, "mm" or "inch"
    line_numbers: bool = False  # -fline-numbers
    keep_subprograms: bool = False  # --keep-subprograms: called programs kept where the target calls them
    target_options: dict[str, Any] = field(default_factory=dict)  # --target-option NAME=VALUE (the -t dialect)
    decimals_mm: int | None = None  # --decimals-mm
    decimals_inch: int | None = None  # --decimals-inch
    pulse_format: str = "vcd"  # --emit=pulses: vcd | csv | npz | queue
    pulse_mode: str = "exact"  # --emit=pulses: exact | interp (SZGH 2 ms interpolation)
    verify: bool = True  # -fno-verify: skip the verify pass after plan (timing, pulses)
    # the pass manager (cncc/pipeline, docs/architecture.md "Pipeline")
    passes: str = ""  # -p 'name{opt=value},name2': the passes instead of the default pipeline
    verify_each: bool = False  # --verify-each: check the IR invariants after every pass
    print_after: tuple[str, ...] = ()  # --print-after=NAME: the IR after these passes
    print_file: str | None = None  # --print-file=FILE: where --print-after writes (default: stderr)
    time_passes: bool = False  # --time-passes: the per-pass timing table on stderr
    keep_trajectory: bool = False  # --emit=timing: keep the trajectories in Result.runs (cncc.api), never stream
    # the command line (cncc/cli.py): project configuration and what the diagnostics options ask
    project_config: bool = False  # read cncc.toml and the modeline per input (cncc/config.py)
    given: frozenset[str] = frozenset()  # fields set on the command line (they beat cncc.toml and the modeline)
    policy: WarningPolicy = field(default_factory=WarningPolicy)  # -w, -Wno-CODE, -Werror=CODE, -fmax-errors

