"""The polycube census: every polycube of up to n cubes, unfolded and unzipped.

``polycubes`` streams every polycube up to rotation in a fixed order (canonical
growth), ``count_free`` counts them up to rotation and up to rotation and
reflection, ``topology`` classifies a surface as the unzipping paper does,
``unzip`` searches an edge-unzipping in that paper's model, ``census_shape``
runs every search on one polycube, ``run_census`` runs them all (serially or on
Dask) into ``census.json`` and a page, and ``check_certificate`` re-checks a
"no unzipping" certificate from the cells alone.
"""

from ._enumerate import MAX_CUBES, canonical_cells, count_free, polycube_levels, polycubes
from ._topology import SURFACE_KINDS, Topology, grid_of, topology
from ._unzip import UNZIP_OUTCOMES, Unzipping, unzip

__all__ = [
    "MAX_CUBES",
    "SURFACE_KINDS",
    "Topology",
    "UNZIP_OUTCOMES",
    "Unzipping",
    "canonical_cells",
    "count_free",
    "grid_of",
    "polycube_levels",
    "polycubes",
    "topology",
    "unzip",
]
