"""Compile the net engine once, before worker processes start.

numba caches compiled code on disk: warmed here, the Dask workers load it
instead of each compiling it inside its first task (a minute on a cold cache).
"""

from __future__ import annotations

import numpy as np
import pytest


@pytest.fixture(scope="session", autouse=True)
def _warm_net_engine() -> None:
    from voxfab.unfold import unfold

    unfold(np.ones((1, 1, 3), dtype=bool), rng=0)
