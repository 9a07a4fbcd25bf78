"""LinuxCNC system parameters and (DEBUG,...) formatting; expected values measured on rs274 2.9
(the same programs run in tests/oracle, features ``parameters`` and ``messages``)."""

from __future__ import annotations

from cncc.api import compile_text
from cncc.frontend.linuxcnc.messages import format_message
from tests.helpers import codes


def _messages(text: str) -> list[str]:
    r = compile_text("G21\n" + text + "M2\n", dialect="linuxcnc", emit="canon")
    return [ln.split("MESSAGE(", 1)[1][1:-2] for ln in r.output.splitlines() if "MESSAGE(" in ln]


def test_format_words_as_rs274_prints_them() -> None:
    values = {1: 5.75, 2: -2.5}
    names = {"_x": 0.0}

    def fmt(text: str) -> str:
        return format_message(text, lambda n: values.get(n, 0.0), names.get)

    assert fmt("A %.1f #1 #1") == "A  5.8 5.8"  # the format holds to the end of the text
    assert fmt("B %d #1 %f #1") == "B  6  5.7500"  # %d: no decimals; %f: four
    assert fmt("C %.9f #1") == "C  5.750000000"
    assert fmt("D %.12f #1") == "D .12f 5.750000"  # two digits: not a format, the % dropped
    assert fmt("E %d #2 %d #<_x>") == "E  -2  0"  # -2.5 rounds to even
    assert fmt("H %x #1 %s %") == "H %x 5.750000 %s %"
    assert fmt("K %d#1%d") == "K 6"
    assert fmt("M %%d #1") == "M % 6"
    assert fmt("O #<nope> %.2f #<nope2>") == "O ######  ######"
    assert fmt("P ##1 # #a") == "P #5.750000 # #a"


def test_text_after_the_comma_is_kept_as_written() -> None:
    assert _messages("#1=5\n(DEBUG,   sp=#1   )\n(MSG,  m2   )\n(MSG, m #1)\n") == \
        ["   sp=5.000000   ", "  m2   ", " m #1"]


def test_offsets_read_back_in_machine_units() -> None:
    # rs274's machine units are inches: G10 L2 P1 X25.4 (mm) is #5221 = 1
    got = _messages("G10 L2 P1 X25.4 R30\nG10 L2 P2 X-25.4\nG55\n(DEBUG,#5221 #5230 #5241 #5220)\n")
    assert got == ["1.000000 30.000000 -1.000000 2.000000"]


def test_g92_parameters() -> None:
    got = _messages("G0 X1\nG92 X0\n(DEBUG,#5210 %.4f#5211)\nG92.2\n(DEBUG,#5210 %.4f#5211)\nG92.1\n"
                    "(DEBUG,#5210 #5211)\n")
    assert got == ["1.000000 0.0394", "0.000000 0.0394", "0.000000 0.000000"]


def test_position_parameters_in_program_units() -> None:
    got = _messages("G10 L2 P1 X5\nG0 X1 Y2\nG20\n(DEBUG,%.4f #5420 #<_x> #<_abs_x> #5421)\n")
    assert got == [" 0.0394 0.0394 0.2362 0.0787"]  # 1 mm, 1 mm, 6 mm, 2 mm in inches


def test_written_offset_is_the_next_g10s() -> None:
    # rs274 2.9: #5222 written, then G10 L2 P1 Z: the G54 offset takes Y from the parameter
    r = compile_text("G21\n#5222 = 25.4\nG10 L2 P1 Z1\nM2\n", dialect="linuxcnc", emit="canon")
    assert "SET_G5X_OFFSET(1, 0.0000, 645.1600, 1.0000" in r.output  # 25.4 inch in mm


def test_read_only_parameters() -> None:
    for text in ("#5420 = 1\n", "#5400 = 1\n", "#<_x> = 1\n", "#<_line> = 2\n"):
        r = compile_text("G21\n" + text + "M2\n", dialect="linuxcnc", emit="canon")
        assert "E0303" in codes(r), text
    r = compile_text("G21\n#5602 = 1\nM2\n", dialect="linuxcnc", emit="canon")
    assert "E0302" in codes(r)
    r = compile_text("G21\n#5221 = 1\n#<_mine> = 2\nM2\n", dialect="linuxcnc", emit="canon")
    assert r.ok


def test_lathe_mode_parameters_follow_g7_g8_and_are_read_only() -> None:
    # rs274 2.9: "G7 (DEBUG,...) G8 (DEBUG,...)" prints d=1 r=0, then d=0 r=1
    got = _messages("(DEBUG,#<_lathe_diameter_mode> #<_lathe_radius_mode>)\nG7\n"
                    "(DEBUG,#<_lathe_diameter_mode> #<_lathe_radius_mode>)\nG8\n"
                    "(DEBUG,#<_lathe_diameter_mode> #<_lathe_radius_mode>)\n")
    assert got == ["0.000000 1.000000", "1.000000 0.000000", "0.000000 1.000000"]
    r = compile_text("G21\n#<_lathe_diameter_mode> = 1\nM2\n", dialect="linuxcnc", emit="canon")
    assert "E0303" in codes(r)
