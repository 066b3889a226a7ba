"""NumPy .npy / .npz: dtypes accepted and refused, headers checked before loading."""

from __future__ import annotations

import io as pyio
import zipfile

import numpy as np
import pytest

from voxfab import io
from voxfab.errors import FormatError, InvalidShapeError
from voxfab.shape import examples


@pytest.mark.parametrize("ext", [".npy", ".npz"])
def test_round_trip_and_deterministic_bytes(tmp_path, ext):
    grid = examples.vase()
    io.write(grid, tmp_path / f"a{ext}")
    io.write(grid.copy(), tmp_path / f"b{ext}")
    assert (tmp_path / f"a{ext}").read_bytes() == (tmp_path / f"b{ext}").read_bytes()
    result = io.read(tmp_path / f"a{ext}")
    assert result.grid.dtype == bool and np.array_equal(result.grid, grid)


def test_written_npz_holds_one_bool_array_named_shape(tmp_path):
    grid = examples.ball(3)
    io.write(grid, tmp_path / "a.npz")
    with np.load(tmp_path / "a.npz") as data:
        assert data.files == ["shape"]
        assert data["shape"].dtype == bool and np.array_equal(data["shape"], grid)
    with zipfile.ZipFile(tmp_path / "a.npz") as zf:
        assert [i.date_time for i in zf.infolist()] == [(1980, 1, 1, 0, 0, 0)]


@pytest.mark.parametrize("dtype", [np.uint8, np.int64, np.float32])
def test_zero_one_arrays_of_other_dtypes(tmp_path, dtype):
    grid = examples.ball(2)
    np.save(tmp_path / "a.npy", grid.astype(dtype))
    np.savez(tmp_path / "a.npz", anything=grid.astype(dtype))
    assert np.array_equal(io.read(tmp_path / "a.npy").grid, grid)
    assert np.array_equal(io.read(tmp_path / "a.npz").grid, grid)


@pytest.mark.parametrize(
    ("array", "message"),
    [
        (np.full((2, 2, 2), 2, dtype=np.uint8), "only 0 and 1"),
        (np.ones((2, 2), dtype=bool), "expected a 3D grid"),
        (np.zeros((2, 2, 2), dtype=bool), "empty"),
        (np.ones((2, 2, 2), dtype=np.complex64), "dtype complex64"),
        (np.array([["a"]]).reshape(1, 1, 1), "dtype <U1"),
        (np.ones((257, 1, 1), dtype=bool), "over the limit of 256"),
    ],
)
def test_wrong_arrays_give_invalid_shape(tmp_path, array, message):
    np.save(tmp_path / "a.npy", array)
    with pytest.raises(InvalidShapeError, match=message):
        io.read(tmp_path / "a.npy")
    np.savez(tmp_path / "a.npz", shape=array)
    with pytest.raises(InvalidShapeError, match=message):
        io.read(tmp_path / "a.npz")


def test_huge_header_is_refused_before_allocating(tmp_path):
    buf = pyio.BytesIO()
    np.lib.format.write_array_header_1_0(buf, {"descr": "|b1", "fortran_order": False, "shape": (10**5,) * 3})
    (tmp_path / "huge.npy").write_bytes(buf.getvalue() + b"\x01" * 64)
    with pytest.raises(InvalidShapeError, match="huge.npy: grid 100000x100000x100000 is over the limit"):
        io.read(tmp_path / "huge.npy")


def test_pickled_objects_are_refused(tmp_path):
    np.save(tmp_path / "obj.npy", np.array([{"a": 1}], dtype=object).reshape(1, 1, 1), allow_pickle=True)
    with pytest.raises(InvalidShapeError, match="dtype object"):
        io.read(tmp_path / "obj.npy")


def test_npz_with_several_arrays_and_none_named_shape(tmp_path):
    np.savez(tmp_path / "two.npz", a=np.ones((1, 1, 1), bool), b=np.ones((1, 1, 1), bool))
    with pytest.raises(FormatError, match=r"two.npz: several arrays \['a', 'b'\]"):
        io.read(tmp_path / "two.npz")
    np.savez(tmp_path / "none.npz")
    with pytest.raises(FormatError, match="holds no array"):
        io.read(tmp_path / "none.npz")
