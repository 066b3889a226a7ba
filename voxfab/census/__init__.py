"""The polycube census: every polycube of up to n cubes, unfolded and unzipped.

``polycubes`` streams every polycube up to rotation (the one-sided polycubes,
OEIS A000162) in a fixed order (canonical growth), ``count_polycubes`` counts
them one-sided and free (up to rotation and reflection, A038119), ``topology`` classifies a surface as the unzipping paper does,
``unzip`` searches an edge-unzipping in that paper's model, ``census_shape``
runs every search on one polycube, ``run_census`` runs them all (serially or on
Dask) into ``census.json`` and a page, ``check_certificate`` re-checks a
"no unzipping" certificate from the cells alone, and ``verify_census`` checks
every net and proof a census wrote.
"""

from ._certificate import check_certificate
from ._enumerate import MAX_CUBES, canonical_cells, count_free, count_polycubes, polycube_levels, polycubes
from ._report import cubes_page, cubes_svg, net_page, net_svg, write_page
from ._run import (
    CENSUS_FORMAT,
    CensusInterrupted,
    CensusReport,
    check_census_size,
    check_scheduler,
    run_census,
    shape_id,
)
from ._task import CensusSettings, CensusTask, census_shape, census_task, fold_tree_pairs, net_paths
from ._topology import SURFACE_KINDS, Topology, grid_of, topology
from ._unzip import UNZIP_OUTCOMES, Unzipping, unzip
from ._verify import CensusCheck, cut_path_problem, record_problems, tree_problem, verify_census

__all__ = [
    "CENSUS_FORMAT",
    "CensusCheck",
    "CensusInterrupted",
    "CensusReport",
    "CensusSettings",
    "CensusTask",
    "census_shape",
    "census_task",
    "check_certificate",
    "cut_path_problem",
    "check_census_size",
    "check_scheduler",
    "count_polycubes",
    "fold_tree_pairs",
    "record_problems",
    "tree_problem",
    "cubes_page",
    "cubes_svg",
    "net_page",
    "net_paths",
    "net_svg",
    "run_census",
    "shape_id",
    "write_page",
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
    "verify_census",
]
