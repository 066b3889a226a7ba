"""Radial joints hold by the interlocked rule: every two plates at the hub engage over half the shorter one."""

from __future__ import annotations

import json
import math

import numpy as np
import shapely

from voxfab.fabricate.plates import PlateOptions, fabricate_plates
from voxfab.recipe import load_recipe, make_shape
from voxfab.shape import crop


def _layers(grid: np.ndarray, pitch: float) -> list:
    """Each voxel layer's filled squares as one shapely geometry, mm."""
    out = []
    for k in range(grid.shape[2]):
        cells = np.argwhere(grid[:, :, k]) * pitch
        out.append(shapely.union_all(shapely.box(cells[:, 0], cells[:, 1], cells[:, 0] + pitch, cells[:, 1] + pitch))
                   .buffer(1e-9))
    return out


def _hub_rows(layers: list, centre, angle: float, half: float, thickness: float):
    """Per voxel layer: whether the plate at ``angle`` meets the hub band ``|r| <= half``, and fills it.

    Measured on the voxel solid itself: a plate is there where its whole thickness is inside the
    layer (the section it is cut to), sampled across the band every 0.1 mm.
    """
    a = math.radians(angle)
    d, n = np.array([math.cos(a), math.sin(a)]), np.array([math.sin(a), -math.cos(a)])
    rs = np.linspace(-half, half, int(2 * half / 0.1) + 1)
    across = shapely.linestrings(np.stack([centre + np.outer(rs, d) - n * thickness / 2,
                                           centre + np.outer(rs, d) + n * thickness / 2], axis=1))
    inside = np.array([shapely.contains(layer, across) for layer in layers])
    return inside.any(axis=1), inside.all(axis=1)


def _runs(flags: np.ndarray) -> int:
    """Length of the longest run of True."""
    best = run = 0
    for f in flags:
        run = run + 1 if f else 0
        best = max(best, run)
    return best


def test_knight_radial_pairs_engage_over_half_the_shorter_plate_or_are_weak(tmp_path) -> None:
    """The knight at 2.4 mm: R2, R3 and R4 meet at the hub over 26.4 of 57.6 mm (0.46): weak, not trimmed."""
    shape = make_shape(load_recipe("recipes/chess/knight.toml"))
    made = fabricate_plates(shape, PlateOptions(style="radial"), tmp_path / "k", name="knight")
    report = json.loads((tmp_path / "k" / "plates.json").read_text())
    grid, pitch = crop(shape.grid), shape.pitch
    centre = np.array(report["plates_list"][0]["origin"][:2])
    half = report["slot_width"] / 2
    layers = _layers(grid, pitch)
    # the four plates asked for, kept or not: their hub band with the margin beside it, and without
    rows = {f"R{k + 1}": _hub_rows(layers, centre, 45.0 * k, half + report["min_width"], report["thickness"])
            for k in range(4)}
    narrow = {f"R{k + 1}": _hub_rows(layers, centre, 45.0 * k, half, report["thickness"])[0] for k in range(4)}

    def holds(a: str, b: str) -> bool:
        shorter = min(narrow[a].sum(), narrow[b].sum())
        return _runs(rows[a][1] & rows[b][1]) >= 0.5 * shorter

    kept = [p["label"] for p in report["plates_list"]]
    assert len(kept) >= 2
    for i, a in enumerate(kept):
        for b in kept[i + 1:]:
            assert holds(a, b), (a, b)
    assert report["weak"] and all(not holds(*pair.split("/")) for pair in report["weak"])
    assert any("crossing(s) dropped" in w and report["weak"][0] in w for w in made.warnings)
