"""Machine models: built-ins load, overrides apply, bad files name the key."""

from __future__ import annotations

from pathlib import Path

import pytest

from cncc.ir.machine import CornerRule, RapidMode
from cncc.machines import MachineError, builtin_names, load_machine


@pytest.mark.parametrize("name", builtin_names())
def test_builtins_load(name: str) -> None:
    m = load_machine(name)
    assert m.name == name and m.axes


def test_szgh_factory_values() -> None:
    m = load_machine("szgh-990mdb")
    x = m.axis("X")
    assert x is not None
    assert m.rapid_mode is RapidMode.INDEPENDENT and m.rapid_ends_in_stop
    assert m.corner_rule is CornerRule.SPEED_STEP and m.interpolation_period_s == 0.002
    assert x.rapid_mm_min == 4000 and x.max_accel_mm_s2 == pytest.approx(50000 / 60, rel=1e-5)
    assert x.step.max_step_rate_hz == 2e6 and x.step.steps_per_mm == 1000


def test_overrides_and_base(tmp_path: Path) -> None:
    m = load_machine("generic-mill", {"axes.X.max_accel_mm_s2": 500, "max_feed_mm_min": 4000})
    assert m.axis("X").max_accel_mm_s2 == 500 and m.max_feed_mm_min == 4000  # type: ignore[union-attr]
    f = tmp_path / "mine.toml"
    f.write_text('base = "szgh-990mdb"\nname = "mine"\n[[axes]]\nname = "Y"\nrapid_mm_min = 8000\n')
    mine = load_machine(str(f))
    assert mine.name == "mine" and mine.axis("Y").rapid_mm_min == 8000  # type: ignore[union-attr]
    assert mine.axis("X").rapid_mm_min == 4000  # type: ignore[union-attr]


@pytest.mark.parametrize(("text", "key"), [
    ('name = "m"\n[[axes]]\nname = "X"\nmax_jerk = 5\n', "axes.X.max_jerk"),
    ('name = "m"\ncorner_rule = "round"\n[[axes]]\nname = "X"\n', "corner_rule"),
    ('name = "m"\n[[axes]]\nname = "X"\nmax_accel_mm_s2 = "fast"\n', "axes.X.max_accel_mm_s2"),
    ('name = "m"\n[[axes]]\nname = "X"\nmax_accel_mm_s2 = -1\n', "axes.X.max_accel_mm_s2"),
    ('name = "m"\n', "axes"),
])
def test_bad_file_names_the_key(tmp_path: Path, text: str, key: str) -> None:
    f = tmp_path / "bad.toml"
    f.write_text(text)
    with pytest.raises(MachineError) as err:
        load_machine(str(f))
    assert err.value.key == key
    assert isinstance(err.value, ValueError)
