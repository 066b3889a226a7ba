"""NumPy ``.npy`` / ``.npz``: a bool or 0/1 array ``[x, y, z]``.

A ``.npz`` written by voxfab also keeps the shape's scale and colours, so a shape
read back is the object that was written: ``shape`` (bool grid), ``pitch_mm``
(a 0-D float), and for a coloured shape ``colour_index`` (uint8 grid) and
``palette`` (256 x 4 uint8).  A ``.npz`` with ``shape`` alone reads as before.
"""

from __future__ import annotations

import io
import zlib
from typing import TYPE_CHECKING

import numpy as np

from voxfab._shared.atomic import write_bytes
from voxfab._shared.typing import BoolGrid, PathLike
from voxfab._shared.validate import MAX_SIDE
from voxfab.errors import FormatError, InvalidShapeError, VoxfabError

from ._registry import ReadResult, register

if TYPE_CHECKING:
    import zipfile

    from voxfab.shape._colour import VoxelColours


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


_KEPT = ("pitch_mm", "colour_index", "palette")


def read_npz(path: PathLike) -> ReadResult:
    """Read a ``.npz`` archive: the array named ``shape``, or its only array, with its
    ``pitch_mm``, ``colour_index`` and ``palette`` when it keeps them."""
    import zipfile  # here: a .npy file, the common case, needs no archive

    try:
        with np.load(path, allow_pickle=False) as data:
            names = list(data.files)
            if not names:
                raise FormatError(f"{path}: the .npz archive holds no array")
            name = "shape" if "shape" in names else names[0]
            if name != "shape" and len([n for n in names if n not in _KEPT]) > 1:
                raise FormatError(f"{path}: several arrays {names} and none named 'shape'")
            for member_name in (name, "colour_index"):
                if member_name not in names:
                    continue
                zipped = f"{member_name}.npy" if f"{member_name}.npy" in data.zip.namelist() else member_name
                with data.zip.open(zipped) as member:
                    _check_header(member, path)
            arr = np.asarray(data[name])
            pitch = _pitch(data, path) if "pitch_mm" in names else None
            colours = _colours(data, arr, path) if "colour_index" in names else None
    except VoxfabError:
        raise
    # zipfile raises NotImplementedError for a member whose compression method
    # field is garbage, which a corrupt archive can have.
    except (ValueError, OSError, EOFError, NotImplementedError, zipfile.BadZipFile, zlib.error) as exc:
        raise FormatError(f"{path}: not a valid .npz file ({exc})") from None
    return ReadResult(arr, pitch, (), colours)


def _pitch(data: np.lib.npyio.NpzFile, path: PathLike) -> float:
    value = np.asarray(data["pitch_mm"])
    if value.shape != () or value.dtype.kind not in "iuf" or not (0 < float(value) < 1e6):
        raise FormatError(f"{path}: pitch_mm must be one positive number of millimetres, got {value!r}")
    return float(value)


def _colours(data: np.lib.npyio.NpzFile, grid: np.ndarray, path: PathLike) -> VoxelColours:
    from voxfab.shape._colour import VoxelColours

    index = np.asarray(data["colour_index"])
    palette = np.asarray(data["palette"]) if "palette" in data.files else None
    if palette is None or index.shape != grid.shape:
        raise FormatError(f"{path}: colour_index needs a palette and the shape's size {grid.shape}")
    return VoxelColours(index, palette)


def write_npy(grid: BoolGrid, path: PathLike) -> None:
    """Write a bool ``.npy`` file."""
    buf = io.BytesIO()
    np.save(buf, np.ascontiguousarray(grid, dtype=bool), allow_pickle=False)
    write_bytes(path, buf.getvalue())


def write_npz(grid: BoolGrid, path: PathLike, *, pitch: float | None = None,
              colours: VoxelColours | None = None) -> None:
    """Write a compressed ``.npz``: the array ``shape``, and the pitch and colours when given.

    The zip entries carry a fixed timestamp so equal shapes give equal bytes.
    """
    import zipfile

    members: dict[str, np.ndarray] = {"shape": np.ascontiguousarray(grid, dtype=bool)}
    if pitch is not None:
        members["pitch_mm"] = np.asarray(float(pitch))
    if colours is not None:
        members["colour_index"] = np.ascontiguousarray(colours.index)
        members["palette"] = np.ascontiguousarray(colours.palette)
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", compression=zipfile.ZIP_DEFLATED) as zf:
        for name, value in members.items():
            arr = io.BytesIO()
            np.save(arr, value, allow_pickle=False)
            info = zipfile.ZipInfo(f"{name}.npy", date_time=(1980, 1, 1, 0, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED
            zf.writestr(info, arr.getvalue())
    write_bytes(path, buf.getvalue())


register(".npy", reader=read_npy, writer=write_npy)
register(".npz", reader=read_npz, writer=write_npz)
