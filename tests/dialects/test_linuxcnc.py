"""LinuxCNC (rs274ngc): O-word control flow, parameters, offsets and the canon trace.

Expected traces are derived by hand from LinuxCNC's G-code and O-code documentation:
each comment says why a line is there.  Bad programs must give the interpreter's
error texts (the dialect's [errors] table holds them; they and the call formats were
checked against LinuxCNC 2.9's stand-alone ``rs274 -g``).
"""

from __future__ import annotations

import pytest

from tests.helpers import calls, canon, codes, moves

# The snippets below are not whole programs: no M2/M30 at the end (E0326 is tested on its own).
SNIPPET = {"dialect_options": {"program_end_required": False}}

P = " N..... "


def trace(text: str) -> list[str]:
    """The trace after the start-up calls, without the stand-alone interpreter's two final ON_RESET()."""
    lines, r = canon(text, "linuxcnc", **SNIPPET)
    assert not r.sink.has_errors, [d.message for d in r.sink]
    assert lines[-2:] == [P + "ON_RESET()"] * 2
    return [ln.removeprefix(P) for ln in lines[:-2]]


def xyz(text: str) -> list[tuple[float, ...]]:
    return [m[1][:3] for m in moves(text, "linuxcnc")]


def errors(text: str) -> list[str]:
    _, r = canon(text, "linuxcnc", **SNIPPET)
    return [d.message for d in r.sink if d.severity.label == "error"]


def test_startup_sequence_is_rs274s() -> None:
    r = canon("G21\n", "linuxcnc")[1]
    head = [ln.removeprefix(P) for ln in r.output.splitlines()[:6]]
    assert head == ["USE_LENGTH_UNITS(CANON_UNITS_MM)",
                    "SET_G5X_OFFSET(1, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)",
                    "SET_G92_OFFSET(0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)",
                    "SET_XY_ROTATION(0.0000)", "SET_FEED_REFERENCE(CANON_XYZ)", "ON_RESET()"]


def test_numbered_and_named_parameters() -> None:
    # #1 = 2, #<d> = 3, #<_g> global; the block's words see the values before its own assignments.
    got = xyz("#1 = 2\n#<d> = 3\n#<_g> = [#1 * #<d>]\nG0 X#1 Y#<d> Z#<_g>\n#1 = 7 G0 X#1\nG0 X#1\n")
    assert got == [(2.0, 3.0, 6.0), (2.0, 3.0, 6.0), (7.0, 3.0, 6.0)]


def test_expressions_precedence_and_functions() -> None:
    # ** binds tighter than *, which binds tighter than +; comparisons then AND/OR.
    got = xyz("G0 X[2 + 3 * 2 ** 2] Y[ATAN[1]/[1]] Z[7 MOD 3]\nG0 X[1 LT 2 AND 3 GT 4] Y[1 EQ 1 OR 0] Z[ABS[-2]]\n")
    assert got == [(14.0, 45.0, 1.0), (0.0, 1.0, 2.0)]


def test_exists() -> None:
    assert xyz("#<a> = 1\nG0 X[EXISTS[#<a>]] Y[EXISTS[#<b>]]\n") == [(1.0, 0.0, 0.0)]


def test_sub_call_return_value_and_local_scope() -> None:
    prog = """o<double> sub
  #<local> = 5
  o<double> return [#1 * 2]
o<double> endsub
#1 = 100
o<double> call [4]
G0 X#<_value> Y#1 Z[EXISTS[#<local>]]
"""
    # _value = 8; #1 in the caller is untouched (#1-#30 are local); #<local> is gone after return.
    assert xyz(prog) == [(8.0, 100.0, 0.0)]


def test_if_elseif_else() -> None:
    prog = """#<n> = {n}
o1 if [#<n> EQ 1]
  G0 X1
o1 elseif [#<n> EQ 2]
  G0 X2
o1 else
  G0 X3
o1 endif
"""
    assert [xyz(prog.format(n=n)) for n in (1, 2, 5)] == [[(1.0, 0.0, 0.0)], [(2.0, 0.0, 0.0)], [(3.0, 0.0, 0.0)]]


def test_while_do_repeat_break_continue() -> None:
    prog = """#<i> = 0
o1 do
  #<i> = [#<i> + 1]
  o2 if [#<i> EQ 2]
    o1 continue
  o2 endif
  o3 if [#<i> EQ 4]
    o1 break
  o3 endif
  G0 Y#<i>
o1 while [#<i> LT 10]
#<j> = 0
o4 while [#<j> LT 2]
  #<j> = [#<j> + 1]
  G0 Z#<j>
o4 endwhile
o5 repeat [3]
  G91 G0 X1
o5 endrepeat
"""
    ys = [p[1] for p in xyz(prog)][:2]
    got = xyz(prog)
    assert ys == [1.0, 3.0]  # 2 skipped by continue, the loop broken at 4
    assert [p[2] for p in got[2:4]] == [1.0, 2.0]
    assert [p[0] for p in got[4:]] == [1.0, 2.0, 3.0]


def test_m98_m99() -> None:
    prog = "G0 X0\nM98 P100 L3\nG90 G0 Y5\nM2\nO100\nG91 G0 X2\nM99\n"
    assert [p[:2] for p in xyz(prog)] == [(0.0, 0.0), (2.0, 0.0), (4.0, 0.0), (6.0, 0.0), (6.0, 5.0)]


def test_g10_l2_l20_and_g92_family() -> None:
    t = trace("G0 X1\nG10 L2 P1 X10\nG10 L20 P1 X0\nG92 X4\nG92.2\nG92.3\nG92.1\n")
    # L2: G54 X offset 10; the machine stays at X1 (program -9).  L20 X0: machine 1 becomes
    # program 0 -> offset 1.
    # G92 X4 at program 0: offset -4.  G92.2 clears it (the parameters keep -4), G92.3 brings it back,
    # G92.1 clears both.
    assert [ln for ln in t if ln.startswith("SET_G")] == [
        "SET_G5X_OFFSET(1, 10.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)",
        "SET_G5X_OFFSET(1, 1.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)",
        "SET_G92_OFFSET(-4.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)",
        "SET_G92_OFFSET(0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)",
        "SET_G92_OFFSET(-4.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)",
        "SET_G92_OFFSET(0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)"]


def test_g10_l1_and_g43() -> None:
    t = trace("G10 L1 P3 Z12.5 R2\nT3 M6\nG43 H3\n")
    assert "USE_TOOL_LENGTH_OFFSET(0.0000 0.0000 12.5000, 0.0000 0.0000 0.0000, 0.0000 0.0000 0.0000)" in t


def test_g43_1_dynamic_offset() -> None:
    assert trace("G43.1 Z3\n")[-1] == (
        "USE_TOOL_LENGTH_OFFSET(0.0000 0.0000 3.0000, 0.0000 0.0000 0.0000, 0.0000 0.0000 0.0000)")


def test_path_modes() -> None:
    # rs274 prints the blending tolerance with %f and the others without a tolerance argument.
    assert trace("G64 P0.01 Q0.02\nG64 P0.05\nG61\nG61.1\n") == [
        "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, 0.010000)", "SET_NAIVECAM_TOLERANCE(0.0200)",
        "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, 0.050000)", "SET_NAIVECAM_TOLERANCE(0.0500)",  # Q defaults to P
        "SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)", "SET_MOTION_CONTROL_MODE(CANON_EXACT_STOP)"]


def test_interpreter_comments() -> None:
    t = trace("G40\nG93\nG94\n")
    assert t[0] == 'COMMENT("interpreter: cutter radius compensation off")'
    assert 'COMMENT("interpreter: feed mode set to inverse time")' in t
    assert 'COMMENT("interpreter: feed mode set to units per minute")' in t


def test_inverse_time_feed() -> None:
    # G93 F2: the 10 mm move takes 1/2 minute -> 20 mm/min.
    t = trace("G0 X0\nG93 G1 X10 F2\n")
    assert calls(t and [P + ln for ln in t], "SET_FEED_RATE") == [("SET_FEED_RATE", [20.0])]


def test_arc_centres_absolute_g90_1() -> None:
    got = moves("G0 X0 Y0\nG90.1 G2 X10 Y0 I5 J0 F100\n", "linuxcnc")
    assert got[-1] == ("ARC_FEED", (10.0, 0.0, 5.0, 0.0, -1.0, 0.0, 0.0, 0.0, 0.0))


def test_messages() -> None:
    _, r = canon("#<d> = 2.5\n(MSG, hello)\n(DEBUG, d=#<d>)\n(PRINT, d is #<d>)\n", "linuxcnc")
    t = r.output.splitlines()[6:-2]
    # the text after the comma as written, its leading blank too (rs274 2.9: MESSAGE(" hello"))
    assert [ln.removeprefix(P) for ln in t] == ['MESSAGE(" hello")', 'MESSAGE(" d=2.500000")']
    assert [d.message for d in r.sink if d.code == "N0353"] == ["d is 2.500000"]


def test_drill_cycle_retracts_as_linuxcnc() -> None:
    # G98 with the start at Z5 and R2: retract to the higher (Z5); L2 in G91 repeats the hole 4 mm on.
    got = xyz("G0 X0 Y0 Z5\nG91 G98 G81 X4 Y0 Z-4 R-3 L2 F100\n")
    assert got[-1] == (8.0, 0.0, 5.0)
    bottoms = [p for p in got if abs(p[2] + 2.0) < 1e-9]
    assert [p[0] for p in bottoms] == [4.0, 8.0]  # R at 5-3=2, bottom 2-4=-2


@pytest.mark.parametrize("prog, text", [
    ("G12 X1\n", "Unknown g code used"),
    ("M123\n", "Unknown m code used"),
    ("G0 G1 X1\n", "Two g codes used from same modal group"),
    ("G0 X1 X2\n", "Multiple x words on one line"),
    ("G1 X1\n", "Cannot do g1 with zero feed rate"),
    ("G2 X10 R2 F100\n", "Arc radius too small to reach end point"),
    ("G0 X#<nope>\n", "Named parameter #<nope> not defined"),
    ("G0 X[1/0]\n", "Attempt to divide by zero"),
    ("G10 L3 P1 X0\n", "Line with G10 does not have L0, L1, L10, L11, L2, or L20"),
    ("G4\n", "Dwell time missing with g4"),
])
def test_error_texts(prog: str, text: str) -> None:
    msgs = errors(prog)
    assert msgs and msgs[0].startswith(text), msgs


def test_program_stops_at_first_error() -> None:
    assert xyz("G0 X1\nG12\nG0 X2\n") == [(1.0, 0.0, 0.0)]


def test_structure_errors() -> None:
    _, r = canon("o1 while [1]\nG0 X1\n", "linuxcnc")
    assert "E0350" in codes(r)
    _, r = canon("o<nowhere> call\n", "linuxcnc")
    assert "E0351" in codes(r)
