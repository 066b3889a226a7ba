"""The one seeding convention: explicit seeds, never numpy's global state."""

from __future__ import annotations

import numpy as np

from voxfab.errors import InvalidShapeError


def as_rng(rng: np.random.Generator | int) -> np.random.Generator:
    """Return a Generator for ``rng`` (an int seed or a Generator)."""
    if isinstance(rng, np.random.Generator):
        return rng
    if isinstance(rng, (int, np.integer)) and not isinstance(rng, bool):
        if rng < 0:
            raise InvalidShapeError(f"seed: expected an integer >= 0, got {rng}")
        return np.random.default_rng(int(rng))
    raise InvalidShapeError(f"seed: expected an int or numpy Generator, got {type(rng).__name__}")
