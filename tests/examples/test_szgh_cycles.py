"""SZGH canned-cycle examples E002-27 ... E002-38 (shared/spec/szgh-990mdb.md section 4).

The programs are the manual's, without the prose lines between blocks; the expected
move sequences are the spec's "Expected" paragraphs.  The tool starts at Z0, so the
initial level is 0.  User P1 = P2 = 5 mm (the factory values) are the dialect defaults.
"""

from __future__ import annotations

import pytest

from tests.helpers import calls, canon, codes, compile_commands

Token = tuple[object, ...]
_SPINDLE = {"START_SPINDLE_CLOCKWISE": "CW", "START_SPINDLE_COUNTERCLOCKWISE": "CCW",
            "STOP_SPINDLE_TURNING": "OFF", "ORIENT_SPINDLE": "ORIENT"}


def tokens(text: str, **options: object) -> tuple[list[Token], list[str]]:
    lines, r = canon(text, "szgh", dialect_options=options) if options else canon(text, "szgh")
    assert r.ok, [d.message for d in r.sink]
    out: list[Token] = []
    for name, args in calls(lines):
        if name == "STRAIGHT_TRAVERSE":
            out.append(("R", *args[:3]))
        elif name == "STRAIGHT_FEED":
            out.append(("F", *args[:3]))
        elif name == "DWELL":
            out.append(("D", args[0]))
        elif name in _SPINDLE:
            out.append((_SPINDLE[name],))
    return out, codes(r)


def frame(holes: list[tuple[float, float]], per_hole: object, r_mm: float, last_g98: bool = True,
          first: str = "CW", start_at_r: bool = False) -> list[Token]:
    """Positioning at the current height, rapid to R, the hole, return (G99 R; last hole G98: 0)."""
    out: list[Token] = [(first,)]
    height, pos = 0.0, (0.0, 0.0)
    for k, (x, y) in enumerate(holes):
        ret = 0.0 if last_g98 and k == len(holes) - 1 else r_mm
        if (x, y) != pos:
            out.append(("R", x, y, height))
        if height != r_mm:
            out.append(("R", x, y, r_mm))
        out.extend(per_hole(x, y, ret))  # type: ignore[operator]
        height, pos = ret, (x, y)
    return out


def until_cancel(t: list[Token], n: int) -> list[Token]:
    return t[:n]


def test_e002_27_g73_high_speed_peck() -> None:
    text = ("M3 S2000 ;\tCause the spindle to start rotating\n"
            "G90 G99 G73 X300. Y-250. Z-150. R-100. Q15. F120. ;\n"
            "Y-550. ;\nY-750. ;\nX1000. ;\nY-550. ;\nG98 Y-750. ;\nG80 G28 G91 X0 Y0 Z0;\nM05 ;\n")

    def hole(x: float, y: float, ret: float) -> list[Token]:
        return [("F", x, y, -115.0), ("R", x, y, -110.0), ("F", x, y, -130.0), ("R", x, y, -125.0),
                ("F", x, y, -145.0), ("R", x, y, -140.0), ("F", x, y, -150.0), ("R", x, y, ret)]

    holes = [(300.0, -250.0), (300.0, -550.0), (300.0, -750.0), (1000.0, -750.0), (1000.0, -550.0),
             (1000.0, -750.0)]
    want = frame(holes, hole, -100.0)
    t, _ = tokens(text)
    assert t[:len(want)] == want
    feed_mm = sum(15 + 20 + 20 + 10 for _ in holes)
    assert feed_mm == 6 * 65  # the spec's 65 mm of feed per hole


def test_e002_28_g74_left_hand_tap_feed_s_times_k() -> None:
    text = ("N1 M4 S100 ;\nN2 G90 G99 G74 X300. Y-250. Z-150. R-100. K5 ;\nN3 Y-550. ;\nN4 Y-750. ;\n"
            "N5 X1000. ;\nN6 Y-750. ;\nN7 G98 Y-550. K5;\nN8 G80 G28 G91 X0 Y0 Z0;\nN9 M05;\n")

    def hole(x: float, y: float, ret: float) -> list[Token]:
        return [("F", x, y, -150.0), ("CW",), ("F", x, y, -100.0), ("CCW",),
                *([("R", x, y, ret)] if ret == 0.0 else [])]

    holes = [(300.0, -250.0), (300.0, -550.0), (300.0, -750.0), (1000.0, -750.0), (1000.0, -750.0),
             (1000.0, -550.0)]
    want = frame(holes, hole, -100.0, first="CCW")
    t, _ = tokens(text)
    assert t[:len(want)] == want
    from cncc.ir import Linear, SpindleSync

    cmds, _ = compile_commands(text, dialect="szgh")
    tap = [c for c in cmds if isinstance(c, Linear) and c.origin.code == "G74"]
    assert {c.feed_mm_min for c in tap} == {500.0}  # S100 x K5
    assert {c.pitch_mm for c in cmds if isinstance(c, SpindleSync)} == {5.0, 0.0}


def test_e002_28_g74_without_pitch_is_an_error() -> None:
    _, r = canon("M4 S100 ;\nG90 G99 G74 X300. Y-250. Z-150. R-100. ;\nG80 ;\n", "szgh")
    assert "E0412" in codes(r)


E29 = ("N10 M3 S500 ;\nN20 G90 G99 G{g} X300 Y-250 Z-150 R-100 Q5 P1 F120;\nN30 Y-350 ;\nN40 Y-550 ;\n"
       "N50 X1000 ;\nN60 Y-550 ;\nN70 G98 Y-750 ;\nN80 G80 G28 G91 X0 Y0 Z0 ;\nN90 M5 ;\n")


def test_e002_29_g76_fine_boring() -> None:
    def hole(x: float, y: float, ret: float) -> list[Token]:
        return [("F", x, y, -150.0), ("D", 1.0), ("ORIENT",), ("R", x + 5, y, -150.0), ("R", x + 5, y, ret),
                ("R", x, y, ret), ("CW",)]

    holes = [(300.0, -250.0), (300.0, -350.0), (300.0, -550.0), (1000.0, -550.0), (1000.0, -550.0),
             (1000.0, -750.0)]
    want = frame(holes, hole, -100.0)
    t, _ = tokens(E29.format(g=76))
    assert t[:len(want)] == want


def test_e002_29_printed_g75_is_unknown() -> None:
    _, r = canon(E29.format(g=75), "szgh")
    assert "E0201" in codes(r)


def test_e002_30_g81_drilling() -> None:
    text = ("M3 S2000 ;\nG90 G99 G81 X300 Y-250 Z-150 R-100 F120 ;\nY-550 ;\nY-750 ;\nX1000 ;\nG98 Y-750 ;\n"
            "G80 G28 G91 X0 Y0 Z0 ;\nM5 ;\n")
    holes = [(300.0, -250.0), (300.0, -550.0), (300.0, -750.0), (1000.0, -750.0), (1000.0, -750.0)]
    want = frame(holes, lambda x, y, ret: [("F", x, y, -150.0), ("R", x, y, ret)], -100.0)
    t, _ = tokens(text)
    assert t[:len(want)] == want


def test_e002_31_g82_dwell_p_in_seconds() -> None:
    text = ("M3 S2000 ;\nG90 G99 G82 X300. Y-250. Z-150. R-100. P1 F120. ;\nY-550. ;\nG98 Y-750. ;\n"
            "G0 X0 Y0 Z0 ;\nM05 ;\n")
    holes = [(300.0, -250.0), (300.0, -550.0), (300.0, -750.0)]
    want = frame(holes, lambda x, y, ret: [("F", x, y, -150.0), ("D", 1.0), ("R", x, y, ret)], -100.0)
    t, _ = tokens(text)
    assert t[:len(want)] == want
    t_ms, _ = tokens(text, cycle_dwell_unit="ms")
    assert ("D", 0.001) in t_ms


def test_e002_32_g83_peck() -> None:
    text = ("M3 S2000 ;\nG90 G99 G83 X300. Y-250. Z-150. R-100. Q15. F120. ;\nY-550.;\nG98 Y-750.;\nG80;\n"
            "M05;\n")

    def hole(x: float, y: float, ret: float) -> list[Token]:
        return [("F", x, y, -115.0), ("R", x, y, -100.0), ("R", x, y, -110.0), ("F", x, y, -130.0),
                ("R", x, y, -100.0), ("R", x, y, -125.0), ("F", x, y, -145.0), ("R", x, y, -100.0),
                ("R", x, y, -140.0), ("F", x, y, -150.0), ("R", x, y, ret)]

    want = frame([(300.0, -250.0), (300.0, -550.0), (300.0, -750.0)], hole, -100.0)
    t, _ = tokens(text)
    assert t[:len(want)] == want


def test_e002_33_g84_dwell_at_bottom_and_at_r() -> None:
    text = ("M3 S100 ;\nG90 G99 G84 X300 Y-250 Z-150 R-120 P300 K5 S100 ;\nY-550. K5;\nG98 Y-750. K5;\n"
            "G80 ;\nM30;\n")

    def hole(x: float, y: float, ret: float, p: float = 300.0) -> list[Token]:
        return [("F", x, y, -150.0), ("D", p), ("CCW",), ("F", x, y, -120.0), ("D", p), ("CW",),
                *([("R", x, y, ret)] if ret == 0.0 else [])]

    holes = [(300.0, -250.0), (300.0, -550.0), (300.0, -750.0)]
    t, diags = tokens(text)
    want = frame(holes, hole, -120.0)
    assert t[:len(want)] == want
    assert "W0417" in diags  # 300 s is implausible
    t, _ = tokens(text, cycle_dwell_unit="ms")
    assert t[:len(want)] == frame(holes, lambda x, y, ret: hole(x, y, ret, 0.3), -120.0)


def test_e002_34_g85_feed_in_feed_out() -> None:
    text = ("M3 S100 ;\nG90 G99 G85 X300. Y-250. Z-150. R-120. F120.\nY-550 ;\nY-750;\nX1000 ;\nG98 Y-750 ;\n"
            "G80 ;\nM05 ;\n")
    holes = [(300.0, -250.0), (300.0, -550.0), (300.0, -750.0), (1000.0, -750.0), (1000.0, -750.0)]

    def hole(x: float, y: float, ret: float) -> list[Token]:
        return [("F", x, y, -150.0), ("F", x, y, -120.0), *([("R", x, y, ret)] if ret == 0.0 else [])]

    t, _ = tokens(text)
    want = frame(holes, hole, -120.0)
    assert t[:len(want)] == want


def test_e002_35_g86_spindle_stop_rapid_out() -> None:
    """Printed with G85 (A-32); run with the G86 the section is about."""
    text = ("M3 S2000 ;\n G90 G99 G86 X300. Y-250. Z-150. R-120. F120.\n Y-550 ;\n G98 Y-750 ;\n G80 ;\n"
            " M05 ;\n")

    def hole(x: float, y: float, ret: float) -> list[Token]:
        return [("F", x, y, -150.0), ("OFF",), ("R", x, y, ret), ("CW",)]

    t, _ = tokens(text)
    want = frame([(300.0, -250.0), (300.0, -550.0), (300.0, -750.0)], hole, -120.0)
    assert t[:len(want)] == want


def test_e002_36_g87_back_boring() -> None:
    """R -100 above Z -150 as printed: the tool goes down to -150 and cuts up to -100 (A-53)."""
    text = ("N10 M3 S500 ;\nN20 G90 G87 X300 Y-250 Z-150 R-100 Q5 P1 F120;\nN30 Y-350 ;\nN40 Y-550 ;\n"
            "N50 X1000 ;\nN60 Y-550 ;\nN70 G98 Y-750 ;\nN80 G80 G28 G91 X0 Y0 Z0 ;\nN90 M5 ;\n")
    holes = [(300.0, -250.0), (300.0, -350.0), (300.0, -550.0), (1000.0, -550.0), (1000.0, -550.0),
             (1000.0, -750.0)]
    want: list[Token] = [("CW",)]
    pos = (0.0, 0.0)
    for x, y in holes:
        if (x, y) != pos:
            want.append(("R", x, y, 0.0))
        want += [("ORIENT",), ("R", x + 5, y, 0.0), ("R", x + 5, y, -150.0), ("R", x, y, -150.0), ("CW",),
                 ("F", x, y, -100.0), ("D", 1.0), ("ORIENT",), ("R", x + 5, y, -100.0), ("R", x + 5, y, 0.0),
                 ("R", x, y, 0.0), ("CW",)]
        pos = (x, y)
    t, diags = tokens(text)
    assert t[:len(want)] == want
    assert "W0418" in diags


def test_e002_37_g89_dwell_feed_out() -> None:
    text = ("M3 S100 ;\nG90 G99 G89 X300. Y-250. Z-150. R-120. P1 F120. ;\nY-550 ;\nX1000 ;\nG98 Y-750 ;\n"
            "G80 G28 G91 X0 Y0 Z0 ;\nM05 ;\n")

    def hole(x: float, y: float, ret: float) -> list[Token]:
        return [("F", x, y, -150.0), ("D", 1.0), ("F", x, y, -120.0), *([("R", x, y, ret)] if ret == 0.0 else [])]

    t, _ = tokens(text)
    want = frame([(300.0, -250.0), (300.0, -550.0), (1000.0, -550.0), (1000.0, -750.0)], hole, -120.0)
    assert t[:len(want)] == want


E38 = """N1 G54 X0 Y0 Z0 ;
N2 G90 G00 Z250.0 T11;
N3 G43 Z0 H11 ;
N4 S30 M3 ;
N5 G99 G81 X400.0 Y-350.0 Z-153.0 R-97.0 F120 ;
N6 Y-550.0 ;
N7 G98 Y-750.0 ;
N8 G99 X1200.0 ;
N9 Y-550.0 ;
N10 G98 Y-350.0 ;
N11 G00 X0 Y0 M5 ;
N12 G49 Z250.0 T15 ;
N13 G43 Z0 H15 ;
N14 S20 M3 ;
N15 G99 G82 X550.0 Y-450.0 Z-130.0 R-97.0 P1 F50 ;
N16 G98 Y-650.0 ;
N17 G99 X1050.0 ;
N18 G98 Y-450.0 ;
N19 G00 X0 Y0 M5 ;
N20 G49 Z250.0 T31 ;
N21 G43 Z0 H31 ;
N22 S10 M3 ;
N23 G85 G99 X800.0 Y-350.0 Z-153.0 R47.0 F150 ;
N24 G91 Y-200.0 ;
N25 Y-200.0 ;
N26 G90 G28 X0 Y0 M5 ;
N27 G49 Z0 G80 ;
N28 M02 ;
"""


def test_e002_38_comprehensive_holes_and_levels() -> None:
    from cncc.ir import Linear

    cmds, r = compile_commands(E38, dialect="szgh")
    feeds = [c for c in cmds if isinstance(c, Linear)]
    by_code: dict[str, list[tuple[float, float, float]]] = {}
    for c in feeds:
        by_code.setdefault(c.origin.code, []).append((c.end[0], c.end[1], c.end[2]))
    assert by_code["G81"] == [(400.0, -350.0, -153.0), (400.0, -550.0, -153.0), (400.0, -750.0, -153.0),
                              (1200.0, -750.0, -153.0), (1200.0, -550.0, -153.0), (1200.0, -350.0, -153.0)]
    assert by_code["G82"] == [(550.0, -450.0, -130.0), (550.0, -650.0, -130.0), (1050.0, -650.0, -130.0),
                              (1050.0, -450.0, -130.0)]
    # G85: feed in to -153 and out to R 47 (above the initial level 0: a warning, not an error)
    assert by_code["G85"] == [(800.0, y, z) for y in (-350.0, -550.0, -750.0) for z in (-153.0, 47.0)]
    assert {c.feed_mm_min for c in feeds if c.origin.code == "G85"} == {150.0}
    assert codes(r).count("W0410") == 1


def test_l_repeats_and_k_is_not_a_repeat() -> None:
    t, _ = tokens("G0 X0 Y0 Z10\nG91 G99 G81 X10 Z-5 R-15 L3 F100\nG80\n")
    assert [tok for tok in t if tok[0] == "F"] == [("F", x, 0.0, -10.0) for x in (10.0, 20.0, 30.0)]


@pytest.mark.parametrize(("p6", "backs_to_r"), [("back_off", False), ("return_r", True)])
def test_szgh_peck_tapping_modes(p6: str, backs_to_r: bool) -> None:
    t, _ = tokens("M3 S100\nG0 X0 Y0 Z0\nG90 G99 G84 X1 Z-20 R-5 Q10 K1\nG80\n", cycle_peck_tap=p6,
                  cycle_tap_clearance_mm=2.0)
    feeds = [float(tok[3]) for tok in t if tok[0] == "F"]  # type: ignore[arg-type]
    assert feeds == ([-15.0, -5.0, -20.0, -5.0] if backs_to_r else [-15.0, -13.0, -20.0, -5.0])


def test_e002_51_g152_bolt_circle_macro_from_the_cycle_library() -> None:
    """ProgramG152 (shipped in cncc/dialects/szgh_cycles) drills 5 holes every 45 degrees."""
    text = "G90 G92 X0 Y0 Z4\nG152 X100 Y50 R10 Z-20.0 F20 I40.0 A0 B45.0 H5\nM30\n"
    t, diags = tokens(text)
    feeds = [tok for tok in t if tok[0] == "F"]
    want = [(140.0, 50.0), (128.284, 78.284), (100.0, 90.0), (71.716, 78.284), (60.0, 50.0)]
    assert len(feeds) == 5
    for (_, x, y, z), (wx, wy) in zip(feeds, want, strict=True):
        assert (x, y, z) == pytest.approx((wx, wy, -20.0), abs=1e-3)
    assert t[-1] == ("R", 60.0, 50.0, 4.0)  # G98: back to the initial level Z4 after the last hole
    assert diags.count("W0410") == 1  # R10 above the initial level, said once
