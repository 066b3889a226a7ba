"""Random shape generators and exploration of the space of well-formed shapes.

The artist's repository follows Borges' *Library of Babel*: every well-formed
shape of the 25³ grid has a place, named by volume and rank.  This package draws
candidates (face-connected growth spanning the grid, or random parameters for the
makers of :mod:`voxfab.digitize`) and :func:`explore` stores the new ones.
"""

from ._explore import ExploreReport, check_explore, explore, parse_volume_range, volume_bins
from ._keys import symmetric_key
from ._makers import Candidate, candidate, generators, growth

__all__ = [
    "Candidate",
    "ExploreReport",
    "check_explore",
    "candidate",
    "explore",
    "generators",
    "growth",
    "parse_volume_range",
    "symmetric_key",
    "volume_bins",
]
