"""Seeds: the board's state is numpy's SeedSequence state, computed without numpy.random."""

from __future__ import annotations

import random

import numpy as np
import pytest

from voxfab._shared.rng import as_rng, check_seed, seed_state
from voxfab.errors import InvalidShapeError


def _numpy_state(entropy: object) -> int:
    return int(np.random.SeedSequence(entropy).generate_state(1, dtype=np.uint64)[0])


def test_seed_state_is_numpys_seed_sequence_for_every_kind_of_seed() -> None:
    draw = random.Random(46)
    # Word edges (0, 2**32 - 1, 2**32), seeds of several words, and the search's lists [seed, 7000 + k].
    seeds: list[object] = [0, 1, 7, 2**31 - 1, 2**32 - 1, 2**32, 2**63 - 1, 2**64 + 5, 2**200 + 3, np.int64(12)]
    seeds += [draw.getrandbits(draw.randint(1, 160)) for _ in range(400)]
    seeds += [[s, 7000 + k] for s in seeds[:60] for k in range(4)]
    seeds += [[], [0], [2**40, 3, 5, 7, 9, 11], (4, np.uint32(5))]
    for s in seeds:
        assert seed_state(s) == _numpy_state(s), s


def test_a_bad_seed_is_refused_in_one_line_by_every_entry() -> None:
    for bad in (-1, True, 1.5, "3", [2, -1]):
        with pytest.raises(InvalidShapeError, match="^seed: expected"):
            seed_state(bad)
        if not isinstance(bad, list):
            with pytest.raises(InvalidShapeError, match="^seed: expected"):
                as_rng(bad)
    assert check_seed(np.int32(9)) == 9 and type(check_seed(np.int32(9))) is int
