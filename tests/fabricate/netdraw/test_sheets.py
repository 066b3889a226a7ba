"""Pieces packed on sheets, checked from the written files only: JSON pieces, DXF sheets, the PDF."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from _net_sheets import pieces_of, queen, read_pieces

from voxfab.fabricate.netdraw import DrawingOptions
from voxfab.shape import examples


def _rings(path: Path) -> list[np.ndarray]:
    import ezdxf

    out = []
    for e in ezdxf.readfile(path).modelspace():
        if e.dxf.layer == "CUT" and e.dxftype() in ("POLYLINE", "LWPOLYLINE") and e.is_closed:
            pts = [tuple(v.dxf.location)[:2] for v in e.vertices] if e.dxftype() == "POLYLINE" else \
                [tuple(p)[:2] for p in e.get_points()]
            out.append(np.array(pts))
    return out


CASES = [
    ("ball r=6", lambda: examples.ball(6), 10.0, "A4"),
    ("ball r=6 on the mat", lambda: examples.ball(6), 12.0, "mat12"),
    ("queen", queen, 8.6, "mat12"),
]


@pytest.mark.parametrize(("name", "make", "face", "sheet"), CASES, ids=[c[0] for c in CASES])
def test_pieces_on_sheets_read_back_from_the_files(sheet_net, name, make, face, sheet) -> None:

    grid = make()
    folder, made, drawing = sheet_net(name, grid, face, sheet)
    pieces = read_pieces(folder, grid)
    faces = sum(p.face_count for p in pieces)
    # Each sheet: one closed outline per piece on it, none meeting another, all inside the margin.
    sheets = sorted(folder.glob("net.sheet-*.dxf"))
    assert len(sheets) == made.report["sheets"]
    w, h = drawing.sheet_size
    m = drawing.margin
    outer = 0
    for path in sheets:
        shells = pieces_of(_rings(path))
        outer += len(shells)
        for i, a in enumerate(shells):
            x0, y0, x1, y1 = a.bounds
            assert x0 >= m - 1e-6 and y0 >= m - 1e-6 and x1 <= w - m + 1e-6 and y1 <= h - m + 1e-6
            for b in shells[i + 1:]:
                assert a.intersection(b).area < 1e-6
    assert outer == len(pieces)
    # Seams marked for tape instead of a tab: a few at most (the goal is none).
    marked = [int(line.split()[0]) for line in made.warnings if "without room for a tab" in line]
    assert sum(marked) <= 0.01 * faces
    # The PDF: an assembly page, then the sheets.
    assert (folder / "net.pdf").read_bytes().count(b"/Type /Page ") == len(sheets) + 1


def test_quarter_turns_pack_two_pieces_on_one_sheet() -> None:
    import shapely

    from voxfab.fabricate.netdraw._sheets import pack_pieces

    # Two L-shaped strips of 6 x 2 cells on a sheet 9 cells wide: only turned do they share it.
    strip = np.array([[[x, y], [x + 1, y], [x + 1, y + 1], [x, y + 1]] for x in range(2) for y in range(6)])
    opts = DrawingOptions(pitch=20.0, sheet="210x170", margin=5.0)
    plan, placed = pack_pieces([strip, strip.copy()], opts)
    assert plan.count == 1
    cells = [set(map(tuple, c.min(axis=1).tolist())) for c in placed]
    assert not cells[0] & cells[1]
    # On the sheet, in mm: the pieces keep clear paper between them, inside the drawable area.
    pos = plan.face_positions()
    n = strip.shape[0]
    a = shapely.union_all([shapely.Polygon(f) for f in pos[:n]])
    b = shapely.union_all([shapely.Polygon(f) for f in pos[n:]])
    assert a.distance(b) >= 1.0 - 1e-9
    x0, y0, x1, y1 = plan.area
    assert pos[..., 0].min() >= x0 - 1e-9 and pos[..., 0].max() <= x1 + 1e-9
    assert pos[..., 1].min() >= y0 - 1e-9 and pos[..., 1].max() <= y1 + 1e-9


def test_tab_bands_cover_the_drawn_tabs_and_narrow_with_them() -> None:
    import shapely

    from voxfab.fabricate.netdraw._sheets import paper, piece_mask
    from voxfab.fabricate.netdraw._tabs import tab_heights, trapezoids

    opts = DrawingOptions(pitch=8.6, sheet="A4", label_height=2.0)
    face = np.array([[[0, 0], [1, 0], [1, 1], [0, 1]]])
    mask, start = piece_mask(face, np.array([[0, k] for k in range(4)]), opts, 8.6)
    p = paper(opts, 8.6)
    covered = shapely.union_all([shapely.box((start[0] + i) * p.step, (start[1] + j) * p.step,
                                             (start[0] + i + 1) * p.step, (start[1] + j + 1) * p.step)
                                 for i, j in zip(*np.nonzero(mask))])
    inset, height = tab_heights(8.6, opts.tab_width, opts.tab_angle)
    corners = face[0] * 8.6
    tabs = trapezoids(corners.astype(float), np.roll(corners, -1, axis=0).astype(float), np.full(4, height), inset,
                      opts.tab_angle)
    for tab in tabs:
        assert covered.buffer(1e-9).contains(shapely.Polygon(tab))
    # The face and four full bands would take (k + 2 depth)^2 less the four corners; the outer rows are shorter.
    k, depth = p.per_cell, p.tab_steps
    assert depth >= 2
    assert int(mask.sum()) < (k + 2 * depth) ** 2 - 4 * depth**2


def test_the_packer_transforms_on_sizes_of_small_primes_and_keeps_every_overlap_count() -> None:
    """A5's raster at 8.6 mm is 59 steps wide, a prime: the packer's correlations run on a padded size of
    small primes, and the overlap counts on the offsets inside the raster are those of a direct count."""
    from voxfab.fabricate.netdraw._sheets import _best_spots, _shape, _Sheet, _Spectra, paper

    options = DrawingOptions(sheet="A5", pitch=8.6)
    sheet_paper = paper(options, 8.6)
    assert 59 in sheet_paper.raster
    sheet = _Sheet(sheet_paper.raster)
    rng = np.random.default_rng(0)
    sheet.blocked[:] = rng.random(sheet.raster) < 0.02
    sheet.free = int(sheet.blocked.size - np.count_nonzero(sheet.blocked))
    corners = np.array([[[0, 0], [1, 0], [1, 1], [0, 1]], [[1, 0], [2, 0], [2, 1], [1, 1]]])
    piece = _Spectra(_shape(corners, np.zeros((0, 2), dtype=np.int64), sheet_paper.per_cell, 1), sheet.raster)
    for size in (piece.mask.shape, sheet.spectra()[0].shape):
        n = (size[0], 2 * (size[1] - 1))  # real transforms keep half the last axis
        for k in n:
            for p in (2, 3, 5, 7, 11):
                while k % p == 0:
                    k //= p
            assert k == 1, size
    (found,) = _best_spots(sheet, [piece], touch=False)
    mask = piece.shape.mask
    w, h = mask.shape
    free = [(ox, oy) for oy in range(sheet.raster[1] - h + 1) for ox in range(sheet.raster[0] - w + 1)
            if not (sheet.blocked[ox:ox + w, oy:oy + h] & mask).any()]
    ox, oy = min(free, key=lambda o: (o[1] + h, o[0] + w))
    assert found == (oy + h, ox + w, ox, oy)


def test_a_packing_after_an_edit_transforms_only_the_pieces_it_changed() -> None:
    """Two packings that share pieces share their turns (the packer's transforms of each piece); a piece
    that changed is transformed anew, and the packing is that of a packer with nothing kept."""
    import voxfab.fabricate.netdraw._sheets as sheets

    options = DrawingOptions(sheet="A5", pitch=8.6)
    square = np.array([[[0, 0], [1, 0], [1, 1], [0, 1]]])
    bar = np.concatenate([square + (x, 0) for x in range(3)])
    ell = np.concatenate([bar, square + (0, 1)])
    made: list[int] = []
    real = sheets._Spectra

    def counted(*args):  # noqa: ANN002 - the packer's own arguments
        made.append(1)
        return real(*args)

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(sheets, "_Spectra", counted)
        sheets._TURNS.clear()
        first = sheets._pack_pieces([square, bar], options, None)
        assert len(made) == 8
        second = sheets._pack_pieces([square, ell], options, None)
        assert len(made) == 12  # only the changed piece's four turns
        sheets._TURNS.clear()
        fresh = sheets._pack_pieces([square, ell], options, None)
    for a, b in zip(second[1], fresh[1]):
        assert np.array_equal(a, b)
    assert np.array_equal(second[0].shift, fresh[0].shift) and np.array_equal(second[0].face_sheet, fresh[0].face_sheet)
    assert len(first[1]) == 2


def test_the_packer_pads_to_the_least_fast_size_without_loading_scipy_fft() -> None:
    """Each side padded to the least 2^i 3^j 5^k at least it, as scipy.fft.next_fast_len(n, real=True)
    answers; and packing the strips (a process of its own) loads no scipy.fft (a tenth of a second of a
    net's whole run)."""
    import subprocess
    import sys

    from scipy.fft import next_fast_len

    from voxfab.fabricate.netdraw._sheets import _fast

    sizes = list(range(1, 3000)) + [7919, 15625, 15626, 59049, 100000]
    assert [_fast((n, n + 1)) for n in sizes] == [(next_fast_len(n, real=True), next_fast_len(n + 1, real=True))
                                                    for n in sizes]
    code = ("import sys\nimport numpy as np\nfrom voxfab.fabricate.netdraw import DrawingOptions\n"
            "from voxfab.fabricate.netdraw._sheets import pack_pieces\n"
            "strip = np.array([[[x, y], [x + 1, y], [x + 1, y + 1], [x, y + 1]] for x in range(2) for y in range(6)])\n"
            "plan, _ = pack_pieces([strip, strip.copy()], DrawingOptions(pitch=20.0, sheet='210x170', margin=5.0))\n"
            "print(plan.count, 'scipy.fft' in sys.modules)\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    assert r.stdout.split() == ["1", "False"]
