"""Hollowing, base plate, magnet pocket and engraved label, each checked on the result."""

import numpy as np
import pytest

from voxfab.errors import FabricationError, InvalidShapeError
from voxfab.fabricate.mesh import build_mesh, hollow_out, parse_magnet
from voxfab.shape import cavity_count, component_count, examples


def test_hollow_keeps_walls_and_opens_every_cavity():
    g = examples.box(8, 8, 8)
    h = hollow_out(g, 2)
    assert cavity_count(h) == 0 and component_count(h) == 1
    # 4³ hollow inside, drained by a 1-voxel column through the 2-voxel floor.
    assert h.sum() == 8**3 - 4**3 - 2
    r = build_mesh(g, pitch=2.0, hollow=2)
    assert r.report.volume == pytest.approx(h.sum() * 8.0)
    assert r.report.bodies == 1 and r.report.shells == 1


def test_solid_fills_cavities_unless_asked_not_to():
    g = np.ones((3, 3, 3), bool)
    g[1, 1, 1] = False
    assert build_mesh(g).report.volume == pytest.approx(27.0)
    kept = build_mesh(g, fill=False).report
    assert kept.volume == pytest.approx(26.0) and kept.shells == 2 and kept.parts == 1


def test_base_plate_joins_and_sizes():
    g = np.zeros((5, 5, 3), bool)
    g[0, 0, :] = True
    g[4, 4, :] = True  # two separate towers
    assert build_mesh(g, pitch=2.0).report.bodies == 2
    r = build_mesh(g, pitch=2.0, base=1.5)
    assert r.report.bodies == 1
    assert r.report.volume == pytest.approx(6 * 8.0 + 10 * 10 * 1.5)
    assert np.allclose(r.report.bounds, [[0, 0, 0], [10, 10, 7.5]])


def test_magnet_pocket_removes_its_cylinder():
    g = examples.box(10, 10, 4)
    r = build_mesh(g, pitch=2.0, magnet="6x3")
    full = 20 * 20 * 8.0
    pocket = full - r.report.volume
    # A 64-sided polygon inscribed in the 6 mm circle, 3 mm deep.
    assert pocket == pytest.approx(64 / 2 * 3.0**2 * np.sin(2 * np.pi / 64) * 3.0, rel=1e-6)
    assert r.report.shells == 1
    with pytest.raises(FabricationError, match="does not fit"):
        build_mesh(g, pitch=2.0, magnet="30x3")
    with pytest.raises(InvalidShapeError, match="magnet"):
        parse_magnet("6 by 3")
    assert parse_magnet("6x3") == (6.0, 3.0)


def test_engraved_label_cuts_the_bottom_only():
    pytest.importorskip("build123d")
    g = examples.box(15, 8, 4)
    plain = build_mesh(g, pitch=2.0).report.volume
    r = build_mesh(g, pitch=2.0, label="VOX 42", base=2.0)
    removed = plain + 30 * 16 * 2.0 - r.report.volume
    assert 5.0 < removed < 30 * 16 * 0.6  # letters, not the whole plate
    assert r.report.bodies == 1
    assert np.allclose(r.report.bounds, [[0, 0, 0], [30, 16, 10]])
    lower = r.mesh.vertices[:, 2]
    # Engraved faces lie at the engraving depth above the bottom.
    assert np.isclose(lower, 0.6).any()
    with pytest.raises(FabricationError, match="no room for the label"):
        build_mesh(examples.ball(3), pitch=1.0, label="X")


def test_glyph_outlines_are_simple_loops_with_the_font_area():
    bd = pytest.importorskip("build123d")
    from functools import reduce

    from shapely.geometry import LinearRing, Polygon

    from voxfab.fabricate.mesh._cad import text_outlines

    text = "gQ&@ 42"
    loops = text_outlines(text, height=10.0)
    assert all(LinearRing(lp).is_simple for lp in loops)
    # Even-odd area of the loops against the font's own faces (OCC), within the chord tolerance.
    even_odd = reduce(lambda a, b: a.symmetric_difference(b), [Polygon(lp) for lp in loops]).area
    occ = sum(f.area for f in bd.Text(text, font_size=10.0).faces())
    assert even_odd == pytest.approx(occ, rel=0.01)


def test_too_many_faces_is_refused_before_meshing(monkeypatch):
    import voxfab.fabricate.mesh._build as build

    noise = np.random.default_rng(0).random((20, 20, 20)) < 0.5
    monkeypatch.setattr(build, "MAX_FACES", 1000)
    monkeypatch.setattr(build, "voxel_mesh", lambda *a, **k: pytest.fail("meshed anyway"))
    with pytest.raises(FabricationError, match="exposed voxel faces, over the limit of 1000"):
        build.build_mesh(noise)


def test_scale_by_size_and_thin_wall_warning():
    g = examples.box(2, 3, 10)
    r = build_mesh(g, size=50.0)
    assert r.pitch == 5.0 and np.allclose(r.report.bounds[1], [10, 15, 50])
    assert not r.warnings
    plate = examples.box(5, 5, 1)
    assert any("thinner than the 0.8 mm" in w for w in build_mesh(plate, pitch=0.5).warnings)
    assert not build_mesh(examples.box(5, 5, 2), pitch=0.5).warnings  # no one-voxel wall
    with pytest.raises(InvalidShapeError, match="not both"):
        build_mesh(g, pitch=1.0, size=10.0)
