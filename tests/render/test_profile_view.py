"""A piece's picture shows its profile: the knight is seen from the side its head shows, the lathe-turned pieces
from the isometric corner."""

from __future__ import annotations

from functools import cache
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from voxfab.recipe import load_recipe, make_shape
from voxfab.render import PictureOptions, profile_camera, render, render_pictures
from voxfab.shape import VoxelShape

RECIPES = Path(__file__).resolve().parents[2] / "recipes" / "chess"


@cache
def piece(name: str) -> np.ndarray:
    return make_shape(load_recipe(RECIPES / f"{name}.toml")).grid


def _outline(silhouette: np.ndarray) -> int:
    """Cell edges on the border of a 2D silhouette, counted here from its differences."""
    m = np.pad(silhouette, 1).astype(np.int8)
    return int(np.abs(np.diff(m, axis=0)).sum() + np.abs(np.diff(m, axis=1)).sum())


def _silhouette(image: Image.Image, side: int = 100) -> np.ndarray:
    """The picture's non-paper pixels, cropped to their box and resampled to ``side`` x ``side``."""
    ink = np.asarray(image.convert("L")) < 250
    ys, xs = np.nonzero(ink)
    box = Image.fromarray(ink[ys.min():ys.max() + 1, xs.min():xs.max() + 1])
    return np.asarray(box.resize((side, side), Image.NEAREST))


def _overlap(a: np.ndarray, b: np.ndarray) -> float:
    return float((a & b).sum() / (a | b).sum())


def test_the_knight_is_pictured_from_the_side_its_head_shows() -> None:
    knight = piece("knight")
    # The horse's outline (head, ears, mane, throat) is seen along x; along y it is a narrow block.
    along_x, along_y = _outline(knight.any(axis=0)), _outline(knight.any(axis=1))
    assert along_x > 1.15 * along_y
    toward = profile_camera(knight).toward
    assert abs(toward[0]) > 2 * abs(toward[1])
    # Measured in the pictures: the profile picture's outline is the side view's (the head's profile),
    # much more than the isometric picture's is.
    side = _silhouette(render(knight, view="x", size=300))
    profile = _overlap(_silhouette(render(knight, view="profile", size=300)), side)
    iso = _overlap(_silhouette(render(knight, view="iso", size=300)), side)
    assert profile >= 0.8 and profile > iso + 0.05, (profile, iso)


@pytest.mark.parametrize("name", ["queen", "pawn"])
def test_a_lathe_turned_piece_keeps_the_isometric_picture(name: str) -> None:
    grid = piece(name)
    assert _outline(grid.any(axis=0)) == pytest.approx(_outline(grid.any(axis=1)), rel=0.15)
    assert render(grid, view="profile", size=120).tobytes() == render(grid, view="iso", size=120).tobytes()


def test_the_recipe_pictures_show_the_profile(tmp_path: Path) -> None:
    knight = piece("knight")
    made = render_pictures(VoxelShape(knight), PictureOptions(size=200, triptych=False), tmp_path, name="knight",
                           seed=1)
    assert [f.path for f in made.files] == ["render_profile.png"]
    with Image.open(tmp_path / "render_profile.png") as written:
        assert written.tobytes() == render(knight, view="profile", size=200).tobytes()
