"""SZGH G25/G61/G26, M99 in a main program, and Fanuc macro B ROUND inside an address
(issue 17).  Each expected motion is derived here from the manual's rule.

* SZGH 002 §3.12/§3.13 (spec E002-12): G25 saves the position of all axes, G61 rapids
  back to it (G611..G614 one axis), without a G25 it acts as G26; §3.11: G26 rapids back
  to the program start point, "the coordinate position of the N0000 block".
* SZGH §3.7 (spec §4, M99): in a main program ``M99`` is ``M02`` (the end) and
  ``M99 P_`` is ``M97 P_`` (a jump to N_).
* Fanuc macro B: ROUND in an NC address rounds to the address's least input increment
  (0.001 mm, 0.001 deg), ROUND elsewhere rounds to an integer.
"""

from __future__ import annotations

from tests.helpers import calls, canon, codes


def traverses(text: str, dialect: str = "szgh", **opts: object) -> list[tuple[float, ...]]:
    lines, r = canon(text, dialect, **opts)
    assert not [c for c in codes(r) if c.startswith("E")], codes(r)
    return [tuple(a[:3]) for n, a in calls(lines, "STRAIGHT_TRAVERSE", "STRAIGHT_FEED")]


def test_e002_12_g25_save_and_g61_return() -> None:
    # the manual's example in mill axes (X, Z), with its U/W increments written as G91 words
    text = ("N0000 G0 X20. Z80. ;\nN0001 G91 G01 X5. Z-16. F200 ;\nN0002 Z-100. ;\nN0003 G00 X10. ;\n"
            "N0004 G90 Z80. ;\nN0005 G25 ;\nN0006 G91 G01 X10. Z-30. ;\nN0007 G90 G0 X100. Z200. ;\n"
            "N0008 G61 ;\nN0009 M2 ;\n")
    pts = [(x, z) for x, _, z in traverses(text)]
    saved = (20.0 + 5.0 + 10.0, 80.0)  # N0005: X 20 + 5 + 10, Z back at 80
    assert pts == [(20.0, 80.0), (25.0, 64.0), (25.0, -36.0), (35.0, -36.0), (35.0, 80.0), (45.0, 50.0),
                   (100.0, 200.0), saved]


def test_g61_single_axis_and_without_g25_acts_as_g26() -> None:
    pts = traverses("G0 X20. Y5. Z80. ;\nG25 ;\nG0 X100. Y50. Z200. ;\nG612 ;\nM2 ;\n")
    assert pts[-1] == (100.0, 5.0, 200.0)  # only Y goes back to the saved 5
    pts = traverses("G0 X20. Y5. Z80. ;\nG61 ;\nM2 ;\n")
    assert pts[-1] == (0.0, 0.0, 0.0)  # no G25: the program start point


def test_g26_returns_to_the_program_start_point_from_any_start() -> None:
    text = "G0 X20. Y5. Z80. ;\nG91 G01 X10. F300 ;\nG26 ;\nM2 ;\n"
    assert traverses(text)[-1] == (0.0, 0.0, 0.0)
    start = (13.0, -7.0, 25.0)  # the machine's position at N0000 (no work offset loaded)
    assert traverses(text, start_machine_mm=start)[-1] == start
    assert traverses("G0 X20. Y5. Z80. ;\nG263 ;\nM2 ;\n")[-1] == (20.0, 5.0, 0.0)  # Z only


def test_m99_in_a_main_program_ends_it() -> None:
    lines, r = canon("G0 X10. ;\nM99 ;\nG0 X20. ;\nM2 ;\n", "szgh")
    assert [a[0] for _, a in calls(lines, "STRAIGHT_TRAVERSE")] == [10.0]  # M99 = M02
    assert calls(lines, "PROGRAM_END")
    assert "E0204" not in codes(r)


def test_m99_p_in_a_main_program_jumps() -> None:
    lines, _ = canon("N1 G0 X10. ;\nM99 P3 ;\nN2 G0 X20. ;\nN3 G0 X30. ;\nM2 ;\n", "szgh")
    assert [a[0] for _, a in calls(lines, "STRAIGHT_TRAVERSE")] == [10.0, 30.0]  # M99 P3 = M97 P3: N2 skipped


def test_round_in_an_address_rounds_to_the_least_input_increment() -> None:
    v = 12.4567
    liu_mm = 0.001
    in_address = round(v / liu_mm) * liu_mm  # 12.457 (half away from zero; no tie here)
    as_integer = float(round(v))  # 12
    text = f"#1={v}\n#2=ROUND[#1]\nG21 G01 X[ROUND[#1]] Y#2 F100.\nG01 Z[ROUND[#1]+1.]\nA[ROUND[#1]]\nM30\n"
    lines, r = canon(text, "fanuc")
    assert not [c for c in codes(r) if c.startswith("E")], codes(r)
    feeds = [a for _, a in calls(lines, "STRAIGHT_FEED")]
    assert abs(feeds[0][0] - in_address) < 1e-9 and feeds[0][1] == as_integer
    assert abs(feeds[1][2] - (in_address + 1.0)) < 1e-9  # ROUND inside the address expression
    assert abs(feeds[2][3] - round(v / 0.001) * 0.001) < 1e-9  # A: 0.001 degree


def test_round_half_away_from_zero_in_an_address() -> None:
    lines, _ = canon("#1=-2.0005\nG21 G01 X[ROUND[#1]] F100.\nM30\n", "fanuc")
    assert abs(calls(lines, "STRAIGHT_FEED")[0][1][0] - (-2.001)) < 1e-9
