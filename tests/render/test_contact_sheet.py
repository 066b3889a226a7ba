import numpy as np
import pytest

from voxfab.errors import InvalidShapeError, RepositoryError
from voxfab.render import contact_sheet, render, repository_contact_sheet, sheet_layout
from voxfab.repo import Repository
from voxfab.shape import examples


def test_contact_sheet_tiles_are_the_shapes_in_order():
    shapes = [("a", examples.ball(2)), ("b", examples.box(1, 2, 3)), ("c", examples.torus(4, 1.5))]
    img = np.asarray(contact_sheet(shapes, tile=80))
    lay = sheet_layout(3, tile=80)
    assert img.shape == (lay.height, lay.width, 3)
    for (_, g), (x0, y0) in zip(shapes, lay.origins):
        tile = np.asarray(render(g, view="iso", size=80))
        assert np.array_equal(img[y0 : y0 + 80, x0 : x0 + 80], tile)
        label = img[y0 + 80 : y0 + 80 + lay.label_height, x0 : x0 + 80]
        assert (label.sum(axis=-1) < 300).any()


def test_repository_contact_sheet_orders_by_volume(tmp_path):
    path = tmp_path / "repo.sqlite"
    named = [examples.random_shape(s, fill=f) for s, f in ((1, 0.3), (2, 0.15), (3, 0.22))]
    drafts = [examples.ball(2), examples.box(2, 2, 2)]
    grids = named + drafts
    with Repository(path) as repo:
        for g in named:
            repo.add(g)
        for g in drafts:
            repo.add(g, draft=True)
        entries = repo.list()
    assert sum(e.draft for e in entries) == 2
    img = np.asarray(repository_contact_sheet(path, tile=64))
    ordered = sorted(grids, key=lambda g: int(g.sum()))
    lay = sheet_layout(len(grids), tile=64)
    assert len(entries) == 5
    for g, (x0, y0) in zip(ordered, lay.origins):
        tile = np.asarray(render(g, view="iso", size=64))
        assert np.array_equal(img[y0 : y0 + 64, x0 : x0 + 64], tile)
    only_named = np.asarray(repository_contact_sheet(path, tile=64, drafts=False))
    lay3 = sheet_layout(3, tile=64)
    assert only_named.shape == (lay3.height, lay3.width, 3)
    for g, (x0, y0) in zip(sorted(named, key=lambda g: int(g.sum())), lay3.origins):
        tile = np.asarray(render(g, view="iso", size=64))
        assert np.array_equal(only_named[y0 : y0 + 64, x0 : x0 + 64], tile)


def test_empty_repository_and_empty_list(tmp_path):
    path = tmp_path / "empty.sqlite"
    Repository(path).close()
    with pytest.raises(RepositoryError, match="no shape"):
        repository_contact_sheet(path)
    with pytest.raises(InvalidShapeError):
        contact_sheet([])
