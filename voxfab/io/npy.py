"""NumPy ``.npy`` / ``.npz``: a bool or 0/1 array ``[x, y, z]``."""

from __future__ import annotations

import io
import zipfile
import zlib

import numpy as np

from voxfab._shared.atomic import write_bytes
from voxfab._shared.typing import BoolGrid, PathLike
from voxfab._shared.validate import MAX_SIDE
from voxfab.errors import FormatError, InvalidShapeError, VoxfabError

from ._registry import ReadResult, register


def _check_header(fh: io.BufferedIOBase | zipfile.ZipExtFile, path: PathLike) -> None:
    """Check the array header before loading: a corrupt or hostile header must not
    make numpy allocate terabytes."""
    try:
        version = np.lib.format.read_magic(fh)
        if version == (1, 0):
            shape, _, dtype = np.lib.format.read_array_header_1_0(fh)
        else:
            shape, _, dtype = np.lib.format.read_array_header_2_0(fh)
    except Exception as exc:  # noqa: BLE001
        # numpy parses the header text as a Python literal: a corrupt one raises
        # ValueError, SyntaxError, tokenize.TokenError... all mean "not an .npy".
        raise FormatError(f"{path}: not a valid .npy header ({type(exc).__name__})") from None
    if len(shape) == 3 and max(shape) > MAX_SIDE:
        raise InvalidShapeError(
            f"{path}: grid {'x'.join(map(str, shape))} is over the limit of {MAX_SIDE} voxels per side"
        )
    if len(shape) != 3:
        raise InvalidShapeError(f"{path}: expected a 3D grid, got {len(shape)}D with shape {shape}")
    if dtype.kind not in "biuf":
        raise InvalidShapeError(f"{path}: expected a bool or 0/1 array, got dtype {dtype}")


def read_npy(path: PathLike) -> ReadResult:
    """Read a ``.npy`` file holding one 3D bool or 0/1 array (no pickles)."""
    try:
        with open(path, "rb") as fh:
            _check_header(fh, path)
        arr = np.load(path, allow_pickle=False)
    except VoxfabError:
        raise
    except (ValueError, OSError, EOFError) as exc:
        raise FormatError(f"{path}: not a valid .npy file ({exc})") from None
    return ReadResult(np.asarray(arr))


def read_npz(path: PathLike) -> ReadResult:
    """Read a ``.npz`` archive: the array named ``shape``, or its only array."""
    try:
        with np.load(path, allow_pickle=False) as data:
            names = list(data.files)
            if not names:
                raise FormatError(f"{path}: the .npz archive holds no array")
            name = "shape" if "shape" in names else names[0]
            if name != "shape" and len(names) > 1:
                raise FormatError(f"{path}: several arrays {names} and none named 'shape'")
            member_name = f"{name}.npy" if f"{name}.npy" in data.zip.namelist() else name
            with data.zip.open(member_name) as member:
                _check_header(member, path)
            arr = np.asarray(data[name])
    except VoxfabError:
        raise
    # zipfile raises NotImplementedError for a member whose compression method
    # field is garbage, which a corrupt archive can have.
    except (ValueError, OSError, EOFError, NotImplementedError, zipfile.BadZipFile, zlib.error) as exc:
        raise FormatError(f"{path}: not a valid .npz file ({exc})") from None
    return ReadResult(arr)


def write_npy(grid: BoolGrid, path: PathLike) -> None:
    """Write a bool ``.npy`` file."""
    buf = io.BytesIO()
    np.save(buf, np.ascontiguousarray(grid, dtype=bool), allow_pickle=False)
    write_bytes(path, buf.getvalue())


def write_npz(grid: BoolGrid, path: PathLike) -> None:
    """Write a compressed ``.npz`` with one array named ``shape``.

    The zip entry carries a fixed timestamp so equal shapes give equal bytes.
    """
    arr = io.BytesIO()
    np.save(arr, np.ascontiguousarray(grid, dtype=bool), allow_pickle=False)
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", compression=zipfile.ZIP_DEFLATED) as zf:
        info = zipfile.ZipInfo("shape.npy", date_time=(1980, 1, 1, 0, 0, 0))
        info.compress_type = zipfile.ZIP_DEFLATED
        zf.writestr(info, arr.getvalue())
    write_bytes(path, buf.getvalue())


register(".npy", reader=read_npy, writer=write_npy)
register(".npz", reader=read_npz, writer=write_npz)
