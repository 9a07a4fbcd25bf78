"""``--emit=gcode`` in the same dialect re-parses to the same motion."""

from __future__ import annotations

from pathlib import Path

from hypothesis import given, settings
from hypothesis import strategies as st

from cncc.api import compile_commands, compile_text
from tests.translate.motion import difference
from tests.translate.motion import motion as machine_motion

ROOT = Path(__file__).resolve().parents[2]


def motion(text: str, **opts: object) -> list[tuple[object, ...]]:
    """Moves and dwells in machine terms; arcs the emitter had to cut are joined (tests/translate/motion.py)."""
    cmds, r = compile_commands(text, **opts)
    assert r.ok, [(d.code, d.message) for d in r.sink]
    return machine_motion(cmds)


def roundtrip(text: str) -> None:
    """Positions agree to the output precision: 1 um in mm, half of 0.0001 inch in inch."""
    r = compile_text(text, emit="gcode")
    assert r.ok
    tol = 1.3e-3 if "G70" in text else 1e-6
    why = difference(motion(text), motion(r.output), tol_mm=tol)
    assert not why, (why, r.output)


def test_example_roundtrips() -> None:
    roundtrip((ROOT / "examples" / "contour.nc").read_text())


def test_modes_units_planes_and_offsets_roundtrip() -> None:
    roundtrip("G91 G01 X1. Y2. F100\nG90 G18 G02 X5. Z1. I2. K0.5\nG70 G01 X1. F10\n"
              "G71 G17 G00 X0 Y0\nG04 X1.5\nG03 I1. J0 F20\nM30\n")


def test_integer_words_keep_their_meaning() -> None:
    text = "G00 X5500 Y4000\nG01 X1500 F200\n"
    r = compile_text(text, emit="gcode")
    assert "X5.5" in r.output and "X1.5" in r.output  # written with a point, never as 5500
    roundtrip(text)


# 0.01 mm steps: finer geometry cannot survive an inch program's 4 decimals (2.54 um)
coord = st.integers(-10000, 10000).map(lambda i: f"{i / 100:.2f}")
block = st.one_of(
    st.tuples(st.sampled_from(["G00", "G01", "G90 G01", "G91 G01", "G90 G00"]),
              st.lists(st.tuples(st.sampled_from("XYZ"), coord), min_size=1, max_size=3, unique_by=lambda t: t[0]),
              st.sampled_from(["", " F100.", " F1500."])).map(
        lambda t: t[0] + " " + " ".join(a + v for a, v in t[1]) + t[2]),
    st.tuples(st.sampled_from(["G02", "G03"]), coord, coord).filter(lambda t: float(t[1]) or float(t[2])).map(
        lambda t: f"G90 {t[0]} I{t[1]} J{t[2]} F200."),
    st.sampled_from(["G04 X0.5", "G04 P250", "G70", "G71", "M03 S1000", "M05", "T2 M06"]),
)


@settings(max_examples=60, deadline=None)
@given(st.lists(block, min_size=1, max_size=15))
def test_generated_programs_roundtrip(blocks: list[str]) -> None:
    roundtrip("\n".join(["G90 G71 G17 G00 X0 Y0 Z0", *blocks, "M30"]) + "\n")


def test_full_circle_after_a_unit_change_stays_a_full_circle() -> None:
    """Found by the property above: Y reached in inch (0.264 mm, written 0.0104 in = 0.26416 mm) and then a
    full circle in mm.  The target is where the inch numbers put it, not at 0.264 mm, so an end word of
    Y0.264 would turn the circle into a 0.016 rad arc; the emitter must still sweep the whole circle."""
    text = ("G90 G71 G17 G00 X0 Y0 Z0\nG00 Y0.01\nG70\nG00 X0.00\nG91 G01 Y0.01 F100.\nG71\n"
            "G90 G02 I-0.01 J0.00 F200.\nM30\n")
    roundtrip(text)
