"""SYNTEC canned-cycle examples E000-42 ... E000-53 (= 900M E004-38 ... E004-49).

Each test compares the whole canon trace of the example, reduced to tokens, with the
sequence the spec (syntec-mill-v8.20.md section 6) derives: ("R", x, y, z) a rapid,
("F", x, y, z) a feed, ("D", s) a dwell, and the spindle events.  The peck clearance d
(Pr4002) is a parameter; the tests set it explicitly.
"""

from __future__ import annotations

import pytest

from tests.helpers import calls, canon, codes

Token = tuple[object, ...]
_SPINDLE = {"START_SPINDLE_CLOCKWISE": "CW", "START_SPINDLE_COUNTERCLOCKWISE": "CCW",
            "STOP_SPINDLE_TURNING": "OFF", "ORIENT_SPINDLE": "ORIENT"}


def tokens(text: str, **options: object) -> list[Token]:
    lines, r = canon(text, dialect_options=options) if options else canon(text)
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
    return out


HEAD = "F1000. S500;\n{m}G90;\nG00 X0. Y0. Z10.;\nG17;\nG90 G99;\n"
TAIL = "G80;\nM05;\nM02;\n"


def program(cycle: str, holes5: bool, m: str = "M03;\n") -> str:
    body = cycle + "\nX15.;\nY15.;\nG98 X5.;\n" + ("X10. Y10. Z-20.;\n" if holes5 else "")
    return HEAD.format(m=m) + body + TAIL


HOLES_G99 = [(5.0, 5.0), (15.0, 5.0), (15.0, 15.0)]


def plan(per_hole: object, holes5: bool, first: str = "CW") -> list[Token]:
    """The example's frame: holes 1-3 G99 (B -10), hole 4 G98, hole 5 G98 with B -20.

    ``per_hole(x, y, bottom, ret)`` gives the moves after the XY positioning.
    """
    out: list[Token] = [(first,), ("R", 0.0, 0.0, 10.0)]
    height = 10.0
    holes = [(x, y, -10.0, -5.0) for x, y in HOLES_G99] + [(5.0, 15.0, -10.0, 10.0)]
    if holes5:
        holes.append((10.0, 10.0, -20.0, 10.0))
    for x, y, bottom, ret in holes:
        out.append(("R", x, y, height))
        if height != -5.0:
            out.append(("R", x, y, -5.0))
        out.extend(per_hole(x, y, bottom, ret))  # type: ignore[operator]
        height = ret
    out.append(("OFF",))
    return out


def test_e000_42_g73_high_speed_peck() -> None:
    d = 0.5

    def hole(x: float, y: float, bottom: float, ret: float) -> list[Token]:
        depths = [-7.0, -9.0, -10.0] if bottom == -10.0 else [-7.0, -9.0, -11.0, -13.0, -15.0, -17.0, -19.0, -20.0]
        out: list[Token] = []
        for b in depths[:-1]:
            out += [("F", x, y, b), ("R", x, y, b + d)]
        return [*out, ("F", x, y, bottom), ("R", x, y, ret)]

    text = program("G73 X5. Y5. Z-10. R-5. Q2.;", True)
    assert tokens(text, cycle_g73_retract_mm=d) == plan(hole, True)


def test_e000_42_feed_length_is_35_plus_15d() -> None:
    d = 0.25
    t = tokens(program("G73 X5. Y5. Z-10. R-5. Q2.;", True), cycle_g73_retract_mm=d)
    length, z = 0.0, 10.0
    for tok in t:
        if tok[0] in ("R", "F"):
            if tok[0] == "F":
                length += abs(float(tok[3]) - z)  # type: ignore[arg-type]
            z = float(tok[3])  # type: ignore[arg-type]
    assert length == pytest.approx(35 + 15 * d)


def test_e000_43_g74_left_hand_tapping() -> None:
    def hole(x: float, y: float, bottom: float, ret: float) -> list[Token]:
        return [("F", x, y, bottom), ("D", 2.0), ("CW",), ("F", x, y, -5.0), ("D", 2.0), ("CCW",),
                *([("R", x, y, ret)] if ret != -5.0 else [])]

    text = program("G74 X5. Y5. Z-10. R-5. P2.;", True, m="M04;\n")
    assert tokens(text) == plan(hole, True, first="CCW")


def test_e000_43_g74_spindle_sync_in_ir() -> None:
    from cncc.api import compile_commands
    from cncc.ir import Linear, SpindleSync

    cmds, r = compile_commands(program("G74 X5. Y5. Z-10. R-5. P2.;", True, m="M04;\n"))
    assert r.ok
    syncs = [c.pitch_mm for c in cmds if isinstance(c, SpindleSync)]
    assert syncs == [2.0, 0.0] * 5  # pitch F/S = 1000/500 mm/rev on, then off, per hole
    inside = False
    for c in cmds:
        if isinstance(c, SpindleSync):
            inside = bool(c.pitch_mm)
        elif isinstance(c, Linear):
            assert inside and c.origin.code == "G74"


def test_e000_44_g76_fine_boring_shift_along_pr4020() -> None:
    def hole(x: float, y: float, bottom: float, ret: float) -> list[Token]:
        return [("F", x, y, bottom), ("D", 5.0), ("ORIENT",), ("R", x + 2, y, bottom), ("R", x + 2, y, ret),
                ("R", x, y, ret), ("CW",)]

    assert tokens(program("G76 X5. Y5. Z-10. R-5. Q2. P5.;", True)) == plan(hole, True)


@pytest.mark.parametrize(("pr4020", "dx", "dy"), [(1, -2.0, 0.0), (2, 0.0, 2.0), (3, 0.0, -2.0)])
def test_e000_44_g76_other_shift_directions(pr4020: int, dx: float, dy: float) -> None:
    t = tokens(program("G76 X5. Y5. Z-10. R-5. Q2. P5.;", True), cycle_shift_direction=pr4020)
    assert t[6:9] == [("ORIENT",), ("R", 5 + dx, 5 + dy, -10.0), ("R", 5 + dx, 5 + dy, -5.0)]


def test_e000_45_g81_drilling_table() -> None:
    expected = [("R", 0.0, 0.0, 10.0),
                ("R", 5.0, 5.0, 10.0), ("R", 5.0, 5.0, -5.0), ("F", 5.0, 5.0, -10.0), ("R", 5.0, 5.0, -5.0),
                ("R", 15.0, 5.0, -5.0), ("F", 15.0, 5.0, -10.0), ("R", 15.0, 5.0, -5.0),
                ("R", 15.0, 15.0, -5.0), ("F", 15.0, 15.0, -10.0), ("R", 15.0, 15.0, -5.0),
                ("R", 5.0, 15.0, -5.0), ("F", 5.0, 15.0, -10.0), ("R", 5.0, 15.0, 10.0),
                ("R", 10.0, 10.0, 10.0), ("R", 10.0, 10.0, -5.0), ("F", 10.0, 10.0, -20.0), ("R", 10.0, 10.0, 10.0)]
    text = HEAD.format(m="") + "G81 X5. Y5. Z-10. R-5.;\nX15.;\nY15.;\nG98 X5.;\nX10. Y10. Z-20.;\nG80;\nM02;\n"
    assert tokens(text) == expected


def test_e000_46_g82_dwell() -> None:
    def hole(x: float, y: float, bottom: float, ret: float) -> list[Token]:
        return [("F", x, y, bottom), ("D", 2.0), ("R", x, y, ret)]

    assert tokens(program("G82 X5. Y5. Z-10. R-5. P2.;", False)) == plan(hole, False)


def test_e000_47_g83_peck() -> None:
    d = 0.5

    def hole(x: float, y: float, bottom: float, ret: float) -> list[Token]:
        return [("F", x, y, -8.0), ("R", x, y, -5.0), ("R", x, y, -8.0 + d), ("F", x, y, -10.0), ("R", x, y, ret)]

    assert tokens(program("G83 X5. Y5. Z-10. R-5. Q3.;", False), cycle_g83_clearance_mm=d) == plan(hole, False)


def test_e000_48_g84_tapping_type_1() -> None:
    def hole(x: float, y: float, bottom: float, ret: float) -> list[Token]:
        return [("F", x, y, bottom), ("CCW",), ("F", x, y, -5.0), ("CW",),
                *([("R", x, y, ret)] if ret != -5.0 else [])]

    assert tokens(program("G84 X5. Y5. Z-10. R-5.;", False)) == plan(hole, False)


def test_g84_type_3_general_peck_tapping() -> None:
    def hole(x: float, y: float, bottom: float, ret: float) -> list[Token]:
        out: list[Token] = []
        for b in (-8.0, -10.0):
            out += [("F", x, y, b), ("CCW",), ("F", x, y, -5.0), ("CW",)]
        return out + ([("R", x, y, ret)] if ret != -5.0 else [])

    assert tokens(program("G84 X5. Y5. Z-10. R-5. Q3.;", False)) == plan(hole, False)


def test_g84_type_2_high_speed_peck_tapping_backs_off_d() -> None:
    d = 1.0

    def hole(x: float, y: float, bottom: float, ret: float) -> list[Token]:
        return [("F", x, y, -8.0), ("CCW",), ("F", x, y, -8.0 + d), ("CW",),
                ("F", x, y, -10.0), ("CCW",), ("F", x, y, -5.0), ("CW",),
                *([("R", x, y, ret)] if ret != -5.0 else [])]

    t = tokens(program("G84 X5. Y5. Z-10. R-5. Q3.;", False), cycle_peck_tap="back_off", cycle_tap_clearance_mm=d)
    assert t == plan(hole, False)


def test_e000_49_g85_feed_out() -> None:
    def hole(x: float, y: float, bottom: float, ret: float) -> list[Token]:
        return [("F", x, y, bottom), ("F", x, y, -5.0), *([("R", x, y, ret)] if ret != -5.0 else [])]

    assert tokens(program("G85 X5. Y5. Z-10. R-5.;", False)) == plan(hole, False)


def test_e000_50_g86_spindle_stop_rapid_out() -> None:
    def hole(x: float, y: float, bottom: float, ret: float) -> list[Token]:
        return [("F", x, y, bottom), ("OFF",), ("R", x, y, ret), ("CW",)]

    assert tokens(program("G86 X5. Y5. Z-10. R-5.;", False)) == plan(hole, False)


def test_e000_51_g87_back_boring_table() -> None:
    text = (HEAD.format(m="") + "M03;\nG87 X5. Y5. Z10. R-30. Q5. P4.;\nX15.;\nY15.;\n" + TAIL)
    expected: list[Token] = [("R", 0.0, 0.0, 10.0), ("CW",)]
    for x, y in HOLES_G99:
        expected += [("R", x, y, 10.0), ("ORIENT",), ("R", x - 5, y, 10.0), ("R", x - 5, y, -30.0),
                     ("R", x, y, -30.0), ("CW",), ("F", x, y, 10.0), ("D", 4.0), ("ORIENT",),
                     ("R", x - 5, y, 10.0), ("R", x, y, 10.0), ("CW",)]
    assert tokens(text) == [*expected, ("OFF",)]


def test_e000_52_g88_manual_retract() -> None:
    from cncc.api import compile_commands
    from cncc.ir import Wait

    def hole(x: float, y: float, bottom: float, ret: float) -> list[Token]:
        return [("F", x, y, bottom), ("D", 3.0), ("OFF",), ("F", x, y, -5.0),
                *([("R", x, y, ret)] if ret != -5.0 else []), ("CW",)]

    text = program("G88 X5. Y5. Z-10. R-5. P3.;", False)
    assert tokens(text) == plan(hole, False)
    cmds, _ = compile_commands(text)
    assert sum(isinstance(c, Wait) for c in cmds) == 4  # one operator stop per hole


def test_e000_53_g89_dwell_feed_out() -> None:
    def hole(x: float, y: float, bottom: float, ret: float) -> list[Token]:
        return [("F", x, y, bottom), ("D", 2.5), ("F", x, y, -5.0), *([("R", x, y, ret)] if ret != -5.0 else [])]

    assert tokens(program("G89 X5. Y5. Z-10. R-5. P2.5;", False)) == plan(hole, False)


def test_dwell_without_point_is_ms() -> None:
    t = tokens(program("G82 X5. Y5. Z-10. R-5. P2500;", False))
    assert ("D", 2.5) in t


def test_r_and_z_in_g91() -> None:
    """G91: R from the initial level (10 - 15 = -5), Z from R (-5 - 5 = -10), XY incremental."""
    text = "F1000. S500;\nM03;\nG00 X0. Y0. Z10.;\nG91 G99 G81 X5. Y5. Z-5. R-15.;\nX10.;\nG80;\nM02;\n"
    assert tokens(text) == [("CW",), ("R", 0.0, 0.0, 10.0), ("R", 5.0, 5.0, 10.0), ("R", 5.0, 5.0, -5.0),
                            ("F", 5.0, 5.0, -10.0), ("R", 5.0, 5.0, -5.0), ("R", 15.0, 5.0, -5.0),
                            ("F", 15.0, 5.0, -10.0), ("R", 15.0, 5.0, -5.0)]


def test_g91_z_from_initial_option() -> None:
    text = "F1000.;\nG00 X0. Y0. Z10.;\nG91 G98 G81 X5. Z-15. R-5.;\nG80;\nM02;\n"
    assert ("F", 5.0, 0.0, -10.0) in tokens(text)  # R 5, bottom R - 15
    assert ("F", 5.0, 0.0, -5.0) in tokens(text, cycle_z_incremental_from="initial")


def test_k_repeats_in_g91_and_k0_stores_only() -> None:
    text = ("F1000.;\nG00 X0. Y0. Z10.;\nG91 G99 G81 X10. Z-5. R-15. K0;\nX10. K3;\nG80;\nM02;\n")
    t = tokens(text)
    feeds = [tok for tok in t if tok[0] == "F"]
    assert feeds == [("F", 10.0, 0.0, -10.0), ("F", 20.0, 0.0, -10.0), ("F", 30.0, 0.0, -10.0)]


def test_block_without_axis_words_does_not_drill_nor_store() -> None:
    text = "F1000.;\nG00 X0. Y0. Z10.;\nG99 G81 X5. Z-10. R-5.;\nR-2.;\nX15.;\nG80;\nM02;\n"
    _, r = canon(text)
    assert "W0416" not in codes(r)  # no cycle code in the R-only block: silently not a drilling block
    t = tokens(text)
    assert ("R", 15.0, 0.0, -5.0) in t and ("F", 15.0, 0.0, -10.0) in t  # R stayed -5


def test_group_01_cancels_the_cycle() -> None:
    text = "F1000.;\nG00 X0. Y0. Z10.;\nG99 G81 X5. Z-10. R-5.;\nG00 X20.;\nX30.;\nM02;\n"
    t = tokens(text)
    assert t[-2:] == [("R", 20.0, 0.0, -5.0), ("R", 30.0, 0.0, -5.0)]


def test_g18_drills_along_y() -> None:
    text = "F1000.;\nG00 X0. Y10. Z0.;\nG18 G99 G81 X5. Z5. Y-10. R-5.;\nG80;\nM02;\n"
    assert tokens(text)[-4:] == [("R", 5.0, 10.0, 5.0), ("R", 5.0, -5.0, 5.0), ("F", 5.0, -10.0, 5.0),
                                 ("R", 5.0, -5.0, 5.0)]


def test_g95_tapping_pitch_is_f() -> None:
    from cncc.api import compile_commands
    from cncc.ir import Cycle, Linear, SpindleSync

    cmds, r = compile_commands("S600 M03;\nG00 X0 Y0 Z10.;\nG95 G84 X5. Z-10. R-5. F1.25;\nG80;\nM02;\n")
    assert r.ok
    assert not any(isinstance(c, Cycle) for c in cmds)  # expanded by the pass

    assert [c.pitch_mm for c in cmds if isinstance(c, SpindleSync)] == [1.25, 0.0]
    assert [c.feed_mm_min for c in cmds if isinstance(c, Linear)] == pytest.approx([750.0, 750.0])  # 600 rpm x 1.25
