"""Shape makers for recipes: keyword-only, TOML-typed wrappers of the digitizers, and their random keys.

Each ``make_*`` function is one row of :data:`voxfab.digitize.MAKERS`; a ``random_*``
function draws that maker's keys from a ``numpy.random.Generator`` for ``voxfab explore``.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any, Literal

import numpy as np

from ._fit import fit
from ._focal import focal
from ._implicit import implicit_field
from ._revolution import revolution
from ._tube import tube

__all__ = ["make_revolution", "make_tube", "make_focal", "make_implicit", "random_revolution", "random_tube",
           "random_focal", "rounded_param"]

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


# --- random keys for ``voxfab explore`` --------------------------------------------------------

def rounded_param(x: float) -> float:
    """``x`` to 4 decimals: parameters are stored in the repository's metadata, and the stored values are
    exactly the ones used."""
    return round(float(x), 4)


def random_revolution(rng: np.random.Generator) -> dict[str, Any]:
    """Random keys of :func:`make_revolution` for ``voxfab explore``: a superellipse, circle or star turned about a wavy generatrix."""
    kind = int(rng.integers(3))
    if kind == 0:
        curve = "x^2 + y^2 - 1"
    elif kind == 1:
        p, q = (rounded_param(v) for v in rng.choice([1.0, 1.5, 3.0, 4.0], size=2))
        curve = f"abs(x)^{p} + abs(y)^{q} - 1"
    else:
        curve = f"sqrt(x^2 + y^2) - 1 - {rounded_param(rng.uniform(0.1, 0.35))}*cos({int(rng.integers(3, 9))}*atan2(y, x))"
    r0 = rounded_param(rng.uniform(0.35, 1.0))
    amp = rounded_param(rng.uniform(0.0, 0.3) * r0)
    freq, phase, height = rounded_param(rng.uniform(0.5, 5.0)), rounded_param(rng.uniform(0.0, math.tau)), rounded_param(rng.uniform(0.6, 2.5))
    generatrix = f"max(x - ({r0} + {amp}*sin({freq}*y + {phase})), abs(y) - {height})"
    return {"curve": curve, "generatrix": generatrix, "mode": str(rng.choice(["solid", "solid", "surface"]))}


def random_tube(rng: np.random.Generator) -> dict[str, Any]:
    """Random keys of :func:`make_tube`: a helix or a Lissajous spine with a round, square or diamond profile."""
    if rng.integers(2) == 0:
        turns, r = rounded_param(rng.uniform(0.5, 3.0)), rounded_param(rng.uniform(0.3, 1.5))
        spine = [f"{r}*cos(tau*{turns}*t)", f"{r}*sin(tau*{turns}*t)", "t"]
    else:
        a, b, c = (int(v) for v in rng.integers(1, 5, size=3))
        ph = rounded_param(rng.uniform(0.0, math.tau))
        spine = [f"sin(tau*{a}*t + {ph})", f"sin(tau*{b}*t)", f"t + 0.3*sin(tau*{c}*t)"]
    profile = str(rng.choice(["x^2 + y^2 - 1", "abs(x)^4 + abs(y)^4 - 1", "abs(x) + abs(y) - 1"]))
    return {"spine": spine, "profile": profile, "radius": rounded_param(rng.uniform(0.06, 0.25)),
            "twist": rounded_param(rng.uniform(0.0, 2.0)), "cap": str(rng.choice(["flat", "round"]))}


def random_focal(rng: np.random.Generator) -> dict[str, Any]:
    """Random keys of :func:`make_focal`: two to four weighted foci and a radius just above the smallest."""
    n = int(rng.integers(2, 5))
    foci = np.round(rng.uniform(-1.5, 1.5, size=(n, 3)), 4)
    weights = np.round(rng.uniform(0.5, 3.0, size=n), 4)
    # The level set is empty below the smallest weighted sum, reached at a focus.
    least = min(float(np.sum(weights * np.linalg.norm(foci - f, axis=1))) for f in foci)
    radius = rounded_param(least * rng.uniform(1.05, 1.6) + float(weights.sum()) * rng.uniform(0.2, 1.0))
    return {"foci": foci.tolist(), "weights": weights.tolist(), "radius": radius,
            "mode": str(rng.choice(["solid", "solid", "surface"]))}
