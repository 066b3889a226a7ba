"""Nets: single-piece edge unfoldings of voxel surfaces, and their validator.

``unfold`` searches a net, ``unfold_many`` several distinct ones, ``validate``
refolds a net and checks it against the shape, ``seam_pairs`` and ``tab_room``
describe its cut edges for glue tabs, ``EdgeConstraints`` names edges to cut
or keep folded, ``cut_edge`` and ``join_edge`` edit one edge of a net and
repair its layout around the change, ``hunt_shape`` tells whether a shape has a
one-piece net and a zipper net, ``solve_with_nogoods`` runs CP-SAT with
no-goods added lazily (the zipper search's and the census's loop).
"""

from typing import TYPE_CHECKING

from voxfab._shared.lazy import lazy_names
from voxfab.errors import NoNetExistsError

from ._constraints import EdgeConstraints
from ._job import NoFitError, Pieces, Strategy
from ._layout import seam_pairs, tab_room
from ._net import NET_FORMAT, Net, fold_tree
from ._search import unfold
from ._validate import ValidationReport, validate

if TYPE_CHECKING:
    from ._cpsat import solve_with_nogoods
    from ._edit import EditResult, cut_edge, join_edge
    from ._exact import Undecided
    from ._hunt import HUNT_NET, HUNT_ZIPPER, HuntOutcome, hunt_shape
    from ._many import unfold_many
    from ._outline import outline_key

#: Names whose modules load on first use: a command that searches one net never runs them.
_LAZY = {"solve_with_nogoods": "_cpsat", "EditResult": "_edit", "cut_edge": "_edit", "join_edge": "_edit",
         "HUNT_NET": "_hunt", "HUNT_ZIPPER": "_hunt", "HuntOutcome": "_hunt", "hunt_shape": "_hunt",
         "unfold_many": "_many", "Undecided": "_exact", "outline_key": "_outline"}

__getattr__, __dir__ = lazy_names(__name__, _LAZY, globals())

__all__ = [
    "fold_tree",
    "NET_FORMAT",
    "EdgeConstraints",
    "EditResult",
    "HUNT_NET",
    "HUNT_ZIPPER",
    "HuntOutcome",
    "Net",
    "NoFitError",
    "NoNetExistsError",
    "Pieces",
    "Strategy",
    "cut_edge",
    "Undecided",
    "ValidationReport",
    "outline_key",
    "join_edge",
    "seam_pairs",
    "solve_with_nogoods",
    "tab_room",
    "unfold",
    "unfold_many",
    "hunt_shape",
    "validate",
]
