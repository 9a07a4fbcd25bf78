"""Translation keeps the motion from any start position (issue 17) and keeps G10 offset
changes (issue 25), on generated programs, for every source with the feature and every
target.

A machine starts wherever it is.  Each generated program is translated once; then the
source and its translation are both run from two start positions (the G54 zero and the
machine point 13, -7, 25) and their moves compared block by block in machine
coordinates (work offsets and tool length added: ``tests/translate/motion.py``).  The
programs mix what used to break this: explicit words equal to the assumed start on the
first move of an axis (``G00 X0 Y10 Z5``), a tool change before a partial move, G91
moves of axes the program has not positioned yet, ``G10 L2 P2`` setting G55 before
moving in it (the target's G10, or the offset folded into the coordinates where the
target has no G10), and the other offset-setting forms, G52 and G92.  docs/translation.md says what "same motion" means.
"""

from __future__ import annotations

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from cncc.api import compile_commands, compile_text
from cncc.dialects import available
from tests.backends.test_translate_roundtrip import TABLES, translate
from tests.translate.motion import difference, motion

STARTS = [None, (13.0, -7.0, 25.0)]
SOURCES = ["fanuc", "syntec", "szgh", "linuxcnc", "grbl"]
TARGETS = available()
METRIC = {"syntec": "G71", "series8": "G71"}
END = {"linuxcnc": "M2", "grbl": "M2"}
HAS_G10 = {"fanuc", "syntec", "linuxcnc", "grbl"}
HAS_TOOL_CHANGE = {"fanuc", "syntec", "szgh", "linuxcnc"}
HAS_G52 = {"fanuc", "syntec", "szgh", "linuxcnc"}
HAS_G92 = {"fanuc", "syntec", "szgh", "grbl"}

value = st.sampled_from(["0", "0.", "5.", "-3.5", "12.25", "-20."])


def words(draw: st.DrawFn, min_size: int = 1) -> str:
    axes = draw(st.lists(st.sampled_from("XYZ"), min_size=min_size, max_size=3, unique=True))
    return " ".join(f"{a}{draw(value)}" for a in sorted(axes))


@st.composite
def programs(draw: st.DrawFn) -> tuple[str, str]:
    src = draw(st.sampled_from(SOURCES))
    lines = [f"{METRIC.get(src, 'G21')} G90 G17 G94"]
    if draw(st.booleans()):  # increments before any absolute position
        lines += [f"G91 G01 {words(draw)} F400.", "G90"]
    lines.append(f"G00 {words(draw)}")
    lines.append(f"G01 {words(draw)} F300.")
    if src in HAS_G10 and draw(st.booleans()):
        lines.append(f"G10 L2 P2 X{draw(value)} Y{draw(value)} Z{draw(value)}")
        lines += ["G55", f"G00 {words(draw, 2)}", f"G01 {words(draw)} F250.", "G54"]
    if src in HAS_G52 and draw(st.booleans()):  # a local offset, then moves in it, then cancelled
        lines += [f"G52 X{draw(value)} Y{draw(value)}", f"G00 {words(draw)}", f"G01 {words(draw)} F350.",
                  "G52 X0 Y0 Z0"]
    if src in HAS_G92 and draw(st.booleans()):  # a G92 preset where the tool is
        lines += [f"G92 {words(draw)}", f"G00 {words(draw)}"]
    if src in HAS_TOOL_CHANGE and draw(st.booleans()):
        lines += ["T2 M06" if src != "linuxcnc" else "T2 M6", f"G00 {words(draw)}"]
        if draw(st.booleans()):
            lines += [f"G91 G00 {words(draw)}", "G90"]
    lines.append(f"G01 {words(draw)} F500.")
    lines.append(END.get(src, "M30"))
    return src, "\n".join(lines) + "\n"


def run(text: str, dialect: str, start: tuple[float, ...] | None) -> list[tuple[object, ...]]:
    cmds, r = compile_commands(text, dialect=dialect, start_machine_mm=start, **TABLES)  # type: ignore[arg-type]
    assert r.ok, [(d.code, d.message) for d in r.sink]
    return motion(cmds)


@settings(max_examples=100, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(programs(), st.sampled_from(TARGETS))
def test_translation_moves_alike_from_two_start_positions(case: tuple[str, str], target: str) -> None:
    src, text = case
    out = translate(text, src, target)
    for start in STARTS:
        want = run(text, src, start)
        got = run(out, target, start)
        why = difference(want, got, 1e-3)
        assert not why, f"start {start}: {why}\n--- {src} source:\n{text}--- translation to {target}:\n{out}"


def test_the_issue_example_keeps_x0() -> None:
    """``G00 X0 Y10 Z5`` used to become ``G00 Y10. Z5.`` (X dropped as equal to an assumed 0)."""
    out = translate("G21 G90\nG00 X0 Y10. Z5.\nM30\n", "fanuc", "fanuc")
    assert "G00 X0. Y10. Z5." in out


def test_g91_from_an_unknown_start_stays_incremental() -> None:
    text = "G21 G91 G01 X10. F100.\nG90 G00 X0 Y0 Z0\nM30\n"
    out = translate(text, "fanuc", "linuxcnc")
    assert "G91 G01 X10. F100.\nG90\n" in out
    start = (13.0, -7.0, 25.0)
    assert run(text, "fanuc", start)[0][1][:3] == (23.0, -7.0, 25.0)  # 10 from where the machine was
    assert not difference(run(text, "fanuc", start), run(out, "linuxcnc", start))


def test_g10_work_offset_survives_translation() -> None:
    text = "G21 G90 G54\nG10 L2 P2 X100. Y50. Z0\nG55 G00 X10. Y10. Z5.\nM30\n"
    for target in ("fanuc", "syntec", "linuxcnc", "grbl"):
        assert "G10 L2 P2 X100. Y50. Z0." in translate(text, "fanuc", target), target
    for target in TARGETS:  # with the target's G10 or folded: the machine goes to 100 + 10, 50 + 10
        out = translate(text, "fanuc", target)
        assert not difference(run(text, "fanuc", None), run(out, target, None)), (target, out)
        assert run(out, target, None)[-1][1][:2] == (110.0, 60.0)


def moves_alike_into_every_target(text: str, src: str) -> None:
    """``text`` and its translation into every target give the same machine positions from each start."""
    for target in TARGETS:
        out = translate(text, src, target)
        for start in STARTS:
            why = difference(run(text, src, start), run(out, target, start), 1e-3)
            assert not why, (target, start, why, out)


def test_linuxcnc_g52_of_an_unpositioned_axis_moves_alike_from_any_start() -> None:
    """Found by the property above once G52 became LinuxCNC's G92 offset: Y has no position yet when
    ``G52 Y5.`` runs, so a target ``G92 Y-5.`` would set the origin from wherever the machine is.  The
    offset change must be written position-independently (the target's G52) and still cancel."""
    text = ("G21 G90 G17 G94\nG00 X0\nG01 X0 F300.\nG52 X0 Y5.\nG00 X0 Y0\nG01 X0 F350.\nG52 X0 Y0 Z0\n"
            "G01 X0 F500.\nM2\n")
    moves_alike_into_every_target(text, "linuxcnc")


def test_incremental_cycle_from_an_unknown_start_moves_alike() -> None:
    """A G91 drilling cycle as the first motion: its holes are increments from wherever the machine is,
    so no target may get them as absolute coordinates (the cycle is written as its G91 moves)."""
    text = "G21 G17 G91 G98 G81 X10. Y10. Z-5. R-2. F100.\nX10.\nG80\nG90 G00 X0 Y0 Z50.\nM30\n"
    moves_alike_into_every_target(text, "fanuc")


def test_szgh_return_to_start_is_kept_or_refused() -> None:
    """SZGH G26 (and G261-G264 for one axis) return to where the program started, which only the
    machine knows: kept as the code in SZGH output (same motion from any start), refused with E0861
    where the target has no such code, never written as a rapid to an assumed start."""
    for code in ("G26", "G262"):
        text = f"G00 X10. Y10. Z5.\nG01 X20. F300.\n{code}\nG01 X30.\nM30\n"
        out = translate(text, "szgh", "szgh")
        assert f"\n{code}\n" in out
        for start in STARTS:
            why = difference(run(text, "szgh", start), run(out, "szgh", start), 1e-3)
            assert not why, (code, start, why, out)
        r = compile_text(text, dialect="szgh", emit="gcode", target="fanuc")
        assert "E0861" in [d.code for d in r.sink]
