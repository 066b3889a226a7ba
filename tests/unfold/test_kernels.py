"""The compiled search kernels: how they are compiled, and that they agree with their plain-Python copy."""

from __future__ import annotations

import numba
import numpy as np

from voxfab.shape import examples
from voxfab.unfold import _board, _growth, _tabroom, unfold, validate


def _kernels():
    for module in (_board, _growth, _tabroom):
        for name, value in vars(module).items():
            if isinstance(value, numba.core.registry.CPUDispatcher) and value.py_func.__module__ == module.__name__:
                yield f"{module.__name__}.{name}", value


def test_kernels_are_compiled_without_reference_counting():
    # Each call between kernels took and dropped a reference to every array it
    # passed (an atomic add each): most of the time of a growth step.
    kernels = dict(_kernels())
    assert {"voxfab.unfold._board.place", "voxfab.unfold._growth.grow", "voxfab.unfold._tabroom.anneal"} <= set(kernels)
    counted = [name for name, k in kernels.items() if k.targetoptions.get("_nrt", True)]
    assert counted == []


def test_the_hot_helpers_are_inlined_into_their_callers():
    for k in (_board.update, _board.seam_update, _board.fits, _board.randint, _board.forced):
        assert k.targetoptions.get("inline") == "always", k.py_func.__name__


def test_compiled_kernels_give_the_nets_of_the_plain_python_copy(monkeypatch):
    from voxfab.unfold import _searchboard

    grid = examples.tunnel_cube(5)  # 270 faces through a hole: folds, seams, annealing
    compiled = [unfold(grid, rng=s) for s in range(2)]
    monkeypatch.setattr(_searchboard, "_PURE_FACES", 10**6)
    plain = [unfold(grid, rng=s) for s in range(2)]
    assert [n.to_json() for n in plain] == [n.to_json() for n in compiled]
    for net in compiled:
        report = validate(grid, net)
        assert report.ok and report.seams_without_tab_room == 0
    assert np.unique([n.to_json() for n in compiled]).size == 2
