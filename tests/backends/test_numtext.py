"""Vectorised number text (cncc/backends/numtext.py, gcode/batch.py) against Python's own formatting."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from cncc.backends import numtext as nt
from cncc.backends.gcode.batch import _counts, _words
from cncc.backends.gcode.numbers import counts_text, quantize


def rows(m: nt.Matrix) -> list[str]:
    return [bytes(r[r != nt.PAD]).decode() for r in m]


def canon(v: float, decimals: int) -> str:
    s = f"{v:.{decimals}f}"
    return s.lstrip("-") if float(s) == 0.0 else s  # the trace writes no -0.0000


values = st.lists(st.one_of(st.floats(-1e6, 1e6, allow_nan=False), st.integers(-10**6, 10**6).map(lambda i: i / 1000),
                            st.sampled_from([0.0, -0.0, 1e-9, -1e-9, 0.00005, -0.00004999, 2.5, -2.5, 1e10 / 3])),
                  min_size=1, max_size=50)


@settings(max_examples=300, deadline=None)
@given(values, st.sampled_from([0, 3, 4]), st.booleans())
def test_fixed_is_percent_f(vals: list[float], decimals: int, minus_zero: bool) -> None:
    m = nt.fixed(np.array(vals), decimals, minus_zero=minus_zero)
    if m is None:  # refused: some value is within its rounding error of a half (or too large)
        scaled = [abs(v) * 10**decimals for v in vals]
        assert any(abs(s - int(s) - 0.5) < 1e-6 or s >= 1e15 for s in scaled)
        return
    want = [f"{v:.{decimals}f}" if minus_zero else canon(v, decimals) for v in vals]
    assert rows(m) == want


def test_fixed_refuses_halves() -> None:
    assert nt.fixed(np.array([0.5]), 0) is None
    assert nt.fixed(np.array([1.25]), 1) is None
    assert rows(nt.fixed(np.array([1.26, -0.00001]), 1)) == ["1.3", "0.0"]  # type: ignore[arg-type]


@settings(max_examples=300, deadline=None)
@given(st.lists(st.floats(-1e7, 1e7, allow_nan=False), min_size=1, max_size=40), st.sampled_from([0, 3, 4]))
def test_gcode_counts_and_words(vals: list[float], decimals: int) -> None:
    q = _counts(np.array(vals), decimals)
    assert q is not None
    assert q.tolist() == [quantize(v, decimals) for v in vals]
    assert rows(_words("X", q, decimals)) == [" X" + counts_text(int(c), decimals) for c in q.tolist()]


def test_integers() -> None:
    assert rows(nt.integers(np.array([-1, 1, 0, -12, 345]))) == ["-1", "1", "0", "-12", "345"]
