"""Shape makers for recipes: keyword-only, TOML-typed wrappers of the digitizers."""

from __future__ import annotations

from pathlib import Path
from typing import Literal

import numpy as np

from ._fit import fit
from ._focal import focal
from ._implicit import implicit_field
from ._revolution import revolution
from ._tube import tube

__all__ = ["make_revolution", "make_tube", "make_focal", "make_implicit"]

ModeName = Literal["solid", "surface"]


def make_revolution(
    *,
    base_dir: Path,
    generatrix: str,
    curve: str = "x^2 + y^2 - 1",
    axis: float | None = None,
    curve_threshold: float = 0.5,
    generatrix_threshold: float = 0.5,
    k: int = 0,
    mode: ModeName = "solid",
    size: int = 25,
    scale: float | None = None,
    at: float | None = None,
    z_range: list[float] | None = None,
    arc: list[float] | None = None,
    center: list[float] | None = None,
    curve_open: bool = False,
) -> np.ndarray:
    """Surface of revolution: ``curve`` (expression in x, y or x, y, z; SVG/JSON/CSV/PNG file) times ``generatrix``.

    An explicit generatrix ``x = g(y)`` spans the heights ``z_range`` (default ``[-1, 1]``).
    ``arc = [start, end]`` (degrees) keeps only that open part of the curve: a swept surface.
    ``curve_open = true`` takes a drawn ``curve`` as the open stroke it is (mode ``"surface"``).
    ``center`` (with ``scale``) is the model point at the grid's middle.
    """
    return revolution(
        curve, generatrix, k=k, mode=mode, size=size, scale=scale, at=at, base_dir=Path(base_dir),
        curve_threshold=curve_threshold, generatrix_threshold=generatrix_threshold, axis=axis, z_range=z_range,
        arc=arc, center=center, curve_open=curve_open,
    )


def make_tube(
    *,
    base_dir: Path,
    spine: list[str] | str | list[list[float]],
    profile: str = "x^2 + y^2 - 1",
    radius: float = 1.0,
    twist: float = 0.0,
    phase: float = 0.0,
    frame: Literal["rmf", "frenet"] = "rmf",
    cap: Literal["flat", "round"] = "flat",
    closed: bool | None = None,
    t_min: float = 0.0,
    t_max: float = 1.0,
    samples: int = 1024,
    threshold: float = 0.5,
    stroke: float | None = None,
    k: int = 0,
    mode: ModeName = "solid",
    size: int = 25,
    scale: float | None = None,
    arc: list[float] | None = None,
    center: list[float] | None = None,
    profile_open: bool = False,
) -> np.ndarray:
    """Swept tube: ``spine`` = [x(t), y(t), z(t)] expressions, a 3D point file or a point list; any 2D ``profile``.

    ``arc = [start, end]`` (degrees) keeps only that open part of the profile: a ribbon;
    ``profile_open = true`` takes a drawn profile as the open stroke it is (a ribbon between its ends).
    ``center`` (with ``scale``) is the model point at the grid's middle.
    """
    spine_arg: object = spine
    if isinstance(spine, list) and spine and isinstance(spine[0], list):
        spine_arg = np.asarray(spine, dtype=np.float64)
    return tube(
        spine_arg, profile, radius=radius, twist=twist, phase=phase, frame=frame, cap=cap, closed=closed,
        t_min=t_min, t_max=t_max, samples=samples, k=k, mode=mode, size=size, scale=scale,
        base_dir=Path(base_dir), threshold=threshold, stroke=stroke, arc=arc, center=center,
        profile_open=profile_open,
    )


def make_focal(
    *,
    base_dir: Path,
    foci: list[list[float]],
    radius: float,
    weights: list[float] | None = None,
    k: int = 0,
    mode: ModeName = "solid",
    size: int = 25,
    scale: float | None = None,
) -> np.ndarray:
    """Weighted focal shape ``Σ w_i ‖x − f_i‖ = radius`` (an egg with two unequal weights)."""
    return focal(foci, weights, radius, k=k, mode=mode, size=size, scale=scale)


def make_implicit(
    *,
    base_dir: Path,
    expression: str,
    bounds: list[float] | None = None,
    at: float | None = None,
    k: int = 0,
    mode: ModeName = "solid",
    size: int = 25,
    scale: float | None = None,
) -> np.ndarray:
    """An expression in x, y, z (or x, y, z, w: 4D, sliced at w = ``at``, default the middle)."""
    fld = implicit_field(expression, bounds=bounds)
    if fld.ndim == 4 and at is None:
        at = float((fld.lo[-1] + fld.hi[-1]) / 2.0)
    return fit(fld, k=k, mode=mode, size=size, scale=scale, at=at)
