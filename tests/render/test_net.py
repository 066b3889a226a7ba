import itertools
from collections import Counter

import numpy as np
import pytest
from _handnets import tree_net

from voxfab.drawing import LAYERS
from voxfab.errors import FormatError, InvalidShapeError
from voxfab.fabricate.netdraw._drawing import TAB_FILL
from voxfab.render import net_picture, png_bytes
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


def rgb(color: str) -> tuple[int, int, int]:
    return int(color[1:3], 16), int(color[3:5], 16), int(color[5:7], 16)


CUT, MOUNTAIN, VALLEY = (LAYERS[n].rgb for n in ("CUT", "MOUNTAIN", "VALLEY"))
TAB = rgb(TAB_FILL)


def counts(img) -> Counter:
    a = np.asarray(img).reshape(-1, 3)
    return Counter(map(tuple, a.tolist()))


def test_picture_shows_faces_tabs_cuts_and_folds():
    net = tree_net(CUBE)
    img = net_picture(net, CUBE, size=500, numbers=False, legend=False)
    assert img.size == (500, 500)
    c = counts(img)
    assert c[CUT] > 0 and c[TAB] > 0 and c[MOUNTAIN] > 0
    # Every fold of a cube is a mountain.
    assert c[VALLEY] == 0
    # One face per direction, six tints of equal area.
    tints = [n for colour, n in c.most_common() if colour not in {CUT, TAB, MOUNTAIN, (255, 255, 255)}][:6]
    assert len(tints) == 6 and max(tints) < 1.1 * min(tints)
    # Seven glued seams on a cube's net, seven tabs: each a separate grey island.
    from scipy import ndimage

    _, islands = ndimage.label((np.asarray(img) == TAB).all(axis=-1))
    assert islands == 7


def test_valley_folds_get_the_valley_style():
    g = l_tromino()
    net = net_with_valley(g)
    img = np.asarray(net_picture(net, g, size=600, legend=False))
    assert (img == np.array(VALLEY, dtype=np.uint8)).all(axis=-1).any()
    img2 = np.asarray(net_picture(net, g, size=600, legend=False, styles={"valley": "none"}))
    assert not (img2 == np.array(VALLEY, dtype=np.uint8)).all(axis=-1).any()


def test_numbers_and_legend_are_drawn_and_deterministic():
    net = tree_net(CUBE)
    plain = np.asarray(net_picture(net, CUBE, size=400, numbers=False, legend=False)).astype(int)
    full = net_picture(net, CUBE, size=400)
    assert np.abs(np.asarray(full).astype(int) - plain).sum() > 0
    assert png_bytes(full) == png_bytes(net_picture(net, CUBE, size=400))


def test_net_of_another_shape_is_refused():
    net = tree_net(CUBE)
    with pytest.raises(FormatError, match="net"):
        net_picture(net, np.ones((2, 1, 1), dtype=bool))
    with pytest.raises(InvalidShapeError, match="styles"):
        net_picture(net, CUBE, styles={"mountain": "wavy"})


def test_json_round_trip_draws_the_same(tmp_path):
    net = tree_net(np.ones((2, 1, 1), dtype=bool))
    again = Net.from_json(net.to_json())
    g = np.ones((2, 1, 1), dtype=bool)
    assert png_bytes(net_picture(net, g, size=300)) == png_bytes(net_picture(again, g, size=300))


def test_engine_net_is_drawn_at_the_size_asked():
    from voxfab.shape import examples
    from voxfab.unfold import unfold

    g = examples.ball(3)
    net = unfold(g, rng=1)
    img = net_picture(net, g, size=600, height=400, legend=False)
    assert img.size == (600, 400)
    a = np.asarray(img)
    # Face tints cover about the faces' share of the picture: every face is drawn.
    painted = ~(a == 255).all(axis=-1)
    assert painted.mean() > 0.15
