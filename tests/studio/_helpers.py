"""Helpers of the studio tests."""

from __future__ import annotations

import functools
import io
import time
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw

#: Screenshots of the browser tests, for a person to look at (output/ is not committed).
SHOTS = Path(__file__).resolve().parents[2] / "output" / "studio"

def png(draw) -> bytes:
    """A 100 × 100 white PNG with ``draw(ImageDraw)`` in black."""
    im = Image.new("L", (100, 100), 255)
    draw(ImageDraw.Draw(im))
    buf = io.BytesIO()
    im.save(buf, format="PNG")
    return buf.getvalue()


def wait_job(client, job: str, limit: float = 120.0) -> dict:
    """Poll a job until it ends (bounded)."""
    end = time.monotonic() + limit
    while time.monotonic() < end:
        s = client.get(f"/api/jobs/{job}").json()
        if s["state"] not in ("queued", "running"):
            return s
        time.sleep(0.1)
    raise AssertionError(f"job {job} still running after {limit} s")


@functools.cache
def _bundled_queen() -> np.ndarray:
    from voxfab.recipe import load_recipe
    from voxfab.recipe._build import make_shape

    return make_shape(load_recipe(Path(__file__).resolve().parents[2] / "recipes" / "chess" / "queen.toml")).grid


def queen() -> np.ndarray:
    """The bundled chess queen's voxels (built once; each caller gets its own copy)."""
    return _bundled_queen().copy()


def small_shape() -> np.ndarray:
    """A well-formed 3 × 3 × 25 column with a foot, centred in 25³: quick nets."""
    g = np.zeros((25, 25, 25), dtype=bool)
    g[11:14, 11:14, :] = True
    g[10:15, 11:14, 0] = True
    return g
