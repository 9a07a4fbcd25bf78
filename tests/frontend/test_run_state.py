"""One owner of run state: the interpreter declares its fields (no per-module side tables),
executors report through an explicit redirect, and an interpreter's run state can be
copied and restored (the LSP's checkpoints) including the records of every layer."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest

from cncc.diagnostics import DiagnosticSink
from cncc.dialects import load_dialect
from cncc.frontend.interp import Interpreter
from cncc.frontend.run_state import LayerRecords, TransformState

ROOT = Path(__file__).resolve().parents[2]
FRONTEND = ROOT / "cncc" / "frontend"


def test_no_module_keeps_per_interpreter_side_tables() -> None:
    offenders = [str(p.relative_to(ROOT)) for p in FRONTEND.rglob("*.py")
                 if re.search(r"WeakKeyDictionary|weakref", p.read_text(encoding="utf-8"))]
    assert offenders == []


def test_the_interpreter_has_only_its_declared_fields() -> None:
    it = Interpreter(load_dialect("syntec"), DiagnosticSink())
    assert not hasattr(it, "__dict__")
    with pytest.raises(AttributeError):
        it.undeclared = 1  # type: ignore[attr-defined]


def test_no_executor_replaces_the_interpreters_sink_or_source() -> None:
    assign = re.compile(r"\.(sink|source_id)\s*=(?!=)")
    offenders = []
    for p in FRONTEND.rglob("*.py"):
        if p.name == "interp.py":
            continue
        for n, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1):
            if assign.search(line) and not re.search(r"\bself\.(sink|source_id)\s*=", line):
                offenders.append(f"{p.relative_to(ROOT)}:{n}")
    assert offenders == []


def test_redirect_restores_sink_and_source_even_after_an_error() -> None:
    outer, inner = DiagnosticSink(), DiagnosticSink()
    it = Interpreter(load_dialect("syntec"), outer, source_id=3)
    with pytest.raises(RuntimeError), it.redirect(sink=inner, source_id=7):
        assert (it.sink, it.source_id) == (inner, 7)
        raise RuntimeError
    assert (it.sink, it.source_id) == (outer, 3)
    with it.redirect(source_id=9):
        assert (it.sink, it.source_id) == (outer, 9)
    assert it.source_id == 3


def test_run_state_copies_the_mutable_records() -> None:
    it = Interpreter(load_dialect("syntec"), DiagnosticSink())
    it.transform.length_wear_mm[1] = 0.3
    saved = it.run_state()
    it.transform.length_wear_mm[1] = 0.5  # a later G10 L11 P1 R0.5
    it.notes.m_codes_warned.add(800)
    assert saved["transform"] == TransformState(length_wear_mm={1: 0.3})
    assert saved != it.run_state()
    it.restore_run_state(saved)
    assert it.transform.length_wear_mm == {1: 0.3} and it.notes.m_codes_warned == set()
    it.transform.length_wear_mm[1] = 0.7
    assert saved["transform"] == TransformState(length_wear_mm={1: 0.3})  # a restore does not share it


def test_layer_records_hold_one_record_per_type() -> None:
    from cncc.frontend.series8.state import S8State

    records = LayerRecords()
    assert records.get(S8State) is None
    first = records.attach(S8State(sharp=True))
    assert records.get(S8State) is first
    second = records.attach(S8State())
    assert records.get(S8State) is second and not second.sharp


def test_a_resumed_lsp_analysis_keeps_offsets_written_before_the_checkpoint() -> None:
    """G10 writes a tool length, its wear and a work offset at the top; G43 H1 and G55 far
    below the last checkpoint use them.  Resuming after an edit near them must give what a
    full analysis gives (the wear is in the interpreter's transform record, the tables in
    its own copy of the options; the checkpoint copies both)."""
    sys.path.insert(0, str(ROOT / "tests" / "lsp"))
    from test_incremental import assert_same, full, resumed  # type: ignore[import-not-found]

    lines = ["%", "O1000", "G90 G17 G21 G94", "G10 L10 P1 R50.", "G10 L11 P1 R0.3", "G10 L2 P2 X10. Y20.",
             "G00 X0 Y0 Z5.", "G01 Z-1. F600."]
    lines += [f"G01 X{i % 17}.5 Y{i % 11}." for i in range(400)]
    lines += ["G43 H1 Z20.", "G01 X3. Y3.", "G55 G01 X1.", "G49 Z30.", "M30", "%"]
    text = "\n".join(lines) + "\n"
    old = full(text)
    edited = text.replace("G01 X3. Y3.", "G01 X4. Y3.")
    got = resumed(old, edited)
    assert got is not None  # resumed, not re-run from the top
    assert_same(got, full(edited))


def test_a_program_does_not_write_the_callers_tables() -> None:
    """G10 changes the interpreter's tables, not the options object the caller gave."""
    from cncc.frontend.interp import InterpOptions
    from cncc.frontend.parser import Parser
    from cncc.source import SourceMap

    opts = InterpOptions(tool_lengths_mm={1: 10.0})
    sink = DiagnosticSink()
    it = Interpreter(load_dialect("syntec"), sink, 0, opts)
    src = SourceMap().add("t.nc", "G10 L10 P1 R50.\nG10 L2 P1 X5.\n")
    for block in Parser(it.dialect, sink).blocks(src):
        it.execute(block)
    assert it.options.tool_lengths_mm == {1: 50.0} and it.options.work_offsets_mm[1][0] == 5.0
    assert opts.tool_lengths_mm == {1: 10.0} and opts.work_offsets_mm == {}
