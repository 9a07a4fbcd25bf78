"""The numpy text renderer of the pulse writers (:mod:`cncc.backends.pulses.text`) against
Python's own formatting."""

from __future__ import annotations

import numpy as np
import pytest

from cncc.backends.pulses.text import choice, decimal, literal, render, signed, stamped

EDGES = [0, 1, 9, 10, 99, 100, 9999, 10_000, 10_001, 99_999_999, 100_000_000, 123_456_789_012, 2**62]


def test_decimal_and_signed_match_str() -> None:
    rng = np.random.default_rng(4)
    v = np.concatenate([np.array(EDGES, np.int64), rng.integers(0, 10**15, 2000)])
    assert render([decimal(v), literal(b"\n", v.size)]) == "".join(f"{x}\n" for x in v.tolist()).encode()
    w = np.concatenate([v, -v[1:]])
    assert render([signed(w), literal(b",", w.size)]) == "".join(f"{x}," for x in w.tolist()).encode()
    with pytest.raises(ValueError):
        decimal(np.array([-1]))


def test_choice_of_unequal_strings() -> None:
    idx = np.array([0, 2, 1, 1, 0])
    opts = [b"step", b"dir", b"backlash"]
    assert render([choice(opts, idx), literal(b";", idx.size)]) == b"step;backlash;dir;dir;step;"


def test_stamped_rows_as_a_vcd_body() -> None:
    rng = np.random.default_rng(5)
    t = np.sort(rng.integers(0, 10**12, 5000))
    t[10:14] = t[10]  # equal times share one stamp
    new = np.ones(t.size, bool)
    new[1:] = t[1:] != t[:-1]
    new[0] = False  # the previous batch ended at this time
    tokens = [b"0!\n", b"1!\n", b'0"\n', b'1"\n']
    code = rng.integers(0, 4, t.size)
    want = "".join((f"#{a}\n" if n else "") + tokens[c].decode()
                   for a, n, c in zip(t.tolist(), new.tolist(), code.tolist(), strict=True))
    assert stamped(t, new, tokens, code) == want.encode()
    assert stamped(t[:0], new[:0], tokens, code[:0]) == b""
