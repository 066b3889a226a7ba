"""Optional parts: a feature whose package is missing fails first, with the install command."""

from __future__ import annotations

import importlib.util

import numpy as np
import pytest

from voxfab._shared.deps import has_extra, require_extra
from voxfab.cli import main
from voxfab.errors import MissingDependencyError
from voxfab.shape import examples


@pytest.fixture
def no_cad(monkeypatch):
    """Behave as an install without the ``cad`` extra (build123d not found)."""
    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec", lambda name, *a: None if name == "build123d" else real(name, *a))


def test_missing_extra_names_the_feature_and_the_install_command(no_cad):
    assert not has_extra("cad")
    with pytest.raises(MissingDependencyError, match=r"^--step needs build123d, an optional part of voxfab: "
                                                     r"pip install 'voxfab\[cad\]'$"):
        require_extra("cad", "--step")


@pytest.mark.parametrize(("argv", "feature"), [
    (["mesh", "b.npy", "-o", "b.3mf", "--label", "HI"], "--label"),
    (["slices", "b.npy", "-o", "plates", "--step"], "step"),
])
def test_cad_features_refuse_before_any_work_without_the_extra(no_cad, tmp_path, monkeypatch, capsys, argv, feature):
    monkeypatch.chdir(tmp_path)
    np.save("b.npy", examples.box(3, 3, 3))
    assert main(argv) == 9
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and feature in err[0] and "pip install 'voxfab[cad]'" in err[0]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["b.npy"]


def test_cad_extra_is_found_when_installed():
    assert has_extra("cad") == (importlib.util.find_spec("build123d") is not None)
