"""--keep-subprograms: called programs written once and called, the motion unchanged.

The round trip (source motion == motion of the translation compiled in the target) is
checked with the subprograms kept; the structure of the output is checked against what
the corpus program ``subprograms.nc`` calls: O1000 (an incremental pocket, called at
three places) and O1100 (nested in it) and O2000 (absolute, the same blocks on both
runs of L2) are kept; O3000 (a G65 macro whose body depends on its argument) is not.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from cncc.api import compile_text
from cncc.cli import main
from tests.backends.test_translate_roundtrip import DATA, TABLES, TARGETS, check

TEXT = (DATA / "corpus" / "syntec" / "subprograms.nc").read_text()
CALLERS = {"syntec", "fanuc", "haas", "szgh", "linuxcnc"}  # targets with M98 or o-word subroutines


def calls(out: str) -> list[str]:
    """The program numbers called, in order (M98 P<n> or o<n> call)."""
    return [a or b for a, b in re.findall(r"M98 P(\d+)|o(\d+) call", out)]


@pytest.mark.parametrize("target", TARGETS)
def test_kept_subprograms_keep_the_motion(target: str) -> None:
    out = check(TEXT, "syntec", target, keep_subprograms=True)
    if target in CALLERS:
        # main: 3 x O1000, 2 x O2000; the O1000 section calls O1100 once
        assert sorted(calls(out)) == ["1000", "1000", "1000", "1100", "2000", "2000"]
        assert "O3000" not in out and "P3000" not in out
    else:
        assert calls(out) == []


@pytest.mark.parametrize("target", sorted(CALLERS - {"linuxcnc"}))
def test_sections_follow_the_main_program(target: str) -> None:
    out = check(TEXT, "syntec", target, keep_subprograms=True)
    end = out.index("M30")
    for n in ("1000", "1100", "2000"):
        assert out.index(f"O{n}\n") > end
    pocket = out[out.index("O1000\n"):out.index("M99", out.index("O1000\n"))]
    assert pocket.splitlines()[1].startswith("G91")  # position-independent: written incremental
    finish = out[out.index("O2000\n"):]
    assert "G90" in finish.splitlines()[1] and "X100. Y100." in finish


def test_linuxcnc_subroutines_come_first() -> None:
    out = check(TEXT, "syntec", "linuxcnc", keep_subprograms=True)
    assert out.index("o1000 sub") < out.index("o1000 endsub") < out.index("G17 G21 G90 G94")
    assert "M98" not in out and "M99" not in out


def diagnostics(text: str, target: str, source: str = "syntec", **opts: object) -> list[tuple[str, str]]:
    r = compile_text(text, dialect=source, emit="gcode", target=target, keep_subprograms=True,
                     **TABLES, **opts)  # type: ignore[arg-type]
    return [(d.code, d.message) for d in r.sink]


def test_flattened_bodies_and_targets_without_calls_are_noted() -> None:
    found = diagnostics(TEXT, "fanuc")
    assert [c for c, m in found if c == "N0808" and "O3000" in m]
    assert not [c for c, m in found if c == "N0808" and ("O1000" in m or "O2000" in m)]
    assert [c for c, m in diagnostics(TEXT, "grbl") if c == "N0808" and "cannot call" in m]


NESTED = """G90 G17 G71 G94
G00 X0. Y0. Z5.
M98 P10
M30
O10
G91 G01 X1. F100.
M98 P20
M99
O20
G91 G01 Y1.
M98 P30
M99
O30
G91 G01 X-1.
G90
M99
"""


def test_nesting_deeper_than_the_target_flattens_the_innermost_level() -> None:
    found = diagnostics(NESTED, "linuxcnc", target_options={"max_call_depth": 2})
    assert [c for c, _ in found].count("W0814") == 1
    out = check(NESTED, "syntec", "linuxcnc", keep_subprograms=True, target_options={"max_call_depth": 2})
    assert sorted(calls(out)) == ["10", "20"] and "o30 sub" not in out
    deep = check(NESTED, "syntec", "linuxcnc", keep_subprograms=True)  # LinuxCNC's own limit is 10
    assert sorted(calls(deep)) == ["10", "20", "30"]


def test_program_numbers_outside_the_target_range_are_renumbered() -> None:
    text = NESTED.replace("P30", "P12345").replace("O30", "O12345").replace("G71", "G21")  # SZGH
    found = diagnostics(text, "fanuc", source="szgh")
    assert [m for c, m in found if c == "W0813" and "12345" in m]
    out = check(text, "szgh", "fanuc", keep_subprograms=True)
    assert "12345" not in out and len(set(calls(out))) == 3


def test_without_the_option_the_output_is_flattened() -> None:
    out = check(TEXT, "syntec", "fanuc")
    assert calls(out) == [] and "O1000" not in out


def test_target_option_on_the_command_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    src = tmp_path / "nested.nc"
    src.write_text(NESTED)
    argv = ["-x", "syntec", "-t", "linuxcnc", "--emit=gcode", "--keep-subprograms", str(src)]
    assert main([*argv, "--target-option", "max_call_depth=1"]) == 0
    one = capsys.readouterr()
    assert "W0814" in one.err and one.out.count(" sub\n") == 1
    assert main(argv) == 0
    assert capsys.readouterr().out.count(" sub\n") == 3
    assert main([*argv, "--target-option", "no_such_option=1"]) != 0
    assert "E0904" in capsys.readouterr().err
