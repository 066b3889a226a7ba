"""Pictures in colour: the triptych's three panels, turntables, fold-ups, contact sheets and batch thumbnails.

Colours are measured from the written PNG and GIF files and compared with the
voxels' own colours, computed here by hand; an uncoloured shape's pictures are
the same bytes as its grid's.
"""

from __future__ import annotations

import functools
import io

import numpy as np
import pytest
from _voxart import character
from PIL import Image

from voxfab.render import contact_sheet, make_net, save_picture, slice_layout, triptych, triptych_layout
from voxfab.render._animate import save_turntable
from voxfab.render._fold import save_fold_animation
from voxfab.shape import VoxelShape, examples

RED, BLUE = (200, 40, 40, 255), (40, 60, 150, 255)


@functools.lru_cache(maxsize=1)
def painted_box() -> VoxelShape:
    """A 3 x 3 x 4 box: the top half red, one side of the bottom half blue, the rest white."""
    g = examples.box(3, 3, 4)
    x, _, z = np.indices(g.shape)
    return VoxelShape(g, 10.0).painted(RED, g & (z >= 2)).painted(BLUE, g & (z < 2) & (x == 0))


def _chroma(rgb) -> np.ndarray:
    rgb = np.asarray(rgb, dtype=np.float64)[..., :3]
    return rgb / np.maximum(rgb.max(axis=-1, keepdims=True), 1)


def _near(pixels: np.ndarray, colour, tol: float = 0.05) -> np.ndarray:
    """Which pixels are a shade of ``colour`` (same hue and saturation, any brightness above dark)."""
    return (np.abs(_chroma(pixels) - _chroma(colour)).max(axis=-1) < tol) & (pixels.max(axis=-1) > 40)


def _read_png(path) -> np.ndarray:
    with Image.open(path) as im:
        return np.asarray(im.convert("RGB")).astype(int)


def _gif_frames(path) -> tuple[list[np.ndarray], list[list[int]]]:
    frames, palettes = [], []
    with Image.open(path) as im:
        for k in range(im.n_frames):
            im.seek(k)
            palettes.append(im.getpalette())
            frames.append(np.asarray(im.convert("RGB")).astype(int))
    return frames, palettes


def _exposed_faces(shape: VoxelShape) -> dict[tuple, int]:
    """Exposed voxel faces of each colour, counted by hand."""
    g = np.pad(shape.grid, 1)
    rgba = np.pad(shape.colours.rgba, ((1, 1), (1, 1), (1, 1), (0, 0)))
    counts: dict[tuple, int] = {}
    for axis in range(3):
        for step in (1, -1):
            open_side = g & ~np.roll(g, -step, axis=axis)
            for c in rgba[open_side]:
                counts[tuple(int(v) for v in c)] = counts.get(tuple(int(v) for v in c), 0) + 1
    return counts


def test_triptych_panels_show_the_voxels_colours(tmp_path) -> None:
    shape = painted_box()
    side = 300
    save_picture(triptych(shape, name="box", panel=side, rng=0), tmp_path / "t.png")
    picture = _read_png(tmp_path / "t.png")
    net_box, slices_box, iso_box = triptych_layout(side).panels
    # slices: each cell's centre pixel is its voxel's colour (layer i is z = i, rows run down y, columns x)
    lay = slice_layout(4, (3, 3), width=side, height=side)
    for i, (x0, y0) in enumerate(lay.origins):
        for r in range(3):
            for c in range(3):
                px = picture[slices_box[1] + y0 + r * lay.cell + lay.cell // 2,
                             slices_box[0] + x0 + c * lay.cell + lay.cell // 2]
                assert tuple(px) == tuple(shape.colours.rgba[c, 2 - r, i, :3]), (i, r, c)
    # 3D: the iso view shows the red top and the blue side
    iso = picture[iso_box[1]:iso_box[3], iso_box[0]:iso_box[2]]
    assert _near(iso, RED).sum() > 1000 and _near(iso, BLUE).sum() > 200
    # net: the faces of each colour cover the net's area in proportion to their count
    net = picture[net_box[1]:net_box[3], net_box[0]:net_box[2]]
    faces = _exposed_faces(shape)
    red, blue = _near(net, RED).sum(), _near(net, BLUE).sum()
    white = ((net.min(axis=-1) > 110) & (np.ptp(net, axis=-1) < 8) & (net.max(axis=-1) < 250)).sum()
    total = sum(faces.values())
    assert red / (red + blue + white) == pytest.approx(faces[RED] / total, abs=0.08)
    assert blue / (red + blue + white) == pytest.approx(faces[BLUE] / total, abs=0.08)


def test_an_uncoloured_triptych_is_its_grids_triptych(tmp_path) -> None:
    grid = painted_box().grid
    plain = triptych(VoxelShape(grid, 10.0), name="box", panel=200, rng=0)
    assert plain.tobytes() == triptych(grid, name="box", panel=200, rng=0).tobytes()
    coloured = np.asarray(triptych(painted_box(), name="box", panel=200, rng=0)).astype(int)
    assert not _near(np.asarray(plain).astype(int), BLUE).any() and _near(coloured, BLUE).any()


def test_slices_of_the_character_colour_every_cell(tmp_path) -> None:
    from voxfab.render import slice_sheet

    shape = character().crop()
    save_picture(slice_sheet(shape, size=900), tmp_path / "s.png")
    picture = _read_png(tmp_path / "s.png")
    nx, ny, nz = shape.grid.shape
    lay = slice_layout(nz, (ny, nx), width=900)
    wrong = 0
    for z, (x0, y0) in enumerate(lay.origins):
        for x, y in np.argwhere(shape.grid[:, :, z]):
            px = picture[y0 + (ny - 1 - y) * lay.cell + lay.cell // 2, x0 + x * lay.cell + lay.cell // 2]
            wrong += tuple(px) != tuple(shape.colours.rgba[x, y, z, :3])
    assert wrong == 0


def test_turntable_keeps_the_colours_on_one_palette(tmp_path) -> None:
    shape = character()
    save_turntable(shape, tmp_path / "a.gif", frames=8, size=200)
    save_turntable(shape, tmp_path / "b.gif", frames=8, size=200)
    assert (tmp_path / "a.gif").read_bytes() == (tmp_path / "b.gif").read_bytes()
    frames, palettes = _gif_frames(tmp_path / "a.gif")
    pixels = np.concatenate([f.reshape(-1, 3) for f in frames])
    # one palette: no frame carries its own (Pillow gives None for a frame on the global one)
    assert len(frames) == 8 and all(p is None or p == palettes[0] for p in palettes[1:])
    assert len(np.unique(pixels, axis=0)) <= 256
    for colour in _exposed_faces(shape):
        if max(colour[:3]) >= 60:  # the belt is too dark for its hue to be measured after shading
            assert _near(pixels, colour, 0.06).any(), colour
    # frame 0 is the iso view: the shirt covers more of it than any other colour but the skin
    first = frames[0]
    assert _near(first, (200, 40, 40)).sum() > _near(first, (40, 60, 150)).sum() > 0
    # an uncoloured shape's turntable is its grid's, on the fixed palette of shades
    save_turntable(VoxelShape(shape.grid, 2.0), tmp_path / "plain.gif", frames=8, size=200)
    save_turntable(shape.grid, tmp_path / "grid.gif", frames=8, size=200)
    assert (tmp_path / "plain.gif").read_bytes() == (tmp_path / "grid.gif").read_bytes()


def test_fold_animation_folds_coloured_faces(tmp_path) -> None:
    shape = painted_box()
    net = make_net(shape, rng=0)
    save_fold_animation(net, tmp_path / "c.gif", steps=6, size=240, colours=shape.colours)
    save_fold_animation(net, tmp_path / "p.gif", steps=6, size=240)
    frames, palettes = _gif_frames(tmp_path / "c.gif")
    assert all(p is None or p == palettes[0] for p in palettes[1:])
    assert len(np.unique(np.concatenate([f.reshape(-1, 3) for f in frames]), axis=0)) <= 256
    flat, folded = frames[0], frames[-1]
    # flat, the outsides face the viewer or away; folded, the red top and the blue side show
    assert _near(folded, RED).sum() > 200 and _near(folded, BLUE).sum() > 20
    assert _near(flat, RED).any() or _near(flat, BLUE).any()
    plain, _ = _gif_frames(tmp_path / "p.gif")
    assert not _near(plain[-1], BLUE).any()


def test_contact_sheet_and_thumbnails_draw_a_coloured_shape_in_colour(tmp_path) -> None:
    from voxfab.batch._index import draw_thumbnails

    shape = painted_box()
    sheet = contact_sheet([("coloured", shape), ("plain", shape.grid)], tile=160, columns=2)
    save_picture(sheet, tmp_path / "sheet.png")
    picture = _read_png(tmp_path / "sheet.png")
    left, right = picture[:160, :160], picture[:160, 160:320]
    assert _near(left, RED).sum() > 300 and _near(left, BLUE).any()
    assert not _near(right, RED).any() and not _near(right, BLUE).any()
    assert draw_thumbnails(shape, {}, tmp_path / "thumbs", name="box", seed=0, size=160) == []
    render = _read_png(tmp_path / "thumbs" / "box.png")
    net = _read_png(tmp_path / "thumbs" / "box-net.png")
    assert _near(render, RED).sum() > 300 and _near(net, RED).sum() > 300 and _near(net, BLUE).sum() > 50
    buf = io.BytesIO()
    Image.fromarray(render.astype(np.uint8)).save(buf, format="PNG")
    assert buf.tell() > 0


def test_a_turntable_of_255_colours_keeps_its_frames_on_one_palette(tmp_path) -> None:
    from voxfab.shape import VoxelColours

    g = examples.box(15, 17, 1)[:, :, :1].repeat(3, axis=2)
    rng = np.random.default_rng(5)
    palette = rng.integers(0, 256, size=(256, 4))
    palette[:, 3] = 255
    index = np.where(g, (np.arange(g.size).reshape(g.shape) % 255) + 1, 0)
    shape = VoxelShape(g, 1.0, VoxelColours(index, palette))
    assert shape.colours.count > 200
    save_turntable(shape, tmp_path / "a.gif", frames=4, size=120)
    save_turntable(shape, tmp_path / "b.gif", frames=4, size=120)
    assert (tmp_path / "a.gif").read_bytes() == (tmp_path / "b.gif").read_bytes()
    frames, palettes = _gif_frames(tmp_path / "a.gif")
    assert all(p is None or p == palettes[0] for p in palettes[1:])
    pixels = np.concatenate([f.reshape(-1, 3) for f in frames])
    assert len(np.unique(pixels, axis=0)) <= 256
    # the many colours stay many hues: not one card colour in shades
    lit = pixels[(pixels.max(axis=1) > 60) & (pixels != 255).any(axis=1)]
    assert len(np.unique(np.rint(_chroma(lit) * 10), axis=0)) > 30


def test_cli_fold_takes_the_shape_for_its_colours(tmp_path, capsys) -> None:
    from voxfab.cli import main
    from voxfab.io import write
    from voxfab.repo import load_shape

    write(painted_box(), tmp_path / "box.vox")
    shape = load_shape(str(tmp_path / "box.vox"), None)[0]
    (tmp_path / "net.json").write_text(make_net(shape, rng=0).to_json())
    out = tmp_path / "fold.gif"
    assert main(["render", str(tmp_path / "box.vox"), "--fold", str(tmp_path / "net.json"), "-o", str(out),
                 "--steps", "4", "--size", "200"]) == 0
    frames, _ = _gif_frames(out)
    assert _near(frames[-1], RED).sum() > 200 and _near(frames[-1], BLUE).sum() > 20
    # another shape's colours do not fit the net's faces: one line, no picture
    write(VoxelShape(examples.box(2, 2, 2), 10.0).painted(RED), tmp_path / "small.vox")
    assert main(["render", str(tmp_path / "small.vox"), "--fold", str(tmp_path / "net.json"), "-o",
                 str(tmp_path / "other.gif")]) != 0
    err = capsys.readouterr().err
    assert "voxfab: error: colours: the net's faces" in err and "Traceback" not in err
    assert not (tmp_path / "other.gif").exists()
