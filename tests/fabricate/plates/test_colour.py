"""Plates by colour: each plate's main colour from the voxels of its section, and sheets of one colour.

The checks read the written files (plates.json, the DXF sheets with ezdxf) and
compute each plate's colours from the shape's own voxels by sampling the plate's
cut outline as read from the sheet, sharing no code with the library's exact split.
"""

from __future__ import annotations

import functools
import json
from collections import Counter

import ezdxf
import numpy as np
import pytest
import shapely
from _dxf_read import closed_rings
from _voxart import character
from scipy import ndimage

from voxfab.fabricate.plates import PlateOptions, fabricate_plates, make_slices
from voxfab.recipe import load_recipe, make_shape
from voxfab.shape import VoxelShape

_TRANSPOSE = {"x": (0, 1, 2), "y": (1, 2, 0), "z": (2, 0, 1)}


@functools.lru_cache(maxsize=1)
def painted_queen() -> VoxelShape:
    """The chess queen in four colours: a red foot, a blue crown, a green and white middle split off-centre."""
    q = make_shape(load_recipe("recipes/chess/queen.toml"))
    g = q.grid
    x, y, z = np.indices(g.shape)
    return (q.painted((200, 40, 40, 255), g & (z < 4)).painted((40, 60, 150, 255), g & (z >= 17))
            .painted((30, 160, 60, 255), g & (z >= 4) & (z < 17) & (x + 2 * y < 38)))


@functools.lru_cache(maxsize=1)
def joined_character() -> VoxelShape:
    return character().joined()[0]


def _cropped_rgba(shape: VoxelShape, *, solid: bool = False) -> np.ndarray:
    grid = shape.grid
    rgba = np.where(grid[..., None], shape.colours.rgba, 0).astype(np.uint8)
    if solid:  # the slotted styles run through closed cavities: fill them with the nearest voxel's colour
        full = ndimage.binary_fill_holes(grid)
        _, near = ndimage.distance_transform_edt(~grid, return_indices=True)
        rgba = np.where(full[..., None], rgba[near[0], near[1], near[2]], 0).astype(np.uint8)
        grid = full
    nz = np.argwhere(grid)
    lo, hi = nz.min(axis=0), nz.max(axis=0) + 1
    return rgba[lo[0]:hi[0], lo[1]:hi[1], lo[2]:hi[2]]


def _hex(rgba) -> str:
    return "#{:02x}{:02x}{:02x}".format(*(int(c) for c in rgba[:3]))


def _main(counts: Counter) -> tuple[str, float, float]:
    """Main colour, its share, and its lead over the second colour."""
    total = sum(counts.values())
    top = counts.most_common(2) + [("", 0)]
    return top[0][0], top[0][1] / total, (top[0][1] - top[1][1]) / total


def _turn(xy: np.ndarray, turns: int) -> np.ndarray:
    for _ in range(turns % 4):
        xy = np.column_stack([-xy[:, 1], xy[:, 0]])
    return xy


def _sheet_parts(path) -> list[shapely.Polygon]:
    """The parts cut on one DXF sheet: each outer ring with the rings inside it as holes."""
    doc = ezdxf.readfile(path)
    assert not doc.audit().has_errors
    rings = sorted((shapely.Polygon(r) for r in closed_rings(doc)), key=lambda r: -r.area)
    parts: list[shapely.Polygon] = []
    for r in rings:
        host = [i for i, p in enumerate(parts) if shapely.Polygon(p.exterior).contains(r)]
        if host and not any(shapely.Polygon(h).contains(r) for h in parts[host[-1]].interiors):
            p = parts[host[-1]]
            parts[host[-1]] = shapely.Polygon(p.exterior, [*p.interiors, r.exterior])
        else:
            parts.append(r)
    for c in doc.modelspace().query("CIRCLE"):  # dowel holes
        disc = shapely.Point(tuple(c.dxf.center)[:2]).buffer(c.dxf.radius, quad_segs=32)
        k = next(i for i, p in enumerate(parts) if p.contains(shapely.Point(tuple(c.dxf.center)[:2])))
        parts[k] = parts[k].difference(disc)
    return parts


def _sampled_colours(polygon: shapely.Polygon, frame, rgba: np.ndarray, pitch: float) -> tuple[Counter, int]:
    """Colours under a dense lattice of points of a plate (its frame, mm) on its mid-plane, and the points."""
    origin, u, v = (np.asarray(a, float) for a in frame)
    step = pitch / 16
    x0, y0, x1, y1 = polygon.bounds
    xs, ys = np.meshgrid(np.arange(x0 + step / 2, x1, step), np.arange(y0 + step / 2, y1, step))
    inside = shapely.contains_xy(polygon, xs.ravel(), ys.ravel())
    uv = np.column_stack([xs.ravel()[inside], ys.ravel()[inside]])
    points = origin + uv[:, :1] * u + uv[:, 1:] * v
    cells = np.floor(points / pitch).astype(int)
    ok = np.all((cells >= 0) & (cells < rgba.shape[:3]), axis=1)
    found = rgba[cells[ok, 0], cells[ok, 1], cells[ok, 2]]
    return Counter(_hex(c) for c in found if c[3] > 0), len(uv)


def _stacked_frame(record: dict, axis: str, pitch: float):
    w, u, v = _TRANSPOSE[axis]
    e = np.eye(3)
    return e[w] * (record["voxel_layer"] - 0.5) * pitch, e[u], e[v]


def _check_written(folder, shape: VoxelShape, *, by_colour: bool) -> dict:
    """Match every plate of plates.json to its part on its DXF sheet and check its colour from the voxels."""
    report = json.loads((folder / "plates.json").read_text())
    pitch = shape.pitch
    rgba = _cropped_rgba(shape, solid=report["plates_list"][0]["style"] != "stacked")
    sheets = {s["index"]: s for s in report["sheets_list"]}
    assert sorted(sheets) == list(range(1, report["sheets"] + 1)) and report["by_colour"] == by_colour
    parts = {k: _sheet_parts(folder / s["file"]) for k, s in sheets.items()}
    assert sum(len(p) for p in parts.values()) == len(report["plates_list"])
    decided = 0
    for rec in report["plates_list"]:
        # the plate's part on its sheet, turned and moved back into the plate's frame by plates.json
        candidates = [shapely.transform(p, lambda xy, r=rec: _turn(xy - r["offset"], -r["turns"]))
                      for p in parts[rec["sheet"]]]
        matches = [c for c in candidates if abs(c.area - rec["area"]) < 1e-3 * rec["area"]]
        frame = (_stacked_frame(rec, report["axis"], pitch) if rec["style"] == "stacked"
                 else (rec["origin"], rec["u"], rec["v"]))
        counts = [_sampled_colours(m, frame, rgba, pitch) for m in matches]
        # the part that lies in the voxel solid at the plate's plane is the plate
        own = [c for c, n in counts if n and sum(c.values()) == n]
        assert own, rec["label"]
        colour, share, lead = _main(own[0])
        if lead > 0.02:  # a near tie is left to the library's tie rule
            assert rec["colour"]["hex"] == colour, rec["label"]
            decided += 1
        assert rec["colour"]["share"] == pytest.approx(share, abs=0.02), rec["label"]
        if by_colour:
            assert sheets[rec["sheet"]]["colour"] == rec["colour"]["hex"]
            assert sheets[rec["sheet"]]["file"].endswith(rec["colour"]["hex"][1:] + ".dxf")
    assert decided >= 0.8 * len(report["plates_list"])
    by_hex = {c["colour"]: c for c in report["colours"]}
    assert sorted(p for c in report["colours"] for p in c["plates"]) == [p["number"] for p in report["plates_list"]]
    for rec in report["plates_list"]:
        assert rec["number"] in by_hex[rec["colour"]["hex"]]["plates"]
        assert rec["sheet"] in by_hex[rec["colour"]["hex"]]["sheets"]
    if by_colour:  # every sheet holds plates of one colour, and each colour's sheets are its own
        for s in sheets.values():
            assert {report["plates_list"][n - 1]["colour"]["hex"] for n in s["plates"]} == {s["colour"]}
        assert sum(len(c["sheets"]) for c in report["colours"]) == report["sheets"]
    return report


@pytest.mark.parametrize("style", ["stacked", "interlocked", "radial"])
def test_each_plate_of_the_painted_queen_names_its_main_colour(tmp_path, style) -> None:
    shape = painted_queen()
    fabricate_plates(shape, PlateOptions(style=style, sheet="300x200"), tmp_path / "q", name="queen")
    report = _check_written(tmp_path / "q", shape, by_colour=False)
    assert len({p["colour"]["hex"] for p in report["plates_list"]}) >= 2


@pytest.mark.parametrize("style", ["stacked", "radial"])
def test_by_colour_puts_one_colour_on_each_sheet(tmp_path, style) -> None:
    shape = painted_queen()
    made = fabricate_plates(shape, PlateOptions(style=style, sheet="300x200", by_colour=True), tmp_path / "q",
                            name="queen")
    report = _check_written(tmp_path / "q", shape, by_colour=True)
    assert len(report["colours"]) >= 2
    assert {f.path for f in made.files if f.path.endswith(".dxf")} == {s["file"] for s in report["sheets_list"]}


@pytest.mark.parametrize("style", ["stacked", "interlocked"])
def test_the_coloured_character_by_colour(tmp_path, style) -> None:
    shape = joined_character()
    extra = {"count": 4} if style == "interlocked" else {}  # a count is the interlocked style's option alone
    fabricate_plates(shape, PlateOptions(style=style, thickness=2.0, sheet="200x150", by_colour=True, **extra),
                     tmp_path / "c", name="character")
    report = _check_written(tmp_path / "c", shape, by_colour=True)
    assert len(report["colours"]) >= 4 if style == "stacked" else len(report["colours"]) >= 1


def test_an_uncoloured_shape_writes_what_it_wrote_before(tmp_path) -> None:
    coloured = painted_queen()
    plain = VoxelShape(coloured.grid, coloured.pitch)
    fabricate_plates(plain, PlateOptions(), tmp_path / "plain", name="queen")
    made = fabricate_plates(plain, PlateOptions(by_colour=True), tmp_path / "asked", name="queen")
    assert any("no colours" in w for w in made.warnings)
    fabricate_plates(coloured, PlateOptions(), tmp_path / "coloured", name="queen")
    names = sorted(p.name for p in (tmp_path / "plain").iterdir())
    assert names == sorted(p.name for p in (tmp_path / "asked").iterdir())
    assert names == sorted(p.name for p in (tmp_path / "coloured").iterdir())
    for n in names:
        assert (tmp_path / "asked" / n).read_bytes() == (tmp_path / "plain" / n).read_bytes(), n
        if n != "plates.json":  # a coloured shape nests and draws its sheets the same way
            assert (tmp_path / "coloured" / n).read_bytes() == (tmp_path / "plain" / n).read_bytes(), n
    plain_json = json.loads((tmp_path / "plain" / "plates.json").read_text())
    assert "colours" not in plain_json and all("colour" not in p for p in plain_json["plates_list"])
    coloured_json = json.loads((tmp_path / "coloured" / "plates.json").read_text())
    for p in coloured_json["plates_list"]:
        del p["colour"]
    for key in ("colours", "by_colour", "sheets_list"):
        del coloured_json[key]
    assert coloured_json == plain_json


def test_by_colour_needs_no_more_sheets_than_colours_ask() -> None:
    shape = painted_queen()
    together = make_slices(shape, sheet="600x400")
    apart = make_slices(shape, sheet="600x400", by_colour=True)
    assert len(together.sheets) == 1
    assert len(apart.sheets) == len({c.hex for c in apart.colours}) >= 3
    assert [len(s.parts) for s in apart.sheets] and sum(len(s.parts) for s in apart.sheets) == len(apart.plates)


def test_a_recipe_asks_for_sheets_by_colour(tmp_path) -> None:
    from voxfab.io import write
    from voxfab.recipe import build_recipe

    write(joined_character(), tmp_path / "hero.vox")
    (tmp_path / "hero.toml").write_text('name = "hero"\npitch = 2.0\n\n[source]\nfile = "hero.vox"\n\n'
                                        '[outputs.slices]\nby_colour = true\nthickness = 2.0\nsheet = "200x150"\n')
    built = build_recipe(load_recipe(tmp_path / "hero.toml"), tmp_path / "out")
    report = json.loads((built.folder / "slices" / "plates.json").read_text())
    assert report["by_colour"] and len(report["colours"]) >= 4
    colour_of = {p["number"]: p["colour"]["hex"] for p in report["plates_list"]}
    for sheet in report["sheets_list"]:
        assert {colour_of[n] for n in sheet["plates"]} == {sheet["colour"]}
        assert (built.folder / "slices" / sheet["file"]).is_file()
