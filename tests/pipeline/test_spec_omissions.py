"""W0973: a -p list that leaves out path passes the output is made of (docs/architecture.md, "-p spec").

``-p 'blend,plan,verify'`` names plan-stage passes only: it replaces the planning stage and, since
path-stage names replace the path stage, drops the path stage with it.  The output is then not the
program's motion -- here a G68 rotation (SYNTEC §1.2.23: X10. under G68 R90. is the point (0, 10))
is not applied -- and cncc says so.  A list that names path passes chose them, except that the
machine-coordinate outputs (timing, pulses) need ``to-machine`` and ``tool-length``.
"""

from __future__ import annotations

from typing import Any

import pytest

from cncc.api import compile_text
from tests.helpers import codes

ROTATED = "G90 G17 G00 X0. Y0.\nG68 X0. Y0. R90.\nG01 X10. F600.\nG69\nM30\n"
PATH = "expand-cycles,polar,scaling,mirror,rotation,cutter-comp,arc-check"


def feed_end(r: Any) -> tuple[float, float]:
    line = next(x for x in r.output.splitlines() if "STRAIGHT_FEED(" in x)
    x, y = line.split("(")[1].split(",")[:2]
    return float(x), float(y)


def test_plan_passes_alone_drop_the_path_stage_and_say_so() -> None:
    default = compile_text(ROTATED, dialect="syntec")
    assert feed_end(default) == pytest.approx((0.0, 10.0)) and "W0973" not in codes(default)
    dropped = compile_text(ROTATED, dialect="syntec", passes="blend,plan,verify")
    assert feed_end(dropped) == pytest.approx((10.0, 0.0))  # the rotation did not run: the warning is due
    assert "W0973" in codes(dropped)
    d = next(d for d in dropped.sink if d.code == "W0973")
    assert "rotation" in d.message and "expand-cycles" in d.message and "arc-check" not in d.message


def test_a_list_of_path_passes_is_the_users_choice() -> None:
    assert "W0973" not in codes(compile_text(ROTATED, dialect="syntec", passes=PATH))
    assert "W0973" not in codes(compile_text(ROTATED, dialect="syntec", passes="expand-cycles,arc-check"))


@pytest.mark.parametrize("emit", ["timing", "pulses"])
def test_machine_outputs_need_machine_coordinates(emit: str) -> None:
    r = compile_text(ROTATED, dialect="syntec", emit=emit, passes=PATH, quiet=True)
    d = [d for d in r.sink if d.code == "W0973"]
    assert len(d) == 1 and "to-machine" in d[0].message and "tool-length" in d[0].message
    full = PATH.replace("cutter-comp", "to-machine,tool-length,cutter-comp")
    assert "W0973" not in codes(compile_text(ROTATED, dialect="syntec", emit=emit, passes=full, quiet=True))


def test_no_output_no_warning() -> None:
    assert "W0973" not in codes(compile_text(ROTATED, dialect="syntec", passes="blend,plan,verify",
                                             syntax_only=True))
    assert "W0973" not in codes(compile_text(ROTATED, dialect="syntec", emit="none", passes="blend,plan,verify"))
