"""Hardening 3, class 6: the exact strategy's refusals name what was proved.

A torus has one-piece nets, but its handle rules out every zipper net: the refusal of
``--zipper`` must say "no zipper net", never "no one-piece net".  The random engine
finds a one-piece net of each torus here, the independent witness that the old
sentence was false.
"""

from __future__ import annotations

import json
import pickle
from pathlib import Path

import numpy as np
import pytest
from _fuzz import check_outcome, refused, run_cli

from voxfab.errors import NoNetExistsError
from voxfab.fabricate.hunt import HuntOptions, fabricate_hunt
from voxfab.shape import VoxelShape, examples
from voxfab.unfold import unfold, validate

pytest.importorskip("ortools")


@pytest.mark.parametrize(("radius", "tube"), [(6, 2), (5, 2), (7, 3)])
def test_a_torus_is_refused_a_zipper_net_not_a_net(tmp_path: Path, radius: float, tube: float) -> None:
    torus = examples.torus(radius, tube)
    np.save(tmp_path / "t.npy", torus)
    line = refused(["net", tmp_path / "t.npy", "--strategy", "exact", "--zipper", "-o", tmp_path / "z.json"])
    assert "no zipper net of this shape exists, in any box (proved)" in line and "has a handle" in line
    assert "one-piece" not in line
    assert not (tmp_path / "z.json").exists()
    # the witness: a one-piece net of the same torus, refolded by the validator
    o = check_outcome(run_cli(["net", tmp_path / "t.npy", "-o", tmp_path / "n.json"]))
    assert o.code == 0
    validate(torus, unfold(torus, rng=0))


def test_a_zipper_in_a_box_too_small_names_the_zipper_and_the_box() -> None:
    cube = examples.box(2, 2, 2)  # 24 faces
    with pytest.raises(NoNetExistsError, match=r"^no zipper net of this shape fits 4x5 faces \(proved\)$"):
        unfold(cube, rng=0, strategy="exact", zipper=True, fit=(4, 5), timeout=20)
    with pytest.raises(NoNetExistsError, match=r"^no one-piece net of this shape fits 4x5 faces \(proved\)$"):
        unfold(cube, rng=0, strategy="exact", fit=(4, 5), timeout=20)


def test_the_hunt_records_what_it_proved(tmp_path: Path) -> None:
    made = fabricate_hunt(VoxelShape(examples.torus(6, 2)), HuntOptions(timeout=10, exact_timeout=10,
                                                                         zipper_timeout=10),
                          tmp_path, name="torus", seed=0)
    record = json.loads((tmp_path / "hunt.json").read_text())
    assert made.files and record["net"] in ("random", "exact") and record["zipper"] == "none"
    said = " ".join(record["why"]) if isinstance(record["why"], list) else record["why"]
    assert "no zipper net of this shape exists" in said and "no one-piece net" not in said


@pytest.mark.parametrize("error", [NoNetExistsError(3, 4), NoNetExistsError(None, None, "a handle", "zipper net"),
                                   NoNetExistsError(5, 5, kind="zipper net")])
def test_a_proof_crosses_processes_unchanged(error: NoNetExistsError) -> None:
    again = pickle.loads(pickle.dumps(error))
    assert str(again) == str(error) and again.box == error.box and again.kind == error.kind
