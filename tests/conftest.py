"""Test-wide settings.

Hypothesis runs derandomized (a fixed example sequence per test) when ``CI`` is set, so
a CI run is reproducible; locally it explores new examples on every run.  No deadline:
the machine may be shared, and timing is measured by the benchmarks, not by tests.
"""

from __future__ import annotations

import os

import pytest
from hypothesis import settings

settings.register_profile("ci", derandomize=True, deadline=None, print_blob=True)
settings.register_profile("dev", deadline=None, print_blob=True)
settings.load_profile("ci" if os.environ.get("CI") else "dev")


@pytest.fixture
def small_chunks(monkeypatch: pytest.MonkeyPatch) -> None:
    """The fast path's batches cut small, so batch boundaries fall everywhere in short programs."""
    from cncc.frontend import fastbatch

    monkeypatch.setattr(fastbatch, "STREAK", 2)
    monkeypatch.setattr(fastbatch, "MIN_CHUNK", 64)
    monkeypatch.setattr(fastbatch, "MAX_CHUNK", 512)
