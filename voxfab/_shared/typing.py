"""Type aliases used across voxfab."""

from __future__ import annotations

import os
from typing import Union

import numpy as np
import numpy.typing as npt

#: A 3D bool array indexed ``[x, y, z]`` with z up.
BoolGrid = npt.NDArray[np.bool_]
#: An ``(N, 3)`` integer array of voxel coordinates.
Points3 = npt.NDArray[np.int64]
#: A path given as ``str`` or ``os.PathLike``.
PathLike = Union[str, "os.PathLike[str]"]
