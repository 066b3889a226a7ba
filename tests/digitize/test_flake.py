"""k-flake digitization: vertex sets, reference counts, separation, thickness law, evaluation rule."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from scipy import ndimage

import voxfab.digitize._flake as flake_mod
from voxfab.digitize import digitize, flake_vertices, solid, surface
from voxfab.errors import InvalidShapeError


def adjacency(n: int, k: int) -> np.ndarray:
    """Structuring element of k-adjacency: ‖d‖∞ = 1 and ‖d‖₁ <= n - k."""
    st = np.zeros((3,) * n, dtype=bool)
    for d in itertools.product((-1, 0, 1), repeat=n):
        if sum(map(abs, d)) <= n - k:
            st[tuple(x + 1 for x in d)] = True
    return st


def tunnels(surf: np.ndarray, inside: np.ndarray, k: int) -> bool:
    """Whether some k-path joins an interior voxel to an exterior one avoiding the surface."""
    n = surf.ndim
    outside = ~(surf | inside)
    labels, _ = ndimage.label(~surf, structure=adjacency(n, k))
    return bool(np.intersect1d(labels[inside], labels[outside]).size)


def centred(f, n: int, half: int, k: int) -> tuple[np.ndarray, np.ndarray]:
    return digitize(f, (2 * half + 1,) * n, k, origin=[-half] * n)


@pytest.mark.parametrize("n", [2, 3, 4])
def test_flake_vertex_sets(n):
    for k in range(n):
        v = flake_vertices(n, k)
        assert len(v) == math.comb(n, k) * 2 ** (n - k)
        assert np.all(np.count_nonzero(v == 0, axis=1) == k)
        assert np.all(np.isin(np.abs(v), (0.0, 0.5)))
        assert len(np.unique(v, axis=0)) == len(v)


def test_sphere_reference_counts():
    f = lambda x, y, z: x * x + y * y + z * z - 100  # noqa: E731
    assert [int(surface(f, (25,) * 3, k, origin=(-12,) * 3).sum()) for k in range(3)] == [1898, 1610, 1026]


def test_torus_reference_counts():
    f = lambda x, y, z: (np.sqrt(x * x + y * y) - 10) ** 2 + z * z - 16  # noqa: E731
    assert [int(surface(f, (31, 31, 11), k, origin=(-15, -15, -5)).sum()) for k in range(3)] == [2288, 1984, 1368]


def test_4d_reference_counts():
    f = lambda x, y, z, w: (np.sqrt(x * x + y * y + z * z) - 6) ** 2 + w * w - 4  # noqa: E731
    got = [int(surface(f, (19, 19, 19, 7), k, origin=(-9, -9, -9, -3)).sum()) for k in range(4)]
    assert got == [9760, 8928, 7528, 4916]


CLOSED = {
    2: lambda x, y: (x / 9.3) ** 2 + (y / 6.1) ** 2 - 1,
    3: lambda x, y, z: (np.sqrt(x * x + y * y) - 7.2) ** 2 + z * z - 2.9**2,
    4: lambda x, y, z, w: (np.sqrt(x * x + y * y + z * z) - 5.3) ** 2 + w * w - 2.2**2,
}
HALF = {2: 11, 3: 11, 4: 8}


@pytest.mark.parametrize("n", [2, 3, 4])
def test_separation_guarantee_and_its_limit(n):
    for k in range(n):
        surf, inside = centred(CLOSED[n], n, HALF[n], k)
        assert inside.any() and (~(surf | inside)).any()
        assert not tunnels(surf, inside, k), f"F_{k} must be {k}-separating in {n}D"
        if k > 0:
            assert tunnels(surf, inside, k - 1), f"F_{k} should not be {k - 1}-separating in {n}D"


@pytest.mark.parametrize("n", [2, 3, 4])
def test_separation_holds_for_any_function(n):
    # a wild, discontinuous f: the guarantee is combinatorial (one value per half-point)
    def f(*c):
        s = sum((i + 1.37) * np.asarray(x) * 12.9898 for i, x in enumerate(c))
        return np.sin(s * 43758.5453) - 0.1

    side = {2: 30, 3: 14, 4: 7}[n]
    for k in range(n):
        surf, inside = digitize(f, (side,) * n, k, origin=[-3.3] * n, step=0.77)
        outside = ~(surf | inside)
        grown = ndimage.binary_dilation(inside, structure=adjacency(n, k))
        assert not (grown & outside).any()


@pytest.mark.parametrize("n", [2, 3, 4])
def test_hyperplane_thickness_law(n):
    rng = np.random.default_rng(7 + n)
    side = {2: 21, 3: 11, 4: 7}[n]
    for _ in range(3):
        a = rng.normal(size=n)
        c = rng.normal()
        f = lambda *x, a=a, c=c: sum(ai * xi for ai, xi in zip(a, x)) + c  # noqa: E731
        grids = np.meshgrid(*[np.arange(side) - side // 2] * n, indexing="ij")
        value = sum(ai * g for ai, g in zip(a, grids)) + c
        for k in range(n):
            omega = np.sort(np.abs(a))[::-1][: n - k].sum()
            expect = np.abs(value) <= omega / 2
            got = surface(f, (side,) * n, k, origin=[-(side // 2)] * n)
            assert np.array_equal(got, expect)
        # naive (k = n-1, ‖a‖∞) and standard (k = 0, ‖a‖₁) planes
        assert np.array_equal(
            surface(f, (side,) * n, n - 1, origin=[-(side // 2)] * n), np.abs(value) <= np.abs(a).max() / 2
        )
        assert np.array_equal(surface(f, (side,) * n, 0, origin=[-(side // 2)] * n), np.abs(value) <= np.abs(a).sum() / 2)


def test_zero_counts_as_both_signs():
    # plane x = 1/2 with the 2-flake (thin): the closed convention gives 2 layers
    got = surface(lambda x, y, z: x - 0.5, (4, 3, 3), 2)
    assert got[0].all() and got[1].all() and not got[2:].any()


@pytest.mark.parametrize("k", [0, 1, 2])
def test_each_half_point_is_evaluated_once(monkeypatch, k):
    monkeypatch.setattr(flake_mod, "_SLAB_POINTS", 50)  # many slabs: the shared plane is carried over
    seen = []

    def f(x, y, z):
        b = np.broadcast_arrays(x, y, z)
        seen.append(np.stack([a.ravel() for a in b], axis=1))
        return b[0] * b[0] + b[1] * b[1] + b[2] * b[2] - 9.5

    shape = (7, 8, 9)
    got = surface(f, shape, k, origin=(-3, -4, -4))
    pts = np.vstack(seen)
    assert len(np.unique(pts, axis=0)) == len(pts)
    needed = sum(
        math.prod(s if d in odd else s + 1 for d, s in enumerate(shape)) for odd in itertools.combinations(range(3), k)
    )
    assert len(pts) == needed
    monkeypatch.setattr(flake_mod, "_SLAB_POINTS", 1 << 21)
    assert np.array_equal(got, surface(lambda x, y, z: x * x + y * y + z * z - 9.5, shape, k, origin=(-3, -4, -4)))


def test_origin_and_step_place_voxels():
    f = lambda x, y, z: (x - 2.0) ** 2 + (y + 1.0) ** 2 + z * z - 4.0  # noqa: E731
    a = solid(f, (9, 9, 9), 0, origin=(-2.0, -5.0, -4.0), step=1.0)
    b = solid(lambda x, y, z: x * x + y * y + z * z - 1.0, (9, 9, 9), 0, origin=(-2.0, -2.0, -2.0), step=0.5)
    assert np.array_equal(a, b)
    assert a[4, 4, 4]


def test_solid_is_surface_plus_interior():
    f = lambda x, y, z: x * x + y * y + z * z - 30  # noqa: E731
    s, inside = digitize(f, (15,) * 3, 1, origin=(-7,) * 3)
    assert np.array_equal(solid(f, (15,) * 3, 1, origin=(-7,) * 3), s | inside)
    assert not (s & inside).any()
    assert inside[7, 7, 7] and not s[7, 7, 7]


def test_nan_is_outside():
    f = lambda x, y: np.where(x > 0, np.nan, x * x + y * y - 4)  # noqa: E731
    s, inside = digitize(f, (9, 9), 0, origin=(-4, -4))
    assert not inside[5:].any()


@pytest.mark.parametrize(
    ("args", "word"),
    [
        (((5, 5, 5), 3), "k"),
        (((5,), 0), "shape"),
        (((5, 0, 5), 0), "shape"),
        (((5, 5), 0, (0, 0, 0)), "origin"),
        (((5, 5), 0, None, -1.0), "step"),
    ],
)
def test_bad_arguments_name_the_input(args, word):
    with pytest.raises(InvalidShapeError, match=word):
        surface(lambda *c: c[0], *args)


@pytest.mark.parametrize("k", [0, 1, 2])
def test_sector_crop_against_analytic_cut_points(k):
    # torus R = 2, a = 0.8 cut to its half y >= 0: the end rays lie in the plane y = 0,
    # where each flake half-segment's crossing has a closed form
    def f(x, y, z):
        return (np.hypot(x, y) - 2.0) ** 2 + z * z - 0.64

    shape, origin, step = (29, 29, 13), np.array([-3.1, -3.05, -1.2]), 0.23
    got = flake_mod.digitize_sector(f, lambda x, y, z: (x, y), (0.0, math.pi), shape, k, origin, step)
    axes = np.meshgrid(*[origin[d] + np.arange(shape[d]) * step for d in range(3)], indexing="ij")
    le, ge = np.zeros(shape, dtype=bool), np.zeros(shape, dtype=bool)
    full_le, full_ge = np.zeros(shape, dtype=bool), np.zeros(shape, dtype=bool)
    for v in flake_vertices(3, k):
        tip = [axes[d] + v[d] * step for d in range(3)]
        val = f(*tip)
        full_le |= val <= 0
        full_ge |= val >= 0
        keep = tip[1] >= 0
        le |= keep & (val <= 0)
        ge |= keep & (val >= 0)
        if v[1] != 0:
            t = -axes[1] / (v[1] * step)
            cut = [axes[d] + t * v[d] * step for d in range(3)]
            ok = (t >= 0) & (t <= 1)
            cval = f(cut[0], np.zeros(shape), cut[2])
            le |= ok & (cval <= 0)
            ge |= ok & (cval >= 0)
    want = le & ge & full_le & full_ge
    assert want.sum() > 200
    assert np.array_equal(got, want)
    # the half torus: nothing beyond half a voxel below its cut plane, both of its ends reached
    ys = axes[1][got]
    assert ys.min() >= -0.5 * step and ys.min() < step


def test_full_sector_is_the_plain_flake_test():
    def f(x, y, z):
        return x * x + y * y + z * z - 9.0

    s, _ = digitize(f, (15, 15, 15), 1, (-7, -7, -7), 1.0)
    assert np.array_equal(flake_mod.digitize_sector(f, lambda x, y, z: (x, y), (1.0, 1.0 + 2 * math.pi),
                                                   (15, 15, 15), 1, (-7, -7, -7), 1.0), s)


@pytest.mark.parametrize("arc", [(10, 10), (0, 400), ("a", 1), (1,), (math.nan, 3)])
def test_bad_arcs(arc):
    with pytest.raises(InvalidShapeError, match="arc"):
        flake_mod.check_arc(arc)
