"""NumPy ``.npy`` / ``.npz``: a bool or 0/1 array ``[x, y, z]``."""

from __future__ import annotations

import io
import zipfile

import numpy as np

from voxfab._shared.atomic import write_bytes
from voxfab._shared.typing import BoolGrid, PathLike
from voxfab.errors import FormatError

from ._registry import ReadResult, register


def read_npy(path: PathLike) -> ReadResult:
    """Read a ``.npy`` file holding one 3D bool or 0/1 array (no pickles)."""
    try:
        arr = np.load(path, allow_pickle=False)
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
            arr = np.asarray(data[name])
    except (ValueError, OSError, EOFError, zipfile.BadZipFile) as exc:
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
