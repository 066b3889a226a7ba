import itertools

import numpy as np
import pytest
from _handnets import tree_net

from voxfab.errors import InvalidShapeError
from voxfab.render import net_layout, net_picture, net_seams, png_bytes
from voxfab.render._net import LINE_COLORS, TAB_COLOR
from voxfab.shape import FOLD_VALLEY, surface_graph
from voxfab.unfold import Net

CUBE = np.ones((1, 1, 1), dtype=bool)


def l_tromino():
    g = np.zeros((2, 1, 2), dtype=bool)
    g[0, 0, 0] = g[1, 0, 0] = g[0, 0, 1] = True
    return g


def net_with_valley(g):
    sg = surface_graph(g)
    for root in range(sg.face_count):
        for order in itertools.permutations(range(4)):
            try:
                net = tree_net(g, root=root, order=order)
            except AssertionError:
                continue
            for a, b in net.folds:
                k = int(np.flatnonzero(sg.neighbor[a] == b)[0])
                if sg.fold[a, k] == FOLD_VALLEY:
                    return net
    raise AssertionError("no valley in any BFS net")


def px(img, lay, xy):
    c, r = lay.to_pixel(np.asarray(xy, dtype=float))
    return tuple(int(v) for v in np.asarray(img)[int(r), int(c)])


def test_cube_net_seams_pair_every_cut_edge_once():
    net = tree_net(CUBE)
    seams = net_seams(net, CUBE)
    assert len(seams) == 12 - len(net.folds) == 7
    sg = surface_graph(CUBE)
    edges = set()
    for s in seams:
        assert sg.neighbor[s.face_a, s.edge_a] == s.face_b and sg.neighbor_edge[s.face_a, s.edge_a] == s.edge_b
        edges |= {(s.face_a, s.edge_a), (s.face_b, s.edge_b)}
    assert len(edges) == 14
    assert [s.number for s in seams] == list(range(1, 8))
    # In the cross every seam has a free cell on some side.
    assert all(s.tab >= 0 for s in seams)


def test_picture_shows_faces_tabs_cuts_and_folds():
    net = tree_net(CUBE)
    img = net_picture(net, CUBE, size=500, numbers=False, legend=False)
    assert img.size == (500, 500)
    lay = net_layout(net, width=500, height=500)
    cells = {tuple(c) for c in net.corners2d.min(axis=1).tolist()}
    x0, y0, x1, y1 = net.bounds()
    for x in range(x0, x1):
        for y in range(y0, y1):
            colour = px(img, lay, (x + 0.5, y + 0.5))
            assert (colour != (255, 255, 255)) == ((x, y) in cells)
    for s in net_seams(net, CUBE):
        face, edge = (s.face_a, s.edge_a) if s.tab == 0 else (s.face_b, s.edge_b)
        c = net.corners2d[face].astype(float)
        mid = (c[edge] + c[(edge + 1) % 4]) / 2
        out = mid - c.mean(axis=0)
        assert px(img, lay, mid + out * 0.3) == TAB_COLOR  # the tab, 0.15 side out
        for f, e in ((s.face_a, s.edge_a), (s.face_b, s.edge_b)):
            c = net.corners2d[f].astype(float)
            m = (c[e] + c[(e + 1) % 4]) / 2
            assert px(img, lay, m) == LINE_COLORS["cut"]
    # Every fold of a cube is a mountain: its line has the mountain colour somewhere along it.
    a = np.asarray(img)
    for fa, fb in net.folds:
        shared = {tuple(p) for p in net.corners2d[fa].tolist()} & {tuple(p) for p in net.corners2d[fb].tolist()}
        p, q = (np.array(v, dtype=float) for v in sorted(shared))
        pts = [lay.to_pixel(p + (q - p) * t) for t in np.linspace(0.02, 0.98, 60)]
        colours = {tuple(a[int(r), int(c)]) for c, r in pts}
        assert LINE_COLORS["mountain"] in colours
        assert LINE_COLORS["valley"] not in colours


def test_valley_folds_get_the_valley_style():
    g = l_tromino()
    net = net_with_valley(g)
    img = np.asarray(net_picture(net, g, size=600, legend=False))
    assert (img == np.array(LINE_COLORS["valley"], dtype=np.uint8)).all(axis=-1).any()
    img2 = np.asarray(net_picture(net, g, size=600, legend=False, styles={"valley": "none"}))
    assert not (img2 == np.array(LINE_COLORS["valley"], dtype=np.uint8)).all(axis=-1).any()


def test_numbers_and_legend_are_drawn_and_deterministic():
    net = tree_net(CUBE)
    plain = np.asarray(net_picture(net, CUBE, size=400, numbers=False, legend=False)).astype(int)
    full = net_picture(net, CUBE, size=400)
    assert np.abs(np.asarray(full).astype(int) - plain).sum() > 0
    assert png_bytes(full) == png_bytes(net_picture(net, CUBE, size=400))


def test_net_of_another_shape_is_refused():
    net = tree_net(CUBE)
    with pytest.raises(InvalidShapeError, match="net"):
        net_picture(net, np.ones((2, 1, 1), dtype=bool))
    with pytest.raises(InvalidShapeError, match="styles"):
        net_picture(net, CUBE, styles={"mountain": "wavy"})


def test_json_round_trip_draws_the_same(tmp_path):
    net = tree_net(np.ones((2, 1, 1), dtype=bool))
    again = Net.from_json(net.to_json())
    g = np.ones((2, 1, 1), dtype=bool)
    assert png_bytes(net_picture(net, g, size=300)) == png_bytes(net_picture(again, g, size=300))


def test_engine_net_is_drawn_when_the_engine_exists():
    unfold = pytest.importorskip("voxfab.unfold")
    if not hasattr(unfold, "unfold"):
        pytest.skip("voxfab.unfold.unfold not available")
    from voxfab.shape import examples

    g = examples.ball(3)
    net = unfold.unfold(g, rng=1)
    img = net_picture(net, g, size=600, legend=False)
    lay = net_layout(net, width=600, height=600)
    for c in net.corners2d.min(axis=1)[:50]:
        assert px(img, lay, c + 0.5) != (255, 255, 255)


def test_seams_and_tab_room_agree_with_the_net_engine():
    unfold = pytest.importorskip("voxfab.unfold")
    if not hasattr(unfold, "seam_pairs"):
        pytest.skip("voxfab.unfold.seam_pairs not available")
    from voxfab.shape import examples

    for g in (examples.ball(3), examples.tunnel_cube(5)):
        net = unfold.unfold(g, rng=2)
        mine = net_seams(net, g)
        pairs = unfold.seam_pairs(g, net)
        room = unfold.tab_room(g, net)
        assert [[[s.face_a, s.edge_a], [s.face_b, s.edge_b]] for s in mine] == pairs.tolist()
        assert [s.tab >= 0 for s in mine] == room.any(axis=1).tolist()
        assert all(s.tab < 0 or room[i, s.tab] for i, s in enumerate(mine))
