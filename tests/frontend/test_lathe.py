"""LinuxCNC's lathe codes without the oracle: G7/G8, G70-G72, G76 (tests/oracle has the rs274 comparisons).

Expected values come from LinuxCNC's G-code manual (11.5.10 G7, 11.5.38-39 G70-G72, 11.5.42 G76) or are
computed here independently of cncc's code.
"""

from __future__ import annotations

import itertools
import re

import pytest

from tests.helpers import calls, canon, codes, compile_text

PROFILE = "o100 sub\nG1 X2 Z0\nX4 Z-5\nX8 Z-12\no100 endsub\n"


def _moves(text: str) -> list[tuple[str, list[float]]]:
    lines, r = canon(text, "linuxcnc")
    assert r.ok, [d.message for d in r.sink]
    return calls(lines, "STRAIGHT_TRAVERSE", "STRAIGHT_FEED", "ARC_FEED")


# ---- G7 / G8 -------------------------------------------------------------------------------------
def test_g7_x_words_are_diameters() -> None:
    # Manual: "X1 would move the cutter to 0.500 from the center" in diameter mode; G8 is the default.
    got = _moves("G21 G18\nG0 X10 Z1\nG7\nG0 X10\nG91 G0 X4\nG90 G8 G0 X3\nM2\n")
    assert [m[1][0] for m in got] == [10.0, 5.0, 7.0, 3.0]


def test_g7_in_the_block_applies_to_its_own_x() -> None:
    got = _moves("G21 G18\nG7 G0 X10 Z1\nG8 G0 X10\nM2\n")
    assert [m[1][0] for m in got] == [5.0, 10.0]


def test_g7_arc_centre_stays_a_radius() -> None:
    # A half circle from X5 (diameter 10) to X5 about the centre 2 below in Z: I/K are not halved.
    got = _moves("G21 G18 F100\nG7 G0 X10 Z0\nG2 X10 Z-4 I0 K-2\nM2\n")
    name, args = got[-1]
    assert name == "ARC_FEED" and args[0] == -4.0 and args[1] == 5.0


# ---- G70 / G71 / G72 ----------------------------------------------------------------------------------
def _profile_x(z: float) -> float:
    """PROFILE (X2 Z0, X4 Z-5, X8 Z-12) as x of z, computed here."""
    if z >= -5:
        return 2 + (0 - z) * 2 / 5
    return 4 + (-5 - z) * 4 / 7


def test_g71_never_cuts_past_the_profile_and_moves_only_x_z() -> None:
    # Safety: every end point of every move lies on or outside the profile (outside turning, the stock at
    # larger X), and the cycle moves neither Y nor a rotary axis.
    for cycle in ("G71 Q100 D0.5 I1", "G71 Q100 I0.7 R0.2", "G71.1 Q100 D0.2", "G71.2 Q100"):
        got = _moves("G21 G18 F100\n" + PROFILE + "G0 X10 Y3 Z2 A5\n" + cycle + "\nM2\n")
        assert len(got) > 5, cycle
        for name, args in got:
            x, y, z, a = (args[0], args[1], args[2], args[3]) if name != "ARC_FEED" else (args[1], 3.0, args[0], 5.0)
            assert y == 3.0 and a == 5.0, (cycle, name, args)
            if -12 <= z <= 0:
                assert x >= _profile_x(z) - 1e-4, (cycle, name, args)


def test_g71_levels_step_by_i_from_the_start_x() -> None:
    # Manual: I is the cutting increment; the passes run along Z at X = start - n I, above the profile.
    got = _moves("G21 G18 F100\n" + PROFILE + "G0 X12 Z3\nG71 Q100 I1.5\nM2\n")
    # a feed along Z right after a rapid to its X
    passes = [b[1][0] for a, b in itertools.pairwise(got)
              if a[0] == "STRAIGHT_TRAVERSE" and b[0] == "STRAIGHT_FEED" and a[1][0] == b[1][0]]
    assert passes == [12.0, 10.5, 9.0, 7.5, 6.0, 4.5, 3.0]


def test_g70_pass_distances_follow_the_manual() -> None:
    # Manual: pass n is (n-1)*(D-E)/P+E from the profile, towards the start point; the last pass is at E.
    # The first profile line X2 Z0 -> X4 Z-5 has the unit normal (5, 2)/sqrt(29) towards the start point.
    got = _moves("G21 G18 F100\n" + PROFILE + "G0 X12 Z3\nG70 Q100 D1 E0.2 P3\nM2\n")
    n = (5 / 29 ** 0.5, 2 / 29 ** 0.5)
    starts = [args for name, args in got if name == "STRAIGHT_TRAVERSE" and args[0] < 3]
    for args, d in zip(starts, (2 * 0.8 / 3 + 0.2, 0.8 / 3 + 0.2, 0.2), strict=True):
        assert args[0] == pytest.approx(2 + d * n[0], abs=1e-4) and args[2] == pytest.approx(d * n[1], abs=1e-4)
    assert got[-1][0] == "STRAIGHT_FEED" and got[-1][1][0] == pytest.approx(8 + 0.2 * 7 / 65 ** 0.5, abs=1e-4)


def test_g70_follows_the_profile() -> None:
    # No D/E: one pass along the profile itself, ending at its end.
    got = _moves("G21 G18 F100\n" + PROFILE + "G0 X12 Z3\nG70 Q100\nM2\n")
    assert [args[:3:2] for _, args in got[-3:]] == [[2.0, 0.0], [4.0, -5.0], [8.0, -12.0]]


@pytest.mark.parametrize(("text", "code", "line"), [
    ("G21 G18 F100\nG0 X10 Z5\nG71 D0.5\nM2\n", "E0481", 3),  # no Q
    ("G21 G18 F100\n" + PROFILE + "G0 X10 Z2\nG71 Q100 I0\nM2\n", "E0481", 8),  # I must be above zero
    ("G21 G17 F100\n" + PROFILE + "G0 X10 Z2\nG71 Q100\nM2\n", "E0482", 8),  # not G18
    ("G21 G18 F100\nG0 X10 Z5\nG71 Q999\nM2\n", "E0351", 3),  # no subroutine o999
    ("G21 G18 F100\no100 sub\nG1 X2 Z0\nX4 Z-5\nX6 Z-2\no100 endsub\nG0 X10 Z2\nG71 Q100\nM2\n", "E0480", 8),
])
def test_g7x_bad_input_is_a_positioned_error(text: str, code: str, line: int) -> None:
    r = compile_text(text, dialect="linuxcnc", emit="canon")
    assert not r.ok and code in codes(r)
    d = next(d for d in r.sink if d.code == code)
    assert text[:d.span.start].count("\n") + 1 == line


POCKET = "o100 sub\nG1 X2 Z0\nX6 Z-4\nX3 Z-7\nX8 Z-10\no100 endsub\n"


def test_g71_1_bridges_the_pocket_at_the_peak_height() -> None:
    # Manual: G7x.1 does not cut pockets.  Its last pass crosses the pocket at the peak's height X6, from
    # the peak Z-4 to where X3 Z-7 -> X8 Z-10 climbs back to X6: Z = -7 - 3 * (6 - 3) / 5 = -8.8.
    got = _moves("G21 G18 F100\n" + POCKET + "G0 X10 Z2\nG71.1 Q100 I1\nM2\n")
    feeds = [args[:3:2] for name, args in got if name == "STRAIGHT_FEED"]
    k = len(feeds) - 1 - feeds[::-1].index([6.0, -4.0])  # the last pass reaches the peak
    assert feeds[k + 1] == pytest.approx([6.0, -8.8], abs=1e-4)
    assert all(x >= 6 - 1e-9 for x, z in feeds[k:] if -8.8 < z < -4)  # nothing goes into the pocket


def test_g71_2_cuts_the_pocket_levels_only() -> None:
    # Manual: G7x.2 only cuts the pockets: no feed above the peak X6 before the profile climbs past it
    # again (Z-8.8, see above).
    got = _moves("G21 G18 F100\n" + POCKET + "G0 X10 Z2\nG71.2 Q100 I1\nM2\n")
    assert not [args for name, args in got if name == "STRAIGHT_FEED" and args[0] > 6 + 1e-9 and args[2] > -8.8]
    levels = {args[0] for a, (name, args) in itertools.pairwise(got)
              if name == "STRAIGHT_FEED" and a[1][0] == args[0] and args[2] < -4}
    assert {4.0, 5.0, 6.0} <= levels


def test_g71_short_pass_retracts_meet() -> None:
    # A pass shorter than 2R: the 45-degree retract from its end and the one back to its entry meet at the
    # apex of the triangle over the pass (independent computation: half the pass length up and along).
    got = _moves("G21 G18 F100\n" + PROFILE + "G0 X2.6 Z0.3\nG71 Q100 I0.4 R5\nM2\n")
    feeds = [k for k, (name, _) in enumerate(got) if name == "STRAIGHT_FEED"]
    k = feeds[1]
    x, z_end = got[k][1][0], got[k][1][2]
    z_in = got[k - 1][1][2]
    half = (z_in - z_end) / 2
    assert got[k + 1][1][:3:2] == pytest.approx([x + half, z_end + half])
    assert got[k + 2][1][:3:2] == pytest.approx([x + half, z_in - half])


def test_g71_diameter_mode_is_the_radius_program() -> None:
    dia = "G21 G18 F100\nG7\no100 sub\nG1 X4 Z0\nX8 Z-5\nX16 Z-12\no100 endsub\nG0 X24 Z3\nG71 Q100 D0.5 I1\nM2\n"
    rad = "G21 G18 F100\n" + PROFILE + "G0 X12 Z3\nG71 Q100 D0.5 I1\nM2\n"
    assert _moves(dia) == _moves(rad)


def test_g7x_moves_are_the_same_on_the_fast_path(monkeypatch: pytest.MonkeyPatch) -> None:
    from cncc.frontend.linuxcnc import executor

    text = "G21 G18 F100\n" + POCKET + "G0 X10 Z2\nG71 Q100 D0.2 I0.7\nG0 X12\nG1 Z3\nM2\n"
    monkeypatch.setattr(executor, "FAST_MOVES", True)
    fast = _moves(text)
    monkeypatch.setattr(executor, "FAST_MOVES", False)
    assert _moves(text) == fast


def test_g70_refused_when_its_return_rapid_would_clip_the_part() -> None:
    # A convex arc at the end of a facing profile: the straight rapid from its end back to the start point
    # passes under the arc's bulge.  cncc refuses the cycle (E0463) and runs none of its moves.
    text = ("G21 G18 F150\no100 sub\nG0 X-3.1004 Z2.772\nG1 X-6.3252 Z3.7502\nG2 X-10.4226 Z4.6556 R3.2683\n"
            "o100 endsub\nG0 X-1.1318 Z5.669\nG70 Q100 D0.3125 E0.0968 P3\nM2\n")
    r = compile_text(text, dialect="linuxcnc", emit="canon")
    assert not r.ok and "E0463" in codes(r)
    lines, _ = canon(text, "linuxcnc")
    assert len(calls(lines, "STRAIGHT_TRAVERSE", "STRAIGHT_FEED", "ARC_FEED")) == 1  # the G0 before it


def test_g71_translates_to_plain_moves() -> None:
    r = compile_text("G21 G18 F100\n" + PROFILE + "G0 X12 Z3\nG71 Q100 I2\nM2\n", dialect="linuxcnc",
                     emit="gcode", target="fanuc")
    assert r.ok, [d.message for d in r.sink]
    assert "G71" not in r.output and re.search(r"G0?1\b", r.output)


def test_g7x_word_it_does_not_read() -> None:
    # rs274's check_items: G70 reads D E P Q, G71/G72 D I Q R.
    for cycle, word in (("G70", "I1"), ("G71", "E1"), ("G71", "P2"), ("G72", "K1")):
        r = compile_text("G21 G18 F100\n" + PROFILE + f"G0 X10 Z2\n{cycle} Q100 {word}\nM2\n", dialect="linuxcnc")
        assert "E0481" in codes(r), (cycle, word)


# ---- G76 ------------------------------------------------------------------------------------------------
def test_g76_pass_depths_follow_the_manual() -> None:
    # Manual: the first cut is J beyond the thread peak, the last K; with R1 the depth grows by J a pass
    # (depth n = |I| + J * n ** (1/R)), then H spring passes at full depth.  External thread (I < 0).
    i, j, k, h = -0.5, 0.1, 0.45, 1
    got = _moves(f"G21 G18 S100 M3\nG0 X10 Z0\nG76 P1 Z-10 I{i} J{j} K{k} H{h}\nM2\n")
    cuts = [a[0] for n, a in got if n == "STRAIGHT_FEED"]
    want, depth, n = [], abs(i) + j, 1
    while depth < abs(i) + k:
        want.append(10 - depth)
        n += 1
        depth = abs(i) + j * n
    want += [10 - abs(i) - k] * (h + 1)
    assert cuts == pytest.approx(want, abs=1e-4)


def test_g76_is_synchronised_with_the_spindle() -> None:
    lines, r = canon("G21 G18 S100 M3\nG0 X10 Z0\nG76 P1.5 Z-10 I-0.5 J0.1 K0.3\nM2\n", "linuxcnc")
    text = "\n".join(lines)
    assert r.ok
    assert text.count("START_SPEED_FEED_SYNC(1.500000,0)") == text.count("STOP_SPEED_FEED_SYNCH()") > 0
    assert text.count("DISABLE_FEED_OVERRIDE()") == text.count("ENABLE_FEED_OVERRIDE()")


@pytest.mark.parametrize(("words", "code"), [("P1 Z-5 I-1 J0.5 K0.5", "E0481"), ("Z-5 I-1 J0.1 K0.5", "E0481"),
                                             ("P1 Z-5 I0 J0.1 K0.5", "E0481")])
def test_g76_bad_words(words: str, code: str) -> None:
    r = compile_text(f"G21 G18 S100 M3\nG0 X10 Z2\nG76 {words}\nM2\n", dialect="linuxcnc", emit="canon")
    assert not r.ok and code in codes(r)


def test_g76_needs_a_turning_spindle() -> None:
    r = compile_text("G21 G18\nG0 X10 Z2\nG76 P1 Z-5 I-1 J0.1 K0.5\nM2\n", dialect="linuxcnc", emit="canon")
    assert not r.ok and "E0250" in codes(r)


# ---- translation -------------------------------------------------------------------------------------------
@pytest.mark.parametrize("target", ["fanuc", "grbl", "haas", "linuxcnc"])
def test_lathe_cycles_translate_to_plain_moves(target: str) -> None:
    text = "G21 G18 F100\nG0 X10 Z2\nS300 M3\nG76 P1.5 Z-10 I-1 J0.2 K0.9\nG0 X20\nM2\n"
    r = compile_text(text, dialect="linuxcnc", emit="gcode", target=target)
    assert r.ok, [d.message for d in r.sink]
    out = r.output
    assert not re.search(r"\bG7[0-6]\b", out)  # no cycle the target would read otherwise
    assert not re.search(r"\b[YABC]-?[\d.]", out)  # only X and Z move, as in the program
    canon_x = {round(a[0], 3) for _, a in _moves(text)}
    written_x = {round(float(m), 3) for m in re.findall(r"\bX(-?[\d.]+)", out)}
    assert written_x <= canon_x
