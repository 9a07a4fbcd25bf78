"""Fanuc-style M98/M99 programs in the linuxcnc dialect (LinuxCNC 2.9's rules; the programs of
tests/oracle/cases.py ``m98_*``/``m99_*`` check the same against rs274)."""

from __future__ import annotations

from cncc.api import compile_text
from tests.helpers import codes


def _run(text: str) -> tuple[list[str], list[str]]:
    r = compile_text("G21\n" + text, dialect="linuxcnc", emit="canon")
    return [ln.strip() for ln in r.output.splitlines()], codes(r)


def test_l_repeats_and_the_sub_sees_the_callers_parameters() -> None:
    lines, errs = _run("#1 = 7\nM98 P100 L3\n(DEBUG,#2)\nM30\nO100\n#2 = [#2 + #1]\nG91 G0 X1\nG90\nM99\n")
    assert not errs
    assert sum("STRAIGHT_TRAVERSE" in ln for ln in lines) == 3
    assert 'N..... MESSAGE("21.000000")' in lines  # no local scope: #2 = 3 x 7


def test_m99_in_the_main_program_ends_it_as_m2() -> None:
    lines, errs = _run("G0 X1\nM99\nG0 X3\nM2\n")
    assert not errs
    assert "N..... PROGRAM_END()" in lines and not any("TRAVERSE(3.0000" in ln for ln in lines)


def test_m98_reads_only_as_the_first_word() -> None:
    lines, errs = _run("M98 P100 G0 X1 F100\nM30\nO100\nG0 Y1\nM99\n")
    assert not errs and not any("TRAVERSE(1.0000" in ln for ln in lines)  # G0 X1 not run
    assert "E0202" in _run("G0 X1 M98 P100\nM30\nO100\nG0 Y1\nM99\n")[1]


def test_mixed_styles_are_errors() -> None:
    assert "E0386" in _run("o100 call\nM30\nO100\nG0 X1\nM99\n")[1]  # a Fanuc program called by o-call
    assert "E0386" in _run("M98 P100\nM30\no100 sub\nG0 X1\no100 endsub\n")[1]  # an o-sub called by M98
    assert "E0386" in _run("M98 P100\nM30\nO100\nG0 X1\no100 endsub\n")[1]  # ended by endsub
    assert "E0386" in _run("o100 sub\nM99\no100 endsub\no100 call\nM30\n")[1]  # ended by M99
    assert "E0386" in _run("M98 P100\nM30\nO100\nG0 X1 M99\n")[1]  # M99 not alone in a subprogram


def test_negative_cases() -> None:
    assert "E0350" in _run("o100 sub\nO200\nM99\no100 endsub\nM30\n")[1]  # Nested subroutine definition
    assert "E0316" in _run("M98\nM30\n")[1]
    assert "E0316" in _run("M98 P100 L1.5\nM30\nO100\nM99\n")[1]
    assert "E0316" in _run("M98 P100 L-1\nM30\nO100\nM99\n")[1]
    assert "E0326" in _run("M98 P100\nM30\nO100\nG0 X1\n")[1]  # runs off the end without M99
    assert "E0309" in _run("M98 P100\nM30\nO100\nM98 P100\nM99\n")[1]


def test_named_parameter_assigned_on_its_line_reads_zero() -> None:
    # rs274 2.9 defines #<n> when it reads the assignment: #<n> = [#<n> + 1] is 1, not an error
    lines, errs = _run("#<n> = [#<n> + 1]\n(DEBUG,#<n>)\nM2\n")
    assert not errs and 'N..... MESSAGE("1.000000")' in lines
    assert "E0352" in _run("G0 X#<nope>\nM2\n")[1]
