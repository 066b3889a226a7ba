"""Array helpers: numpy's answers, without the modules numpy loads for them."""

from __future__ import annotations

import subprocess
import sys

import numpy as np

from voxfab._shared.arrays import unique


def test_unique_gives_numpys_values_and_rows() -> None:
    rng = np.random.default_rng(46)
    cases = [rng.integers(-5, 5, size=40), rng.integers(0, 2**40, size=7, dtype=np.int64),
             np.array([], dtype=np.int64), rng.integers(0, 3, size=(4, 5)),
             np.array([0.5, -0.0, 0.0, 2.0, 0.5, -3.25])]
    for values in cases:
        got, want = unique(values), np.unique(values)
        assert got.dtype == want.dtype and np.array_equal(got, want)
    rows = rng.integers(0, 3, size=(30, 3))
    assert np.array_equal(unique(rows, axis=0), np.unique(rows, axis=0))


def test_unique_leaves_numpy_ma_unloaded() -> None:
    code = ("import sys\nimport numpy as np\nfrom voxfab._shared.arrays import unique\n"
            "unique(np.array([3, 1, 3]))\nunique(np.array([[1, 2], [1, 2]]), axis=0)\n"
            "print('numpy.ma' in sys.modules)\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert r.stdout.split() == ["False"]
