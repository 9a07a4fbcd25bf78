"""LinuxCNC: splines, G33/G33.1, canned-cycle retracts, cutter-comp errors, canon wording.

Every expected trace below was written from LinuxCNC's G-code documentation and then
compared, line by line, with the output of LinuxCNC 2.9's stand-alone interpreter
(``rs274 -g``, Debian 12 package linuxcnc-uspace 2.9.0~pre1) on the same program; the
comments say what each line rests on.  Geometry that rs274 does not print (the
biarcs of a spline, made by LinuxCNC's motion controller) is checked against the curve
itself: end points, tangents and distance to the exact spline.
"""

from __future__ import annotations

import itertools
import math

import pytest

from cncc.frontend import nurbs
from tests.helpers import calls, canon, compile_commands

# The snippets below are not whole programs: no M2/M30 at the end (E0326 is tested on its own).
SNIPPET = {"dialect_options": {"program_end_required": False}}

P = " N..... "
END_LINES = ["SET_G5X_OFFSET(1, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)", "SET_XY_ROTATION(0.0000)",
             "SET_FEED_MODE(0, 0)", "SET_FEED_RATE(0.0000)", "STOP_SPINDLE_TURNING(0)", "SET_SPINDLE_MODE(0 0.0000)",
             "PROGRAM_END()"]


def trace(text: str) -> list[str]:
    """Calls after the six start-up calls, without the two ON_RESET() rs274 ends with."""
    lines, r = canon(text, "linuxcnc", **SNIPPET)
    assert not r.sink.has_errors, [d.message for d in r.sink]
    assert lines[-2:] == [P + "ON_RESET()"] * 2
    return [ln.removeprefix(P) for ln in lines[:-2]]


def first_error(text: str) -> str:
    _, r = canon(text, "linuxcnc", **SNIPPET)
    msgs = [d.message for d in r.sink if d.severity.label == "error"]
    assert msgs, "expected an error"
    return msgs[0]


# ---- start-up, end, spindle, tool, feed and offset calls --------------------------------------------
def test_program_end_resets() -> None:
    # M2: G54 origin and rotation, feed mode per minute with rate 0, spindle stopped, CSS off, then
    # PROGRAM_END (LinuxCNC's convert_stop).  rs274 then prints ON_RESET() twice.
    assert trace("G0 X1\nM2\n") == ["STRAIGHT_TRAVERSE(1.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)", *END_LINES]


def test_m30_coolant_and_plane_resets() -> None:
    # M30 adds PALLET_SHUTTLE(); a plane other than XY and coolant in force are reset too.  Within
    # a block, coolant (step 8 of LinuxCNC's order of execution) comes before the plane (step 11).
    # M30 turns off only the coolant that is on (rs274 2.9 prints FLOOD_OFF alone here; M9 prints both).
    t = trace("G18 M8\nM30\n")
    assert t == ["FLOOD_ON()", "SELECT_PLANE(CANON_PLANE_XZ)",
                 "SET_G5X_OFFSET(1, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)", "SET_XY_ROTATION(0.0000)",
                 "SELECT_PLANE(CANON_PLANE_XY)", "SET_FEED_MODE(0, 0)", "SET_FEED_RATE(0.0000)",
                 "STOP_SPINDLE_TURNING(0)", "SET_SPINDLE_MODE(0 0.0000)", "FLOOD_OFF()",
                 "PALLET_SHUTTLE()", "PROGRAM_END()"]


def test_spindle_tool_and_coolant_calls_carry_spindle_numbers() -> None:
    # LinuxCNC 2.8+ canon calls name the spindle (0); M6 is START_CHANGE, a spindle stop, CHANGE_TOOL;
    # M9 turns mist off before flood.
    t = trace("T2 M6\nS1000 M3\nM4\nM5\nM8\nM9\n")
    assert t == ["SELECT_TOOL(2)", "START_CHANGE()", "STOP_SPINDLE_TURNING(0)", "CHANGE_TOOL(2)",
                 "SET_SPINDLE_SPEED(0, 1000.0000)", "START_SPINDLE_CLOCKWISE(0)", "START_SPINDLE_COUNTERCLOCKWISE(0)",
                 "STOP_SPINDLE_TURNING(0)", "FLOOD_ON()", "MIST_OFF()", "FLOOD_OFF()"]


def test_g10_l1_tool_table_entry_in_inches_and_g43() -> None:
    # rs274 keeps its tool table in inches: Z 12.5 mm is 0.4921 in.  G43 H3 reports the offset in
    # program units, in three groups of three (x y z, a b c, u v w).
    t = trace("G10 L1 P3 Z12.5 R2\nG43 H3\n")
    assert t == ["SET_TOOL_TABLE_ENTRY(3, 3, 0.0000 0.0000 0.4921 0.0000 0.0000 0.0000 0.0000 0.0000 0.0000, "
                 "0.0000, 0.0000, 0)",
                 "USE_TOOL_LENGTH_OFFSET(0.0000 0.0000 12.5000, 0.0000 0.0000 0.0000, 0.0000 0.0000 0.0000)"]


def test_tool_length_offset_moves_the_program_z_not_the_tool() -> None:
    # G43 does not move the machine: the next move without Z keeps the machine Z, so its program
    # Z is 0 - 20 = -20 (rs274: STRAIGHT_FEED(10.0000, 0.0000, -20.0000 ...)); G49 gives 0 back.
    t = trace("G10 L1 P1 Z20\nG43 H1\nG1 X10 F100\nG49\nG1 X0\n")
    feeds = [ln for ln in t if ln.startswith("STRAIGHT_FEED")]
    assert feeds == ["STRAIGHT_FEED(10.0000, 0.0000, -20.0000, 0.0000, 0.0000, 0.0000)",
                     "STRAIGHT_FEED(0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)"]


def test_repeated_modes_and_interpreter_comments() -> None:
    # G17 and G21 are reported every time; G91 only when the distance mode changes; G98/G99 and G80
    # every time; G54 when already in force says it keeps the system; G55 reports the G92 offset
    # and the rotation after the origin.  G94 also sets the feed rate to 0.
    t = trace("G17\nG21\nG91\nG91\nG80\nG98\nG54\nG55\nG94\n")
    assert t == ["SELECT_PLANE(CANON_PLANE_XY)", "USE_LENGTH_UNITS(CANON_UNITS_MM)",
                 'COMMENT("interpreter: distance mode changed to incremental")',
                 'COMMENT("interpreter: motion mode set to none")',
                 'COMMENT("interpreter: retract mode set to old_z")',
                 'COMMENT("interpreter: continuing to use same coordinate system")',
                 "SET_G5X_OFFSET(2, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)",
                 "SET_G92_OFFSET(0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)", "SET_XY_ROTATION(0.0000)",
                 'COMMENT("interpreter: feed mode set to units per minute")', "SET_FEED_MODE(0, 0)",
                 "SET_FEED_RATE(0.0000)"]


def test_g94_clears_the_feed_rate() -> None:
    # After G94 the feed rate is 0, so a G1 without F is an error again.
    assert first_error("G1 X1 F100\nG94\nG1 X2\n").startswith("Cannot do g1 with zero feed rate")


def test_inch_feed_rate_in_program_units() -> None:
    # SET_FEED_RATE is in program units per minute (rs274: F10 in G20 prints 10.0000).
    assert "SET_FEED_RATE(10.0000)" in trace("G20 F10\n")


def test_syntec_default_wording_unchanged() -> None:
    # The other dialects keep cncc's own wording of these calls (their golden traces depend on it).
    lines, _ = canon("T2 M06\nS1000 M03\nM05\n", "syntec")
    assert [ln.removeprefix(P) for ln in lines] == ["SELECT_TOOL(2)", "CHANGE_TOOL()", "SET_SPINDLE_SPEED(1000.0000)",
                                                   "START_SPINDLE_CLOCKWISE()", "STOP_SPINDLE_TURNING()"]


# ---- G33 / G33.1 -------------------------------------------------------------------------------
def test_g33_spindle_synchronised_moves() -> None:
    # START_SPEED_FEED_SYNC(K, 0) (rs274 prints the name without the final H and K with %f), the
    # move, STOP_SPEED_FEED_SYNCH(); K in program units, negative K passed through.
    t = trace("S500 M3\nG0 X1 Y2 Z3\nG33 Z-10 K1.5\nG33 X2 Z-12 K-2\n")
    assert t[3:] == ["START_SPEED_FEED_SYNC(1.500000,0)",
                     "STRAIGHT_FEED(1.0000, 2.0000, -10.0000, 0.0000, 0.0000, 0.0000)", "STOP_SPEED_FEED_SYNCH()",
                     "START_SPEED_FEED_SYNC(-2.000000,0)",
                     "STRAIGHT_FEED(2.0000, 2.0000, -12.0000, 0.0000, 0.0000, 0.0000)", "STOP_SPEED_FEED_SYNCH()"]


def test_g33_ir_is_a_synchronised_linear_move() -> None:
    from cncc.ir import Linear, SpindleSync

    cmds, r = compile_commands("S500 M3\nG33 Z-10 K1.5\n", dialect="linuxcnc", **SNIPPET)
    assert r.ok
    sync = [c for c in cmds if isinstance(c, SpindleSync | Linear)]
    assert [(type(c).__name__, getattr(c, "pitch_mm", None)) for c in sync] == [
        ("SpindleSync", 1.5), ("Linear", None), ("SpindleSync", 0.0)]
    lin = sync[1]
    assert isinstance(lin, Linear) and lin.feed_mm_min == pytest.approx(500 * 1.5)  # rpm x pitch


def test_g33_1_rigid_tap_returns_to_the_start() -> None:
    # RIGID_TAP(x, y, z) between the synchronisation calls; the tool ends where it started, so the
    # next G1 Z1 starts from X1 Y1 (rs274: STRAIGHT_FEED(1.0000, 1.0000, 1.0000 ...)).
    t = trace("S100 M3\nG0 X1 Y1 Z0\nG33.1 X3 Y3 Z-6 K1\nG1 Z1 F10\n")
    assert t[3:] == ["START_SPEED_FEED_SYNC(1.000000,0)", "RIGID_TAP(3.0000, 3.0000, -6.0000)",
                     "STOP_SPEED_FEED_SYNCH()", "SET_FEED_RATE(10.0000)",
                     "STRAIGHT_FEED(1.0000, 1.0000, 1.0000, 0.0000, 0.0000, 0.0000)"]


def test_g33_1_ir_feeds_in_reverses_and_feeds_out() -> None:
    from cncc.ir import Linear, Spindle, SpindleState

    cmds, _ = compile_commands("S100 M3\nG33.1 Z-5 K1.25\n", dialect="linuxcnc", **SNIPPET)
    moves = [c for c in cmds if isinstance(c, Linear)]
    assert [m.end[2] for m in moves] == [-5.0, 0.0]
    assert [c.state for c in cmds if isinstance(c, Spindle)] == [SpindleState.CW, SpindleState.CCW, SpindleState.CW]


@pytest.mark.parametrize("prog, text", [
    ("S100 M3\nG33.1 Z-5\n", "K word missing with g33/g33.1"),
    ("G33 Z-5 K1\n", "Spindle not turning in G33"),
    ("S100 M3\nM5\nG33.1 Z-2 K1\n", "Spindle not turning in G33.1"),
    ("S100 M3 G33 Z-1 K1 F10\n", "F word used with a g33/g33.1"),
])
def test_g33_errors(prog: str, text: str) -> None:
    assert first_error(prog).startswith(text)


# ---- G5 / G5.1 / G5.2 ------------------------------------------------------------------------------
def test_splines_print_one_nurbs_feed_each() -> None:
    # rs274 prints NURBS_FEED(number of control points, ...): 4 for G5, 3 for G5.1, the start
    # point plus the listed points for G5.2 ... G5.3; the tool ends at the curve's end.
    t = trace("F100\nG5 I0 J3 P0 Q-3 X1 Y1\nG5 P0 Q-3 X2 Y2\nG1 X3\nG5.1 I1 J1 X5 Y2\n"
              "G5.2 X0 Y1 P1 L3\nX2 Y2 P1\nX2 Y0 P1\nX0 Y0 P2\nG5.3\nG0 X9\n")
    assert t[1:] == ["NURBS_FEED(4, ...)", "NURBS_FEED(4, ...)",
                     "STRAIGHT_FEED(3.0000, 2.0000, 0.0000, 0.0000, 0.0000, 0.0000)", "NURBS_FEED(3, ...)",
                     "NURBS_FEED(5, ...)", "STRAIGHT_TRAVERSE(9.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)"]


def _cubic(t: float, p: list[tuple[float, float]]) -> tuple[float, float]:
    b = [(1 - t) ** 3, 3 * t * (1 - t) ** 2, 3 * t * t * (1 - t), t ** 3]
    return sum(b[i] * p[i][0] for i in range(4)), sum(b[i] * p[i][1] for i in range(4))


def test_g5_biarcs_follow_the_bezier() -> None:
    # A cubic B-spline with 4 control points and LinuxCNC's knots (0 0 0 0 1 1 1 1) is the Bezier
    # curve of those points.  The 16 biarcs (4 x 4 control points) must join end to end, end on
    # it, and stay within 5 um of it (the biarc error of 16 pieces on this 10 mm curve).
    from cncc.ir import Arc, Linear

    cmds, r = compile_commands("F100\nG5 I0 J3 P0 Q-3 X10 Y1\n", dialect="linuxcnc", **SNIPPET)
    assert r.ok
    segs = [c for c in cmds if isinstance(c, Arc | Linear)]
    assert len(segs) == 32  # 16 samples x 2 arcs
    ctrl = [(0.0, 0.0), (0.0, 3.0), (10.0, -2.0), (10.0, 1.0)]
    curve = [_cubic(k / 2000, ctrl) for k in range(2001)]
    for a, b in itertools.pairwise(segs):
        assert a.end == b.start
    assert segs[-1].end[:2] == (10.0, 1.0)
    for s in segs:
        for q in _samples(s):
            assert min(math.dist(q, c) for c in curve) < 0.005
    assert max(_gap(s, curve) for s in segs) < 5e-3


def _samples(s: object) -> list[tuple[float, float]]:
    from cncc.ir import Arc

    assert hasattr(s, "start") and hasattr(s, "end")
    x0, y0, x1, y1 = s.start[0], s.start[1], s.end[0], s.end[1]
    if not isinstance(s, Arc):
        return [(x0 + (x1 - x0) * k / 8, y0 + (y1 - y0) * k / 8) for k in range(9)]
    cx, cy = s.center[0], s.center[1]
    r = math.hypot(x0 - cx, y0 - cy)
    a0, a1 = math.atan2(y0 - cy, x0 - cx), math.atan2(y1 - cy, x1 - cx)
    sweep = (a1 - a0) % (2 * math.pi) if s.turns > 0 else -((a0 - a1) % (2 * math.pi))
    return [(cx + r * math.cos(a0 + sweep * k / 8), cy + r * math.sin(a0 + sweep * k / 8)) for k in range(9)]


def _gap(s: object, curve: list[tuple[float, float]]) -> float:
    return max(min(math.dist(q, c) for c in curve) for q in _samples(s))


def test_biarc_is_tangent_at_both_ends() -> None:
    # Leaving (0,0) along +Y and arriving at (2,0) along -Y: two arcs whose first centre lies on
    # the X axis (tangent +Y at the start) and whose second ends on the X axis.
    segs = nurbs.biarc((0.0, 0.0), (0.0, 1.0), (2.0, 0.0), (0.0, -1.0))
    assert len(segs) == 2 and all(s.center is not None for s in segs)
    c0 = segs[0].center
    assert c0 is not None and c0[1] == pytest.approx(0.0, abs=1e-12)
    assert segs[1].end == (2.0, 0.0) and not segs[0].ccw  # turning right: clockwise


def test_nurbs_knots_and_circle_weights() -> None:
    # Knot vector of LinuxCNC's knot_vector_creator: 5 points, order 3 -> 0 0 0 1 2 3 3 3.
    assert nurbs.knots(5, 3) == [0, 0, 0, 1, 2, 3, 3, 3]
    # A quarter circle as a rational quadratic (weights 1, sqrt(2)/2, 1): every point on r = 1.
    cps = [(1.0, 0.0, 1.0), (1.0, 1.0, math.sqrt(0.5)), (0.0, 1.0, 1.0)]
    kv = nurbs.knots(3, 3)
    for k in range(11):
        x, y = nurbs.point(k / 10, 3, cps, kv)
        assert math.hypot(x, y) == pytest.approx(1.0, abs=1e-12)


def test_straight_spline_is_a_line() -> None:
    # Collinear control points: LinuxCNC's biarc formula divides by zero; cncc draws lines.
    cmds, r = compile_commands("F100\nG5.1 I1 J0 X4 Y0\n", dialect="linuxcnc", **SNIPPET)
    assert r.ok
    ends = [c.end[0] for c in cmds if hasattr(c, "end")]
    assert ends and ends[-1] == pytest.approx(4.0)
    assert all(c.end[1] == pytest.approx(0.0) for c in cmds if hasattr(c, "end"))


@pytest.mark.parametrize("prog, text", [
    ("G5 X1 Y1 F10\n", "Must specify both P and Q with G5"),
    ("G5 I1 P1 Q1 X1 F10\n", "Must specify both I and J, or neither"),
    ("G5.1 I1 X1 F10\n", "Must specify both I and J with G5.1"),
    ("G18 G5.1 I1 J1 X1 F10\n", "Splines must be in the XY plane"),
    ("G5.1 I1 J1 X1 Z1 F10\n", "Splines may not have motion in Z, A, B, or C"),
    ("G41.1 D1 G5 I1 J0 P1 Q1 X1 Y1 F10\n", "Cannot convert spline with cutter radius compensation"),
    ("G5.3\n", "Cannot use G5.3 without G5.2 first"),
    ("G5.2 X1 Y1 P1\nX2 Y0 P1\nG5.3\n", "Cannot make a NURBS with 0 feedrate"),
    ("G5.2 X1 Y1 P1 L3 F10\nG5.3\n", "You must specify a number of control points at least equal to the order L = 3"),
    ("G5.2 X1 Y1 P1 F10\nX2 Z1 P1\n", "You must specify both X and Y coordinates for Control Points"),
    ("G5.2 P2 L4 F10\nX1 Y1\n", "Must specify positive weight P for every Control Point"),
    ("G5.2 X1 Y1 P1 F10\nG1 X3\nG5.3\n", "Cannot use G5.3 without G5.2 first"),
])
def test_spline_errors(prog: str, text: str) -> None:
    assert first_error(prog).startswith(text)


# ---- canned cycles --------------------------------------------------------------------------------
def test_cycles_run_in_exact_path_and_restore_the_mode() -> None:
    # Each cycle block switches to CANON_EXACT_PATH and back to the mode in force (G64: tolerance
    # 0 and the naive-CAM tolerance).  G98: back to the start level Z5; G99: back to R.
    t = trace("F100\nG0 X0 Y0 Z5\nG98 G81 X1 Y1 Z-2 R1\nG99 X2\n")
    assert t[2:] == [
        'COMMENT("interpreter: retract mode set to old_z")', "SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)",
        "STRAIGHT_TRAVERSE(1.0000, 1.0000, 5.0000, 0.0000, 0.0000, 0.0000)",
        "STRAIGHT_TRAVERSE(1.0000, 1.0000, 1.0000, 0.0000, 0.0000, 0.0000)",
        "STRAIGHT_FEED(1.0000, 1.0000, -2.0000, 0.0000, 0.0000, 0.0000)",
        "STRAIGHT_TRAVERSE(1.0000, 1.0000, 5.0000, 0.0000, 0.0000, 0.0000)",
        "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, 0.000000)", "SET_NAIVECAM_TOLERANCE(0.0000)",
        'COMMENT("interpreter: retract mode set to r_plane")', "SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)",
        "STRAIGHT_TRAVERSE(2.0000, 1.0000, 5.0000, 0.0000, 0.0000, 0.0000)",
        "STRAIGHT_TRAVERSE(2.0000, 1.0000, 1.0000, 0.0000, 0.0000, 0.0000)",
        "STRAIGHT_FEED(2.0000, 1.0000, -2.0000, 0.0000, 0.0000, 0.0000)",
        "STRAIGHT_TRAVERSE(2.0000, 1.0000, 1.0000, 0.0000, 0.0000, 0.0000)",
        "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, 0.000000)", "SET_NAIVECAM_TOLERANCE(0.0000)"]


def test_g73_chip_break_and_g83_full_retract() -> None:
    # Q1.2 from R1: pecks to -0.2, -1.4, -2.6, then the bottom -3.  G73 backs off 0.010 in
    # (0.254 mm) after each peck; G83 rapids up to R and back down to 0.254 above the last depth.
    # The start-up default is G99 (rs274 starts in R_PLANE retract mode): both end at R.
    moves = [(n, a[2]) for n, a in calls([P + ln for ln in trace(
        "F100\nG0 X0 Y0 Z5\nG73 X3 Z-3 R1 Q1.2\nG83 X4\n")], "STRAIGHT_TRAVERSE", "STRAIGHT_FEED")]
    g73 = [(n[9], round(z, 4)) for n, z in moves[1:11]]
    assert g73 == [("T", 5.0), ("T", 1.0), ("F", -0.2), ("T", 0.054), ("F", -1.4), ("T", -1.146),
                   ("F", -2.6), ("T", -2.346), ("F", -3.0), ("T", 1.0)]
    g83 = [(n[9], round(z, 4)) for n, z in moves[11:]]
    assert g83 == [("T", 1.0), ("F", -0.2), ("T", 1.0), ("T", 0.054), ("F", -1.4), ("T", 1.0),
                   ("T", -1.146), ("F", -2.6), ("T", 1.0), ("T", -2.346), ("F", -3.0), ("T", 1.0)]


def test_incremental_r_and_l_repeats() -> None:
    # G91: R-3 from the start level 5 is 2, Z-4 from R is -2; L2 repeats the X2 step.
    moves = [a[:3] for _, a in calls([P + ln for ln in trace(
        "F100\nG0 X4 Y1 Z5\nG91 G98 G81 X2 Z-4 R-3 L2\n")], "STRAIGHT_TRAVERSE", "STRAIGHT_FEED")]
    assert moves[1:] == [[6, 1, 5], [6, 1, 2], [6, 1, -2], [6, 1, 5], [8, 1, 5], [8, 1, 2], [8, 1, -2], [8, 1, 5]]


def test_cycle_below_r_rises_to_r_first() -> None:
    # Started below R, the tool first rises to R (before the exact-path switch); R is then the
    # level the G98 hole returns to.
    t = trace("F10\nG0 Z0\nG98 G81 X1 Z-1 R1\n")
    assert t[2:5] == ['COMMENT("interpreter: retract mode set to old_z")',
                      "STRAIGHT_TRAVERSE(0.0000, 0.0000, 1.0000, 0.0000, 0.0000, 0.0000)",
                      "SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)"]
    assert t[-3] == "STRAIGHT_TRAVERSE(1.0000, 0.0000, 1.0000, 0.0000, 0.0000, 0.0000)"


@pytest.mark.parametrize("prog, text", [
    ("G81 X1 Z-1 F10\n", "R clearance plane unspecified in cycle"),
    ("G81 X1 R1 F10\n", "Z value unspecified in xy plane canned cycle"),
    ("G81 X1 Z2 R1 F10\n", "R less than z in cycle in xy plane"),
    ("G83 X1 Z-1 R1 F10\n", "Q word missing with g83"),
    ("G73 X1 Z-1 R1 F10\n", "Q word missing with g73"),
])
def test_cycle_errors(prog: str, text: str) -> None:
    assert first_error(prog).startswith(text)


# ---- cutter compensation errors (the comp pass's codes, LinuxCNC's texts) ------------------------------
@pytest.mark.parametrize("prog, text", [
    # an inside arc of radius 1 with a tool of radius 2
    ("F100\nG0 X0 Y-10\nG41.1 D4\nG1 X0 Y0\nG3 X2 Y0 I1 J0\nG1 X10\nG40 X20\n",
     "Tool radius not less than arc radius with comp"),
    # the move after G40 is an arc
    ("F100\nG0 X0 Y-10\nG41.1 D4\nG1 X0 Y0\nX10\nG40 G2 X20 Y0 I5\n",
     "The move just after exiting cutter compensation mode must be straight, not an arc"),
    # a slot 1 mm wide for a tool 4 mm across
    ("F100\nG0 X0 Y0\nG42.1 D4\nG1 X10 Y0\nX10 Y10\nX11 Y10\nX11 Y0\nX20 Y0\nG40 G1 X30 Y-10\n",
     "Straight feed in concave corner cannot be reached by the tool without gouging"),
    ("G17 G41.1 D1\nG18\n", "Cannot change planes with cutter radius compensation on"),
])
def test_cutter_comp_errors_use_linuxcnc_texts(prog: str, text: str) -> None:
    assert first_error(prog).startswith(text)


def test_comp_texts_only_for_linuxcnc() -> None:
    _, r = canon("G00 X0 Y-10\nG41 D1 G01 X0 Y0 F100\nG03 X2 Y0 I1 J0\nG01 X10\nG40 X20\n", "syntec",
                 tools_file=None)
    assert all("Tool radius not less" not in d.message for d in r.sink)
