"""Fuzz every reader through ``voxfab info``: mutated valid files give a grid or one clean error line."""

from __future__ import annotations

import pytest
from _fuzz import check_outcome, mutated, put, run_cli, valid_files
from hypothesis import given, settings
from hypothesis import strategies as st

from voxfab import io

#: Every readable format; ".stl-ascii" is the text flavour of STL.
FORMATS = [".npy", ".npz", ".txt", ".vox", ".binvox", ".png", "/", ".stl", ".stl-ascii", ".obj", ".ply", ".3mf", ".glb"]


def test_every_reader_is_fuzzed():
    assert {f.split("-")[0] for f in FORMATS} == set(io.readable_formats())


@pytest.fixture(scope="module")
def corpus(tmp_path_factory):
    folder = tmp_path_factory.mktemp("valid")
    return folder, valid_files(folder)


@pytest.mark.parametrize("ext", FORMATS)
def test_mutated_files_read_or_fail_cleanly(corpus, ext):
    folder, valid = corpus
    outcomes = []

    meshes = (".stl", ".stl-ascii", ".obj", ".ply", ".3mf", ".glb")

    @settings(max_examples=20 if ext in meshes else 30, database=None, derandomize=True)
    @given(data=st.one_of(mutated(valid[ext]), st.binary(max_size=64)))
    def fuzz(data):
        path = put(folder / "fuzz", ext, data)
        outcomes.append(check_outcome(run_cli(["info", path, "--json"])))

    fuzz()
    # The corpus is hostile enough that most inputs fail, and valid enough that some read.
    assert any(o.code != 0 for o in outcomes)
