"""The smoke runs of the second half of the scripts in ``bench/`` (the first half: ``test_benches.py``)."""

from __future__ import annotations

import pytest
from _bench_smoke import HALVES, Run, check_smoke, smoke_all


@pytest.fixture(scope="module")
def smoke_runs() -> dict[str, Run]:
    """The smoke runs of the second half of the benches, started once for the module."""
    return smoke_all(HALVES[1])


@pytest.mark.parametrize("name", HALVES[1])
def test_bench_runs_in_smoke_mode(name: str, smoke_runs: dict[str, Run]) -> None:
    check_smoke(name, smoke_runs[name])
