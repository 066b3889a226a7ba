"""voxfab studio: a local web app where the artist draws, edits, keeps and chooses.

``voxfab studio`` serves one page on 127.0.0.1: draw a surface of revolution, a
tube or an egg and see its 25³ digitization at once; edit voxels layer by
layer with live well-formedness; paint them (open a MagicaVoxel ``.vox``, paint
voxels, face regions and fills, join parts, save ``.vox`` / ``.npz``); keep shapes
in the repository; pick a net from a gallery, mark edges to cut or keep; download
meshes, nets, plates and the triptych.  The page is plain HTML, CSS and JS modules shipped in this
package; the server is a thin Starlette layer over the library (the library
never imports this package).

Public API: :func:`create_app`, :class:`Settings`, :func:`allowed_hosts`, :func:`serve`, and the
grids on the wire: :func:`pack` (a bool grid, and its colours if it has some, to ``{"dims", "bits"}``
plus ``"colours"`` and ``"palette"``, the JSON body's ``grid``) and :func:`unpack` (the bool grid, checked); :func:`warm_gallery_here` (load what a gallery in pieces first calls, as the
server does at start).
"""

from ._server import serve

__all__ = ["Settings", "allowed_hosts", "create_app", "pack", "serve", "unpack", "warm_gallery_here"]


#: Where each lazily exported name is defined (importing Starlette only when one is asked for).
_LAZY = {"Settings": "_session", "allowed_hosts": "_guard", "create_app": "_app", "pack": "_grid",
         "unpack": "_grid", "warm_gallery_here": "_work"}


def __getattr__(name: str):  # noqa: ANN202 - lazy re-exports keep `import voxfab.studio` free of Starlette
    if name in _LAZY:
        from importlib import import_module

        return getattr(import_module(f"{__name__}.{_LAZY[name]}"), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
