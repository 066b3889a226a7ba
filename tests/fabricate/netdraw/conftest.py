"""Nets in pieces on sheets, made once per session for every test that reads them back from the files."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from voxfab.fabricate.netdraw import DrawingOptions, NetOptions, fabricate_net
from voxfab.shape import VoxelShape


@pytest.fixture(scope="session")
def sheet_net(tmp_path_factory) -> Callable[[str, np.ndarray, float, str], tuple[Path, Any, DrawingOptions]]:
    """``sheet_net(name, grid, face, sheet)``: the net of ``grid`` in pieces on ``sheet`` at ``face`` mm, written
    once per session as DXF sheets, a PDF and the pieces' JSON; (folder, result, drawing options).

    The sheet and dense-page tests read the same nets (seed 1) with checks of their own: one search each.
    """
    made: dict[tuple[str, float, str], tuple[np.ndarray, tuple[Path, Any, DrawingOptions]]] = {}

    def get(name: str, grid: np.ndarray, face: float, sheet: str) -> tuple[Path, Any, DrawingOptions]:
        key = (name, face, sheet)
        if key not in made:
            folder = tmp_path_factory.mktemp("sheet-net")
            drawing = DrawingOptions(pitch=face, sheet=sheet, label_height=2.0)
            result = fabricate_net(VoxelShape(grid), NetOptions(face_size=face, pieces="auto", fill=True,
                                                                formats=("dxf", "pdf")),
                                   drawing, folder, name=name, seed=1)
            made[key] = (grid.copy(), (folder, result, drawing))
        shape, out = made[key]
        assert np.array_equal(shape, grid), f"{name}: another grid under the same name"
        return out

    return get
