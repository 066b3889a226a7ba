"""Tests of voxfab.generate: growth, random maker parameters, candidates by seed."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import ndimage

from voxfab.digitize import get_maker, random_makers
from voxfab.errors import InvalidShapeError
from voxfab.generate import (
    candidate,
    generators,
    growth,
    parse_volume_range,
    symmetric_key,
    volume_bins,
)
from voxfab.shape import GRID_SIDE, canonical_key, crop, symmetries, well_formed_reasons


@pytest.mark.parametrize("volume", [25, 26, 100, 625, 3000])
def test_growth_is_one_piece_of_the_volume_spanning_z(volume: int) -> None:
    for seed in range(5):
        g = growth(seed, volume, wander=0.5)
        assert g.shape == (GRID_SIDE,) * 3 and g.dtype == bool
        assert int(g.sum()) == volume
        # Independent check of face-connectivity: scipy's labelling with the 6-neighbourhood.
        _, pieces = ndimage.label(g, structure=ndimage.generate_binary_structure(3, 1))
        assert pieces == 1
        assert g[:, :, 0].any() and g[:, :, -1].any()
        assert well_formed_reasons(g) == []


def test_growth_volume_25_is_the_straight_column() -> None:
    g = growth(7, 25, wander=1.0)
    assert int(g.sum()) == 25 and np.count_nonzero(g.any(axis=2)) == 1


def test_growth_is_reproducible_and_varies_with_the_seed() -> None:
    assert np.array_equal(growth(11, 300), growth(11, 300))
    grids = [growth(s, 300).tobytes() for s in range(20)]
    assert len(set(grids)) == 20


def test_growth_rejects_impossible_volumes() -> None:
    for v in (24, GRID_SIDE**3 + 1):
        with pytest.raises(InvalidShapeError, match="volume"):
            growth(1, v)


@pytest.mark.parametrize("generator", generators())
def test_candidates_are_reproducible_by_seed_and_index(generator: str) -> None:
    a = [candidate(generator, 5, i) for i in range(4)]
    b = [candidate(generator, 5, i) for i in (3, 2, 1, 0)][::-1]  # any order: each depends on (seed, index)
    for x, y in zip(a, b):
        assert (x is None) == (y is None)
        if x is not None and y is not None:
            assert np.array_equal(x.grid, y.grid) and x.params == y.params and x.generator == y.generator


@pytest.mark.parametrize("generator", random_makers())
def test_maker_candidates_are_remade_from_their_params(generator: str, tmp_path: Path) -> None:
    made = [c for c in (candidate(generator, 2, i) for i in range(6)) if c is not None]
    assert len(made) >= 4
    assert sum(not well_formed_reasons(c.grid) for c in made) >= 3
    for c in made:
        assert c.generator == generator
        again = get_maker(generator)(base_dir=tmp_path, **c.params)
        assert np.array_equal(np.asarray(again, bool), c.grid)
    assert len({c.grid.tobytes() for c in made}) == len(made)


def test_mix_draws_several_generators() -> None:
    kinds = {c.generator for c in (candidate("mix", 9, i) for i in range(40)) if c is not None}
    assert "growth" in kinds and len(kinds) >= 3


def test_growth_candidate_aims_inside_the_volume_range() -> None:
    for i in range(20):
        c = candidate("growth", 3, i, volume=(200, 260))
        assert c is not None and 200 <= int(c.grid.sum()) <= 260
        assert c.params["volume"] == int(c.grid.sum())


def test_parse_volume_range() -> None:
    assert parse_volume_range("25:100") == (25, 100)
    assert parse_volume_range("300") == (300, 300)
    assert parse_volume_range(":50") == (1, 50)
    assert parse_volume_range("50:") == (50, GRID_SIDE**3)
    for bad in ("a:b", "100:50", "0:5", "1:99999"):
        with pytest.raises(InvalidShapeError, match="volume"):
            parse_volume_range(bad)


def test_volume_bins_count_every_volume_in_round_ranges() -> None:
    volumes = [25, 26, 99, 100, 101, 250, 612]
    bins = volume_bins(volumes)
    assert sum(n for _, _, n in bins) == len(volumes)
    widths = {hi - lo + 1 for lo, hi, _ in bins}
    assert len(widths) == 1 and widths.pop() in (50, 100)
    for lo, hi, n in bins:
        assert n == sum(lo <= v <= hi for v in volumes)
    assert volume_bins([]) == []
    assert volume_bins([40]) == [(40, 40, 1)]


@settings(max_examples=80)
@given(st.tuples(st.integers(1, 6), st.integers(1, 6), st.integers(1, 6)).flatmap(
    lambda s: st.lists(st.booleans(), min_size=s[0] * s[1] * s[2], max_size=s[0] * s[1] * s[2]).map(
        lambda bits: np.array(bits, dtype=bool).reshape(s))))
def test_compiled_symmetric_key_is_the_canonical_key(grid: np.ndarray) -> None:
    if not grid.any():
        return
    for h in symmetries(grid, reflections=True)[::7]:
        assert symmetric_key(crop(h)) == canonical_key(grid, symmetric=True)


def test_compiled_symmetric_key_on_grown_and_symmetric_shapes() -> None:
    grids = [crop(growth(s, 40 + 37 * s)) for s in range(30)] + [np.ones((3, 3, 25), bool), np.ones((5, 5, 5), bool)]
    for g in grids:
        keys = {symmetric_key(crop(h)) for h in symmetries(g, reflections=True)}
        assert keys == {canonical_key(g, symmetric=True)}


def test_growth_candidate_outside_the_grid_volumes() -> None:
    with pytest.raises(InvalidShapeError, match="volume"):
        candidate("growth", 1, 0, volume=(1, 20))
