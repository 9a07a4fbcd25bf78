"""IR text (cncc/ir/text.py, docs/ir.md): it round-trips on the whole test corpus, a pass runs on IR
text without the front end, and malformed text gives positioned diagnostics (E0194, E0195)."""

from __future__ import annotations

from pathlib import Path

import pytest

from cncc.diagnostics import DiagnosticSink
from cncc.driver import Options, compile_files
from cncc.ir import IDENTITY_FRAME, Frame, Linear, Origin, OriginKind, SetUnits, Units
from cncc.ir.text import ir_text, parse_ir
from cncc.passes import PassContext
from cncc.passes.expand_cycles import ExpandCycles
from cncc.passes.to_machine import ToMachine
from cncc.source import SourceMap, Span
from tests.helpers import compile_commands
from tests.oracle.cases import CASES

ROOT = Path(__file__).resolve().parents[2]
SUFFIXES = (".nc", ".ngc", ".gcode", ".tap")
EXAMPLES = {"contour.nc": "syntec", "fanuc_bolt_circle.nc": "fanuc", "grbl_square.gcode": "grbl",
            "haas_slots.nc": "haas", "linuxcnc_pocket.ngc": "linuxcnc", "series8_part.nc": "series8",
            "szgh_macro.nc": "szgh"}


def _folders() -> list[tuple[str, list[Path]]]:
    """(dialect, programs compiled together) for every folder of test programs."""
    out = [(EXAMPLES[p.name], [p]) for p in sorted((ROOT / "examples").iterdir()) if p.name in EXAMPLES]
    for base in ("tests/corpus", "tests/translate/corpus"):
        for d in sorted((ROOT / base).iterdir()):
            if d.is_dir():
                out.append((d.name, sorted(p for p in d.iterdir() if p.suffix in SUFFIXES)))
    out.append(("linuxcnc", [ROOT / "tests/lsp/data/square.ngc"]))
    return out


FOLDERS = _folders()


def test_the_corpus_covers_every_dialect() -> None:
    assert {d for d, _ in FOLDERS} == {"syntec", "szgh", "series8", "fanuc", "haas", "linuxcnc", "grbl"}
    assert sum(len(ps) for _, ps in FOLDERS) >= 50


def _round_trip(cmds: list[object], where: str, sources: SourceMap | None = None) -> str:
    text = ir_text(cmds, sources)  # type: ignore[arg-type]
    sink = DiagnosticSink()
    back = parse_ir(text, sink)
    assert [d.code for d in sink] == [], where
    assert back == cmds, where
    assert ir_text(back, sources) == text, where
    # frames are shared as in the input: one label per distinct frame, and equal frames are one object
    assert len({id(c.frame) for c in back}) == text.count("\nframe ")
    return text


@pytest.mark.parametrize(("dialect", "paths"), FOLDERS, ids=[f"{d}-{ps[0].parent.name}" for d, ps in FOLDERS])
def test_every_program_round_trips(dialect: str, paths: list[Path]) -> None:
    """print -> parse -> print is the same text and parse(print(x)) == x; with the source comments
    (--emit=ir) the text is the same plus a comment per command (which test_emit_ir... reads back)."""
    for p in paths:
        cmds, r = compile_commands(p.read_text(encoding="utf-8", errors="replace"), dialect=dialect)
        assert cmds, p
        plain = _round_trip(cmds, str(p)).splitlines()
        noted = ir_text(cmds, r.sources).splitlines()
        assert len(noted) == len(plain)
        assert all(n == t or n.startswith(t + "  ; <text>:") for n, t in zip(noted, plain, strict=True))
        assert sum(n != t for n, t in zip(noted, plain, strict=True)) == len(cmds)  # a comment on every command


def test_emit_ir_prints_the_text_form() -> None:
    """--emit=ir writes IR text per input file, with the source lines as comments; it reads back."""
    paths = [str(p) for p in sorted((ROOT / "tests/corpus/fanuc").iterdir()) if p.suffix == ".nc"][:3]
    r = compile_files(Options(inputs=paths, dialect="fanuc", emit="ir"))
    texts = r.output.split("; cncc IR text 1\n")
    assert texts[0] == "" and len(texts) == len(paths) + 1
    sink = DiagnosticSink()
    for k, text in enumerate(texts[1:]):
        back = parse_ir(text, sink)
        assert [d.code for d in sink] == [] and back
        assert ir_text(back, r.sources) == "; cncc IR text 1\n" + text
        assert f"  ; {paths[k]}:" in text  # the source position and line of each command


@pytest.mark.parametrize("name", sorted(CASES))
def test_oracle_cases_round_trip(name: str) -> None:
    case = CASES[name]
    text = case if isinstance(case, str) else case[0]
    cmds, _ = compile_commands(text, dialect="linuxcnc")
    _round_trip(cmds, name)


def test_values_that_text_could_lose_read_back_exactly() -> None:
    """Shortest-repr floats, a negative zero, NaN-free extremes, quotes and non-ASCII in strings."""
    f = Frame(units=Units.INCH, work_offset_mm=(-0.0, 1e-300, 1.7976931348623157e308, 0.1 + 0.2, -2.5, 3.0))
    from cncc.ir import Comment

    cmds = [Comment(Span(3, 0, 5), f, 'say "hi"; ok\\ \u00b5m \u5927'),
            Linear(Span(3, 6, 9), f, (0.0,) * 6, (1.0, 2.0, 3.0, 0.0, 0.0, 0.0), 123.456,  # type: ignore[arg-type]
                   origin=Origin(OriginKind.REFERENCE, "G28")),
            SetUnits(Span(-1, 0, 0), f, Units.INCH)]
    text = _round_trip(cmds, "values")
    back = parse_ir(text)
    assert str(back[0].frame.work_offset_mm[0]) == "-0.0"
    assert back[0].frame.work_offset_mm[3] == 0.30000000000000004


# ---- a pass on IR text, no front end --------------------------------------------------------------
def _run(pass_: ToMachine | ExpandCycles, text: str) -> str:
    cmds = parse_ir(text)
    return ir_text(pass_.run(cmds, PassContext(DiagnosticSink())))


def test_to_machine_on_ir_text() -> None:
    """G54 X100 Y50 plus a G92 shift of Z-5: machine = program + work + G92 (docs/frames.md)."""
    source = (
        "frame f0 = Frame(work_offset_mm=(100.0, 50.0, 0.0, 0.0, 0.0, 0.0), "
        "g92_offset_mm=(0.0, 0.0, -5.0, 0.0, 0.0, 0.0))\n"
        "Rapid @0:0-10 f0 start=(0.0, 0.0, 0.0, 0.0, 0.0, 0.0) end=(10.0, 20.0, 3.0, 0.0, 0.0, 0.0)\n"
        "Linear @0:11-20 f0 start=(10.0, 20.0, 3.0, 0.0, 0.0, 0.0) end=(10.0, 20.0, -1.0, 0.0, 0.0, 0.0) "
        "feed_mm_min=250.0\n")
    expected = (
        "; cncc IR text 1\n"
        "frame f0 = Frame()\n"
        f"Rapid @0:0-10 f0 start=(100.0, 50.0, -5.0, 0.0, 0.0, 0.0) end=({100.0 + 10.0}, {50.0 + 20.0}, "
        f"{3.0 - 5.0}, 0.0, 0.0, 0.0)\n"
        f"Linear @0:11-20 f0 start=(110.0, 70.0, -2.0, 0.0, 0.0, 0.0) end=(110.0, 70.0, {-1.0 - 5.0}, 0.0, 0.0, 0.0) "
        "feed_mm_min=250.0\n")
    out = _run(ToMachine(), source)
    assert out == expected
    assert parse_ir(out)[0].frame == IDENTITY_FRAME


def test_expand_cycles_on_ir_text() -> None:
    """One G81 hole (G99: back to R): rapid over the hole, rapid to R, feed to Z, rapid to R (docs/cycles.md)."""
    source = (
        "frame f0 = Frame()\n"
        "Cycle @0:0-30 f0 kind=CycleKind.DRILL code=\"G81\" start=(0.0, 0.0, 20.0, 0.0, 0.0, 0.0) "
        "holes=((5.0, 6.0, 0.0, 0.0, 0.0, 0.0),) initial_mm=20.0 r_mm=2.0 bottom_mm=-8.0 retract_mm=2.0 "
        "feed_mm_min=100.0 return_initial=false\n")
    cyc = 'motion=Motion(mode=PathMode.EXACT_STOP) origin=Origin(kind=OriginKind.CYCLE, code="G81")'
    expected = (
        "; cncc IR text 1\n"
        "frame f0 = Frame()\n"
        f"Rapid @0:0-30 f0 start=(0.0, 0.0, 20.0, 0.0, 0.0, 0.0) end=(5.0, 6.0, 20.0, 0.0, 0.0, 0.0) {cyc}\n"
        f"Rapid @0:0-30 f0 start=(5.0, 6.0, 20.0, 0.0, 0.0, 0.0) end=(5.0, 6.0, 2.0, 0.0, 0.0, 0.0) {cyc}\n"
        f"Linear @0:0-30 f0 start=(5.0, 6.0, 2.0, 0.0, 0.0, 0.0) end=(5.0, 6.0, -8.0, 0.0, 0.0, 0.0) "
        f"feed_mm_min=100.0 {cyc}\n"
        f"Rapid @0:0-30 f0 start=(5.0, 6.0, -8.0, 0.0, 0.0, 0.0) end=(5.0, 6.0, 2.0, 0.0, 0.0, 0.0) {cyc}\n")
    assert _run(ExpandCycles(), source) == expected


# ---- malformed text -------------------------------------------------------------------------------
GOOD_FRAME = "frame f0 = Frame()\n"


@pytest.mark.parametrize(("line", "code", "column"), [
    ("Rapid 0:0-1 f0 start=(0.0, 0.0, 0.0, 0.0, 0.0, 0.0) end=(0.0, 0.0, 0.0, 0.0, 0.0, 0.0)", "E0194", 7),
    ("Rapid @0:0-1 f9 start=(0.0, 0.0, 0.0, 0.0, 0.0, 0.0) end=(0.0, 0.0, 0.0, 0.0, 0.0, 0.0)", "E0195", 14),
    ("Rapd @0:0-1 f0", "E0195", 1),
    ("Dwell @0:0-1 f0 seconds=2.0 minutes=1.0", "E0195", 29),
    ("Dwell @0:0-1 f0 seconds=\"2\"", "E0195", 17),
    ("Dwell @0:0-1 f0", "E0195", 1),
    ("Dwell @0:0-1 f0 seconds=2.0 seconds=3.0", "E0195", 29),
    ("Spindle @0:0-1 f0 state=SpindleState.SIDEWAYS rpm=1.0", "E0195", 25),
    ("Rapid @0:0-1 f0 start=(0.0, 0.0) end=(0.0, 0.0, 0.0, 0.0, 0.0, 0.0)", "E0195", 17),
    ("Dwell @0:0-1 f0 seconds=(1.0", "E0194", 29),
    ("Dwell @0:0-1 f0 seconds=1.0 $", "E0194", 29),
    ("Dwell @0:0-1 f0 seconds=Frame()", "E0195", 17),
    ("Comment @0:0-1 f0 text=\"unclosed", "E0194", 24),
])
def test_malformed_ir_text_is_reported_where_it_is(line: str, code: str, column: int) -> None:
    text = GOOD_FRAME + line + "\nDwell @0:2-3 f0 seconds=1.0\n"
    sink = DiagnosticSink()
    cmds = parse_ir(text, sink, source_id=7)
    assert [d.code for d in sink] == [code]
    d = next(iter(sink))
    assert d.span.source_id == 7
    line_start = len(GOOD_FRAME)
    assert d.span.start - line_start + 1 == column, d.message
    assert d.span.end >= d.span.start
    assert len(cmds) == 1 and cmds[0].span == Span(0, 2, 3)  # the bad line is skipped, the next one read


def test_a_frame_must_be_a_frame() -> None:
    sink = DiagnosticSink()
    parse_ir("frame f0 = Motion()\nframe x = Frame()\n", sink)
    assert [d.code for d in sink] == ["E0195", "E0194"]
