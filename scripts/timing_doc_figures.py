"""Regenerate the figures of docs/timing.md from examples/contour.nc (run from the repo root)."""

from __future__ import annotations

from pathlib import Path

from cncc.api import compile_commands
from cncc.backends.timing.aggregate import build_report
from cncc.backends.timing.plots import feed_plot, path_plot
from cncc.diagnostics import DiagnosticSink
from cncc.driver import Options, resolve_machine, timing_runs


def main() -> None:
    example = "examples/contour.nc"
    cmds, res = compile_commands(Path(example).read_text())
    machine = resolve_machine("generic-mill", DiagnosticSink())
    assert machine is not None
    runs = timing_runs(cmds, machine, Options(opt_level=2), DiagnosticSink())
    rep = build_report(cmds, runs, res.sources, example, "syntec")
    Path("docs/timing-contour-speed.svg").write_text(feed_plot(rep, len(cmds)) + "\n")
    Path("docs/timing-contour-path.svg").write_text(path_plot(rep, cmds) + "\n")
    print(f"O2 {rep.primary.total_ns / 1e9:.3f} s, nominal {rep.columns[1].total_ns / 1e9:.3f} s")


if __name__ == "__main__":
    main()
