"""Mesh file formats, found by file extension.

Each format module has ``EXTENSION``, ``DESCRIPTION``, ``to_bytes(mesh, *, name)``
and ``read(path) -> MeshData`` (STL, which has no vertex identity, reads back
one vertex per triangle corner).  A format whose colours live in a second file
(OBJ's material library) also has ``MATERIAL_EXTENSION``, ``MATERIAL_DESCRIPTION``
and ``material_bytes(mesh)``, and its ``to_bytes`` takes that file's name.
STL has no colour: a coloured mesh is written in one.
"""

from __future__ import annotations

import importlib
from pathlib import Path
from types import ModuleType

from voxfab._shared.atomic import write_bytes
from voxfab._shared.typing import PathLike
from voxfab.errors import FormatError, UnknownFormatError

from .._data import MeshData

#: Extension → module implementing the format.
FORMATS: dict[str, str] = {
    ".3mf": "voxfab.fabricate.mesh.formats.threemf",
    ".stl": "voxfab.fabricate.mesh.formats.stl",
    ".obj": "voxfab.fabricate.mesh.formats.obj",
    ".glb": "voxfab.fabricate.mesh.formats.glb",
    ".ply": "voxfab.fabricate.mesh.formats.ply",
}

__all__ = ["FORMATS", "format_for", "write_mesh", "read_mesh", "mesh_extensions"]


def mesh_extensions() -> list[str]:
    """The known extensions, e.g. ``['.3mf', '.glb', '.obj', '.stl']``."""
    return sorted(FORMATS)


def format_for(path: PathLike) -> ModuleType:
    """The format module for ``path``'s extension."""
    ext = Path(path).suffix.lower()
    if ext not in FORMATS:
        raise UnknownFormatError(
            f"{path}: unknown mesh format {ext or '(no extension)'!r}; expected one of {', '.join(mesh_extensions())}"
        )
    return importlib.import_module(FORMATS[ext])


def write_mesh(path: PathLike, mesh: MeshData, *, name: str) -> list[Path]:
    """Check ``mesh`` edge by edge, then write it to ``path`` atomically in the format of its extension.

    Returns the files written: ``path``, and for a coloured OBJ its material
    library beside it (same name, ``.mtl``).
    """
    from .._check import check_mesh

    module = format_for(path)
    check_mesh(mesh, what=str(path))
    target = Path(path)
    if mesh.coloured and hasattr(module, "material_bytes"):
        library = target.with_suffix(module.MATERIAL_EXTENSION)
        write_bytes(library, module.material_bytes(mesh))
        write_bytes(target, module.to_bytes(mesh, name=name, materials=library.name))
        return [target, library]
    write_bytes(target, module.to_bytes(mesh, name=name))
    return [target]


def read_mesh(path: PathLike) -> MeshData:
    """Read a mesh written by :func:`write_mesh`.

    Raises
    ------
    FormatError
        When the file is not one, or names vertices or colours it does not hold.
    """
    import struct

    import numpy as np

    module = format_for(path)
    try:
        mesh = module.read(path)
    except FormatError:
        raise
    except (KeyError, IndexError, TypeError, ValueError, struct.error) as exc:
        # A file of the right kind with missing or malformed pieces (an attribute, an accessor).
        raise FormatError(f"{path}: not a readable {module.EXTENSION} mesh ({type(exc).__name__}: {exc})") from None
    n = len(mesh.vertices)
    if mesh.triangles.ndim != 2 or mesh.triangles.shape[1:] != (3,) or mesh.triangles.size and (
            mesh.triangles.min() < 0 or mesh.triangles.max() >= n):
        raise FormatError(f"{path}: a triangle names a vertex the file does not hold ({n} vertices)")
    if not np.isfinite(mesh.vertices).all():
        raise FormatError(f"{path}: a vertex is not a finite number")
    if mesh.coloured and (len(mesh.colour) != len(mesh.triangles) or mesh.colour.size and (  # type: ignore[arg-type]
            mesh.colour.min() < 0 or mesh.colour.max() >= len(mesh.palette))):  # type: ignore[union-attr,arg-type]
        raise FormatError(f"{path}: a triangle names a colour the file does not hold")
    return mesh
