"""Hypothesis: translated programs move like their source, for every target dialect.

Programs are generated in SYNTEC (moves in G90 and G91, arcs by I/J and by R in three
planes, helices, units changes, dwells, drilling cycles with G98/G99, G52 and work
offsets) and translated to each dialect in ``cncc/dialects``.
"""

from __future__ import annotations

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from cncc.dialects import available
from tests.backends.test_translate_roundtrip import check

coord = st.integers(-50000, 50000).map(lambda i: f"{i / 1000:.3f}")
small = st.integers(1000, 20000).map(lambda i: f"{i / 1000:.3f}")
chord = st.integers(1000, 30000).flatmap(lambda i: st.sampled_from([i, -i])).map(lambda i: f"{i / 1000:.3f}")
axes = st.lists(st.tuples(st.sampled_from("XYZ"), coord), min_size=1, max_size=3, unique_by=lambda t: t[0])

move = st.tuples(st.sampled_from(["G00", "G01", "G90 G01", "G91 G01", "G90 G00"]), axes,
                 st.sampled_from(["", " F100.", " F1500.", " F733.3"])).map(
    lambda t: t[0] + " " + " ".join(a + v for a, v in t[1]) + t[2])
arc_ij = st.tuples(st.sampled_from(["G02", "G03"]), chord, coord, st.sampled_from(["", " Z-2.", " Z3.5"])).map(
    lambda t: f"G90 G17 {t[0]} I{t[1]} J{t[2]}{t[3]} F200.")
arc_r = st.tuples(st.sampled_from(["G02", "G03"]), chord, coord, small, st.booleans()).map(
    lambda t: f"G90 G17 {t[0]} X[#5001+{t[1]}] Y[#5002+{t[2]}] R{'-' if t[4] else ''}[{t[3]}+"
              f"SQRT[{t[1]}*{t[1]}+{t[2]}*{t[2]}]/2] F300.")
plane_arc = st.sampled_from(["G18 G02 I5. K0. F250.", "G19 G03 J0. K-4. F250.",
                             "G90 G18 G03 X[#5001+3.] Z[#5003+3.] R3."])
drill = st.tuples(st.sampled_from(["G81", "G83 Q2.", "G73 Q1.5", "G82 P0.3", "G85", "G86"]),
                  st.sampled_from(["G98", "G99"]), coord, coord).map(
    lambda t: f"G17 G90 G00 Z30.\n{t[1]} {t[0].split()[0]} X{t[2]} Y{t[3]} Z-5. R2. "
              f"{' '.join(t[0].split()[1:])} F120.\nX[{t[2]}+10.]\nG80")
other = st.sampled_from(["G04 X0.5", "G04 P250", "G70", "G71", "M03 S1000", "M05", "G55", "G54",
                         "G52 X5. Y-3.", "G52 X0 Y0", "G17"])
block = st.one_of(move, arc_ij, arc_r, plane_arc, drill, other)


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(block, min_size=1, max_size=10), st.sampled_from(available()))
def test_generated_programs_translate_to_the_same_motion(blocks: list[str], target: str) -> None:
    text = "\n".join(["G90 G71 G17 G00 X0 Y0 Z0", *blocks, "G71 G17", "M30"]) + "\n"
    inch = "G70" in text
    check(text, "syntec", target, tol_mm=1.3e-3 if inch else 1e-3)
